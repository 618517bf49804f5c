#include "simulation.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "stability.h"

namespace neurocloth {

namespace {

// Bad input is refused before anything changes, with the field it is in.
[[noreturn]] void refuse(const std::string& field, std::size_t index, const char* rule,
                         double value) {
  std::ostringstream os;
  os << field << "[" << index << "] must be " << rule << ", got " << value;
  throw std::invalid_argument(os.str());
}

void check_state(const ClothState& s, const char* what) {
  if (s.all_finite()) return;
  for (std::size_t i = 0; i < s.size(); ++i)
    if (!s.position(i).allFinite() || !s.velocity(i).allFinite())
      throw std::invalid_argument(std::string(what) + ": node " + std::to_string(i) +
                                  " has a non-finite position or velocity");
}

// The weights a step divides by or multiplies with: finite, a positive inverse
// mass, no negative stiffness or damping (either would pump energy in).
void check_weights(const ClothNetwork& net) {
  const SpringLayer& sp = net.springs;
  for (std::size_t i = 0; i < sp.size(); ++i) {
    if (!(sp.stiffness[i] >= 0 && std::isfinite(sp.stiffness[i])))
      refuse("springs.stiffness", i, "finite and >= 0", sp.stiffness[i]);
    if (!(sp.damping[i] >= 0 && std::isfinite(sp.damping[i])))
      refuse("springs.damping", i, "finite and >= 0", sp.damping[i]);
  }
  const MassLayer& m = net.masses;
  for (std::size_t i = 0; i < m.size(); ++i)
    if (!(m.inverse_mass[i] > 0 && std::isfinite(m.inverse_mass[i])))
      refuse("masses.inverse_mass", i, "finite and > 0 (a node needs a mass)", m.inverse_mass[i]);
  if (!net.gravity.allFinite()) refuse("gravity", 0, "finite", net.gravity.norm());
}

const SolverSettings& validated(const SolverSettings& s) {
  validate(s);
  return s;
}

}  // namespace

const char* to_string(RunStatus s) {
  return s == RunStatus::ok ? "ok" : "diverged";
}

Simulation::Simulation(ClothNetwork network, ClothState initial, SolverSettings settings,
                       std::vector<std::unique_ptr<ConstraintModule>> constraints)
    : net_(std::move(network)),
      settings_(validated(settings)),  // before the integrator is made from them
      integrator_(make_integrator(settings.integrator, net_)),
      constraints_(std::move(constraints)),
      start_(constraints_.empty() || !integrator_->steps_in_place() ? 0 : initial.size()),
      a_(initial),
      b_(initial),
      checkpoint_(initial),
      force_a_(net_.node_count()),
      force_b_(net_.node_count()),
      monitor_(net_, initial, settings.divergence) {
  if (initial.size() != net_.node_count())
    throw std::invalid_argument("state size differs from the network's");
  check_state(initial, "initial state");
  check_weights(net_);
  for (std::size_t i = 0; i < net_.node_count(); ++i)
    if (net_.masses.free[i] != 0.0)
      force_scale_ = std::max(force_scale_, std::abs(net_.mass(i)) * net_.gravity.norm());
  if (force_scale_ == 0.0) force_scale_ = 1e-9;
}

Simulation::Simulation(Simulation&& o) noexcept
    : net_(std::move(o.net_)),
      settings_(o.settings_),
      integrator_(std::move(o.integrator_)),
      constraints_(std::move(o.constraints_)),
      start_(std::move(o.start_)),
      a_(std::move(o.a_)),
      b_(std::move(o.b_)),
      checkpoint_(std::move(o.checkpoint_)),
      front_(o.front_ == &o.a_ ? &a_ : &b_),
      back_(o.back_ == &o.a_ ? &a_ : &b_),
      force_a_(std::move(o.force_a_)),
      force_b_(std::move(o.force_b_)),
      force_front_(o.force_front_ == &o.force_a_ ? &force_a_ : &force_b_),
      force_back_(o.force_back_ == &o.force_a_ ? &force_a_ : &force_b_),
      front_forces_valid_(o.front_forces_valid_),
      degenerate_(o.degenerate_),
      monitor_(std::move(o.monitor_)),
      ramp_(std::move(o.ramp_)),
      status_(o.status_),
      reason_(std::move(o.reason_)),
      time_(o.time_),
      checkpoint_time_(o.checkpoint_time_),
      steps_(o.steps_),
      checkpoint_steps_(o.checkpoint_steps_),
      rejected_(o.rejected_),
      force_evaluations_(o.force_evaluations_),
      cg_iterations_(o.cg_iterations_),
      steps_since_check_(o.steps_since_check_),
      cap_(o.cap_),
      former_force_(o.former_force_),
      force_scale_(o.force_scale_),
      bound_k_(std::move(o.bound_k_)),
      bound_d_(std::move(o.bound_d_)),
      budget_left_(o.budget_left_),
      budget_exhausted_(o.budget_exhausted_),
      observer_(std::move(o.observer_)),
      interrupt_(std::move(o.interrupt_)),
      interrupted_(o.interrupted_) {}

ClothNetwork& Simulation::mutable_network() {
  front_forces_valid_ = false;
  cap_ = -1;
  former_force_ = -1;
  return net_;
}

// The stability bound does not depend on external forces: only the cached
// forces are dropped.
void Simulation::set_external_force(std::size_t node, const Vec3& f) {
  if (node >= net_.node_count()) throw std::out_of_range("set_external_force: no such node");
  if (!f.allFinite()) throw std::invalid_argument("set_external_force: force must be finite");
  front_forces_valid_ = false;
  former_force_ = -1;
  net_.masses.external_force.x[node] = f.x();
  net_.masses.external_force.y[node] = f.y();
  net_.masses.external_force.z[node] = f.z();
}

void Simulation::set_state(const ClothState& s) {
  if (s.size() != net_.node_count())
    throw std::invalid_argument("state size differs from the network's");
  check_state(s, "set_state");
  *front_ = s;
  checkpoint_ = s;
  checkpoint_time_ = time_;
  checkpoint_steps_ = steps_;
  front_forces_valid_ = false;
  former_force_ = -1;
}

void Simulation::set_solver_settings(const SolverSettings& settings) {
  validate(settings);  // before anything changes
  settings_ = settings;
  integrator_ = make_integrator(settings_.integrator, net_);
  start_.resize(constraints_.empty() || !integrator_->steps_in_place() ? 0 : net_.node_count());
  mutable_network();  // drops cached forces and the step cap
}

void Simulation::set_pinned(std::size_t node, bool pinned) {
  if (node >= net_.node_count()) throw std::out_of_range("no such node");
  mutable_network().set_pinned(node, pinned);
  if (!pinned) return;
  front_->set_velocity(node, Vec3::Zero());
  checkpoint_.set_velocity(node, Vec3::Zero());
}

void Simulation::rebase_divergence_check() {
  monitor_ = DivergenceMonitor(net_, *front_, settings_.divergence);
}

void Simulation::ramp_to_material(const Material& material, int steps) {
  ClothNetwork target = net_;
  target.apply_material(material);
  check_weights(target);  // a bad material is refused; the ramp in progress goes on
  ramp_.start(net_, target, steps);
}

// Applies the ramp's next weights (between two steps); drops what they invalidate.
bool Simulation::advance_ramp() {
  if (!ramp_.advance(net_)) return false;
  front_forces_valid_ = false;
  cap_ = -1;
  former_force_ = -1;
  return true;
}

double Simulation::step_cap() {
  if (cap_ < 0) {
    const double bound = integrator_step_bound(net_, *integrator_, bound_k_, bound_d_);
    cap_ = std::min(settings_.dt, settings_.adaptive_settings.safety * bound);
  }
  return cap_;
}

long Simulation::substeps() {
  if (settings_.adaptive || !settings_.substep_above_cap) return 1;
  const double n = std::ceil(settings_.dt / step_cap() * (1.0 - 1e-12));
  return n >= static_cast<double>(std::numeric_limits<long>::max())
             ? std::numeric_limits<long>::max()
             : std::max(1L, static_cast<long>(n));
}

RunStatus Simulation::advance(double seconds) {
  budget_exhausted_ = false;
  interrupted_ = false;
  if (status_ != RunStatus::ok || !(seconds > 0.0)) return status_;
  const double t_end = time_ + seconds;
  const double dt = settings_.dt;
  // step_budget per dt asked for, rounded up, plus one for a round-off remainder.
  const double allowance =
      static_cast<double>(settings_.step_budget) * (std::ceil(seconds / dt) + 1);
  budget_left_ = allowance < 1e18 ? static_cast<long>(allowance) : 1000000000000000000L;
  while (status_ == RunStatus::ok && time_ < t_end) {
    if (budget_left_ <= 0) {
      budget_exhausted_ = true;
      break;
    }
    const double remaining = t_end - time_;
    const bool last = remaining <= dt * (1.0 + 1e-9);
    // A remainder within round-off of dt is dt: then advance(k dt) takes the same
    // steps, bit for bit, however it is split into calls.
    const bool whole = std::abs(remaining - dt) <= 1e-9 * dt;
    const bool done = settings_.adaptive ? adaptive_frame(last ? t_end : time_ + dt)
                                         : fixed_frame(last && !whole ? remaining : dt);
    if (!done && status_ == RunStatus::ok) budget_exhausted_ = true;
    if (last && done && status_ == RunStatus::ok) time_ = t_end;  // no round-off drift at the end
    if (interrupt_ && !last && status_ == RunStatus::ok && interrupt_(*this)) {
      interrupted_ = true;
      break;
    }
  }
  // Between energy checks, at least never hand out a NaN: a cheap test every call.
  if (status_ == RunStatus::ok && steps_since_check_ > 0 && !front_->all_finite()) run_check();
  return status_;
}

void Simulation::begin_step() {
  bool changed = false;
  for (const auto& m : net_.force_modules)
    changed |= m->begin_step(time_);
  if (changed) {  // a gust moved: the forces cached at the current state are stale
    front_forces_valid_ = false;
    former_force_ = -1;
  }
}

void Simulation::constrain(const StepStart& before, ClothState& after, double h) {
  const StepSpan span{time_, h};
  for (const auto& c : constraints_) {
    ScopedModuleTimer timer(c->clock);
    c->apply(net_, span, before, after);
  }
}

std::size_t Simulation::module_overhead_bytes() const {
  return net_.force_modules.capacity() * sizeof(net_.force_modules[0]) +
         constraints_.capacity() * sizeof(constraints_[0]) + start_.allocated_bytes();
}

std::vector<ModuleReport> Simulation::module_reports() const {
  std::vector<ModuleReport> out;
  auto add = [&](const SceneModule& m) {
    out.push_back({m.type(), m.declaration, m.clock.seconds, m.clock.calls, m.state_bytes()});
  };
  for (const auto& m : net_.force_modules)
    add(*m);
  for (const auto& c : constraints_)
    add(*c);
  return out;
}

void Simulation::ensure_front_forces() {
  if (front_forces_valid_) return;
  net_.net_forces(*front_, *force_front_);
  front_forces_valid_ = true;
}

void Simulation::accept(double h, bool result_in_back) {
  if (result_in_back) std::swap(front_, back_);
  time_ += h;
  ++steps_;
  ++steps_since_check_;
}

void Simulation::after_accept(bool force_check) {
  if (force_check || steps_since_check_ >= settings_.divergence.check_interval) run_check();
}

bool Simulation::fixed_frame(double frame) {
  if (!settings_.substep_above_cap) {  // the plain step: exactly the step asked for
    --budget_left_;
    fixed_step(frame);
    return true;
  }
  // Guarded: equal substeps under the cap, recounted after each one because a
  // ramp may lower the cap mid-frame. Time lands on start + frame exactly, as
  // an unguarded step of the same frame would.
  const double end = time_ + frame;
  double left = frame;
  while (status_ == RunStatus::ok) {
    if (budget_left_ <= 0) return false;
    --budget_left_;
    advance_ramp();
    const double n = std::ceil(left / step_cap() * (1.0 - 1e-12));
    const double h = n > 1 ? left / n : left;
    fixed_step_now(h);
    if (n <= 1) break;
    left -= h;
  }
  if (status_ == RunStatus::ok) time_ = end;
  return true;
}

void Simulation::fixed_step(double h) {
  advance_ramp();
  fixed_step_now(h);
}

void Simulation::fixed_step_now(double h) {
  begin_step();
  ensure_front_forces();
  // A fixed step is never rejected, so an integrator that can may write over
  // the current state (the checkpoint still guards against divergence). With
  // constraints, the start positions are kept aside first: copying three arrays
  // costs less than writing the whole step to the other buffer.
  const bool in_place = integrator_->steps_in_place();
  ClothState* out = in_place ? front_ : back_;
  if (in_place && !constraints_.empty()) {
    std::copy(front_->x.begin(), front_->x.end(), start_.x.begin());
    std::copy(front_->y.begin(), front_->y.end(), start_.y.begin());
    std::copy(front_->z.begin(), front_->z.end(), start_.z.begin());
  }
  const StepStart before = in_place ? StepStart(start_) : StepStart(*front_);
  const StepReport r = integrator_->step(net_, *front_, *force_front_, h, *out);
  constrain(before, *out, h);
  force_evaluations_ += r.force_evaluations;
  cg_iterations_ += r.cg_iterations;
  front_forces_valid_ = false;
  accept(h, out == back_);
  after_accept(false);
}

// The paper's Table 1, with a rollback of rejected trials (the back buffer is
// simply not swapped in), a cap on t_c from the stability bound, a floor on t_c,
// and a tolerance on "the force grows".
bool Simulation::adaptive_frame(double frame_end) {
  const AdaptiveSettings& A = settings_.adaptive_settings;
  double cap = step_cap();
  double floor = cap * A.min_step_fraction;
  double tc = cap;  // Table 1: t_c := t_delta, never above the cap
  bool accepted = true;
  while (status_ == RunStatus::ok && time_ < frame_end) {
    if (budget_left_ <= 0) return false;
    --budget_left_;
    if (accepted && advance_ramp()) {  // weights moved: a new cap, new forces
      cap = step_cap();
      floor = cap * A.min_step_fraction;
      tc = std::min(tc, cap);
    }
    begin_step();
    ensure_front_forces();
    if (former_force_ < 0) former_force_ = net_.max_net_force(*force_front_);
    const double h = std::min(tc, frame_end - time_);
    const StepReport r = integrator_->step(net_, *front_, *force_front_, h, *back_);
    constrain(*front_, *back_, h);
    net_.net_forces(*back_, *force_back_);
    force_evaluations_ += r.force_evaluations + 1;
    cg_iterations_ += r.cg_iterations;
    const double m = net_.max_net_force(*force_back_);
    const double allowed =
        former_force_ + A.growth_tolerance * std::max(former_force_, force_scale_);
    const bool grows = !(m <= allowed);  // NaN grows
    const bool forced = grows && tc <= floor;
    StepEvent ev{time_, tc, h, !grows || forced, forced, m, former_force_};
    accepted = !grows || forced;
    if (grows && !forced) {
      ++rejected_;
      tc = std::max(0.5 * tc, floor);  // Table 1: t_c := t_c * 0.5 (rollback: no swap)
      if (observer_) observer_(ev);
      continue;
    }
    accept(h);
    std::swap(force_front_, force_back_);
    former_force_ = m;
    tc = std::min(2.0 * tc, cap);  // Table 1: t := t + t_c; t_c := t_c * 2
    if (frame_end - time_ <= 1e-12 * settings_.dt) time_ = frame_end;
    if (observer_) observer_(ev);
    after_accept(!std::isfinite(m));
  }
  return true;
}

RunStatus Simulation::check_now() {
  if (status_ == RunStatus::ok && steps_since_check_ > 0) run_check();
  return status_;
}

void Simulation::run_check() {
  steps_since_check_ = 0;
  degenerate_ = net_.degenerate_springs(*front_);
  std::string why = monitor_.check(net_, *front_);
  if (why.empty()) {
    if (!monitor_.striking()) {
      checkpoint_ = *front_;
      checkpoint_time_ = time_;
      checkpoint_steps_ = steps_;
    }
    return;
  }
  // Diverged: go back to the last state that passed a check.
  *front_ = checkpoint_;
  time_ = checkpoint_time_;
  steps_ = checkpoint_steps_;
  front_forces_valid_ = false;
  former_force_ = -1;
  status_ = RunStatus::diverged;
  reason_ = std::move(why);
}

}  // namespace neurocloth
