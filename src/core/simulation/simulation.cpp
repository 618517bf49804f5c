#include "core/simulation/simulation.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "core/integrators/stability.h"
#include "core/integrators/step_controller.h"

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
void check_weights(const std::vector<double>& stiffness, const std::vector<double>& damping,
                   const std::vector<double>& inverse_mass) {
  for (std::size_t i = 0; i < stiffness.size(); ++i)
    if (!(stiffness[i] >= 0 && std::isfinite(stiffness[i])))
      refuse("springs.stiffness", i, "finite and >= 0", stiffness[i]);
  for (std::size_t i = 0; i < damping.size(); ++i)
    if (!(damping[i] >= 0 && std::isfinite(damping[i])))
      refuse("springs.damping", i, "finite and >= 0", damping[i]);
  for (std::size_t i = 0; i < inverse_mass.size(); ++i)
    if (!(inverse_mass[i] > 0 && std::isfinite(inverse_mass[i])))
      refuse("masses.inverse_mass", i, "finite and > 0 (a node needs a mass)", inverse_mass[i]);
}

void check_weights(const ClothNetwork& net) {
  check_weights(net.springs.stiffness, net.springs.damping, net.masses.inverse_mass);
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
                       std::vector<std::shared_ptr<const ConstraintModule>> constraints)
    : net_(std::move(network)),
      constraints_(std::move(constraints)),
      settings_(validated(settings)),  // before the integrator is made from them
      states_{initial, initial},
      checkpoint_(initial),
      monitor_(net_, initial, settings.divergence),
      integrator_(make_integrator(settings.integrator, net_,
                                  settings.adaptive_settings.min_step_fraction, settings.iterations,
                                  settings.linear_tolerance)),
      threads_(settings.threads),
      start_(constraints_.empty() || !integrator_->steps_in_place() ? 0 : initial.size()),
      forces_{NodeVectors(net_.node_count()), NodeVectors(net_.node_count())} {
  if (initial.size() != net_.node_count())
    throw std::invalid_argument("state size differs from the network's");
  check_state(initial, "initial state");
  check_weights(net_);
  for (std::size_t i = 0; i < net_.node_count(); ++i)
    if (net_.masses.free[i] != 0.0)
      force_scale_ = std::max(force_scale_, std::abs(net_.mass(i)) * net_.gravity.norm());
  if (force_scale_ == 0.0) force_scale_ = 1e-9;
  inputs_.clocks.resize(net_.force_modules.size());
  inputs_.precision = settings_.precision;
  constraint_clocks_.resize(constraints_.size());
  for (const auto& c : constraints_)
    module_states_.push_back(c->make_state());
}

void Simulation::invalidate(Stale what) {
  front_forces_valid_ = false;
  former_force_ = -1;
  if (what == Stale::weights) cap_ = -1;
}

ClothNetwork& Simulation::mutable_network() {
  invalidate(Stale::weights);
  return net_;
}

bool Simulation::set_module_parameter(std::size_t index, const ParameterId& id, double value) {
  if (index >= net_.force_modules.size()) throw std::out_of_range("no such force module");
  std::shared_ptr<ForceModule> changed = net_.force_modules[index]->clone();
  if (!changed->set_parameter(id, value)) return false;
  net_.force_modules[index] = std::move(changed);
  invalidate(Stale::forces);
  return true;
}

// The stability bound does not depend on external forces: only the cached
// forces are dropped.
void Simulation::set_external_force(std::size_t node, const Vec3& f) {
  if (node >= net_.node_count()) throw std::out_of_range("set_external_force: no such node");
  if (!f.allFinite()) throw std::invalid_argument("set_external_force: force must be finite");
  NodeVectors& ext = inputs_.external_force;
  if (ext.size() == 0) {
    if (f == Vec3::Zero()) return;  // nothing to add: no memory, no work
    ext.resize(net_.node_count());
  }
  ext.x[node] = f.x();
  ext.y[node] = f.y();
  ext.z[node] = f.z();
  invalidate(Stale::forces);
}

void Simulation::set_state(const ClothState& s) {
  if (s.size() != net_.node_count())
    throw std::invalid_argument("state size differs from the network's");
  check_state(s, "set_state");
  front() = s;
  checkpoint_ = s;
  checkpoint_time_ = time_;
  checkpoint_steps_ = steps_;
  invalidate(Stale::forces);
}

void Simulation::set_solver_settings(const SolverSettings& settings) {
  validate(settings);  // before anything changes
  // Made before anything changes too: an integrator may refuse this cloth.
  std::unique_ptr<Integrator> integrator =
      make_integrator(settings.integrator, net_, settings.adaptive_settings.min_step_fraction,
                      settings.iterations, settings.linear_tolerance);
  settings_ = settings;
  inputs_.precision = settings_.precision;
  if (threads_.size() != settings_.threads) threads_ = OwnedStepThreads(settings_.threads);
  integrator_ = std::move(integrator);
  start_.resize(constraints_.empty() || !integrator_->steps_in_place() ? 0 : net_.node_count());
  invalidate(Stale::weights);
}

void Simulation::set_pinned(std::size_t node, bool pinned) {
  if (node >= net_.node_count()) throw std::out_of_range("no such node");
  mutable_network().set_pinned(node, pinned);
  if (!pinned) return;
  front().set_velocity(node, Vec3::Zero());
  checkpoint_.set_velocity(node, Vec3::Zero());
}

void Simulation::rebase_divergence_check() {
  monitor_ = DivergenceMonitor(net_, state(), settings_.divergence);
}

void Simulation::ramp_to_material(const Material& material, int steps) {
  const MaterialWeights target = net_.material_weights(material);
  // A bad material is refused; the ramp in progress goes on.
  check_weights(target.stiffness, target.damping, target.inverse_mass);
  ramp_.start(net_, target, steps);
}

// Applies the ramp's next weights (between two steps); drops what they invalidate.
bool Simulation::advance_ramp() {
  if (!ramp_.advance(net_)) return false;
  invalidate(Stale::weights);
  return true;
}

double Simulation::step_cap() {
  if (cap_ < 0) {
    // Recomputed after every weight change, a ramp's steps too: the bound is
    // not monotone along a ramp (damping moves linearly, mass geometrically).
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
  // The team serves this call only (see threads_).
  struct LendTeam {
    ForceInputs& inputs;
    ~LendTeam() { inputs.threads = nullptr; }
  } lend{inputs_};
  inputs_.threads = threads_.get();
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
  if (status_ == RunStatus::ok && steps_since_check_ > 0 && !state().all_finite()) run_check();
  return status_;
}

// The step's inputs are frozen at its start; forces cached at the current state
// for an earlier time are stale when a module reads the time (a gust).
void Simulation::begin_step() {
  if (inputs_.time == time_) return;
  inputs_.time = time_;
  for (const auto& m : net_.force_modules)
    if (m->time_dependent()) {
      invalidate(Stale::forces);
      return;
    }
}

void Simulation::constrain(const StepStart& before, ClothState& after, double h) {
  const StepSpan span{time_, h};
  for (std::size_t k = 0; k < constraints_.size(); ++k) {
    ScopedModuleTimer timer(constraint_clocks_[k]);
    constraints_[k]->apply(net_, span, before, after, module_states_[k].get());
  }
}

std::size_t Simulation::module_overhead_bytes() const {
  return net_.force_modules.capacity() * sizeof(net_.force_modules[0]) +
         constraints_.capacity() * sizeof(constraints_[0]) +
         module_states_.capacity() * sizeof(module_states_[0]) +
         inputs_.clocks.capacity() * sizeof(ModuleClock) +
         constraint_clocks_.capacity() * sizeof(ModuleClock) + start_.allocated_bytes();
}

std::vector<ModuleReport> Simulation::module_reports() const {
  std::vector<ModuleReport> out;
  for (std::size_t k = 0; k < net_.force_modules.size(); ++k) {
    const ForceModule& m = *net_.force_modules[k];
    const ModuleClock& c = inputs_.clocks[k];
    out.push_back({m.type(), m.declaration, c.seconds, c.calls, m.state_bytes()});
  }
  for (std::size_t k = 0; k < constraints_.size(); ++k) {
    const ConstraintModule& m = *constraints_[k];
    const ModuleClock& c = constraint_clocks_[k];
    const std::size_t state = module_states_[k] ? module_states_[k]->bytes() : 0;
    out.push_back({m.type(), m.declaration, c.seconds, c.calls, m.state_bytes() + state});
  }
  return out;
}

void Simulation::ensure_front_forces() {
  if (front_forces_valid_) return;
  net_.net_forces(state(), inputs_, forces_[force_front_]);
  front_forces_valid_ = true;
}

void Simulation::accept(double h, bool result_in_back) {
  if (result_in_back) front_ = 1 - front_;
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
    const double h =
        StepController(step_cap(), settings_.adaptive_settings.min_step_fraction).equal_piece(left);
    fixed_step_now(h);
    if (h == left) break;
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
  if (integrator_->reads_start_force()) ensure_front_forces();
  // A fixed step is never rejected, so an integrator that can may write over
  // the current state (the checkpoint still guards against divergence). With
  // constraints, the start positions are kept aside first: copying three arrays
  // costs less than writing the whole step to the other buffer.
  const bool in_place = integrator_->steps_in_place();
  ClothState& in = front();
  ClothState& out = in_place ? in : back();
  if (in_place && !constraints_.empty()) {
    std::copy(in.x.begin(), in.x.end(), start_.x.begin());
    std::copy(in.y.begin(), in.y.end(), start_.y.begin());
    std::copy(in.z.begin(), in.z.end(), start_.z.begin());
  }
  const StepStart before = in_place ? StepStart(start_) : StepStart(in);
  const StepReport r = integrator_->step(net_, inputs_, in, forces_[force_front_], h, out);
  constrain(before, out, h);
  force_evaluations_ += r.force_evaluations;
  cg_iterations_ += r.cg_iterations;
  invalidate(Stale::forces);
  accept(h, !in_place);
  after_accept(false);
}

// The paper's Table 1, with a rollback of rejected trials (the back buffer is
// simply not swapped in), a cap on t_c from the stability bound, a floor on t_c,
// and a tolerance on "the force grows".
bool Simulation::adaptive_frame(double frame_end) {
  const AdaptiveSettings& A = settings_.adaptive_settings;
  StepController tc(step_cap(), A.min_step_fraction);  // Table 1: t_c := t_delta, under the cap
  bool accepted = true;
  while (status_ == RunStatus::ok && time_ < frame_end) {
    if (budget_left_ <= 0) return false;
    --budget_left_;
    if (accepted && advance_ramp()) tc.set_cap(step_cap());  // weights moved: a new cap
    begin_step();
    ensure_front_forces();
    if (former_force_ < 0) former_force_ = net_.max_net_force(forces_[force_front_]);
    const double tried = tc.trial(std::numeric_limits<double>::infinity());
    const double h = tc.trial(frame_end - time_);
    const StepReport r =
        integrator_->step(net_, inputs_, front(), forces_[force_front_], h, back());
    constrain(front(), back(), h);
    NodeVectors& landed = forces_[1 - force_front_];
    net_.net_forces(back(), inputs_, landed);
    force_evaluations_ += r.force_evaluations + 1;
    cg_iterations_ += r.cg_iterations;
    const double m = net_.max_net_force(landed);
    const double allowed =
        former_force_ + A.growth_tolerance * std::max(former_force_, force_scale_);
    const bool grows = !(m <= allowed);  // NaN grows
    const bool forced = grows && tc.at_floor();
    StepEvent ev{time_, tried, h, !grows || forced, forced, m, former_force_};
    accepted = !grows || forced;
    if (!accepted) {
      ++rejected_;
      tc.reject();  // rollback: the back buffer is not swapped in
      if (observer_) observer_(ev);
      continue;
    }
    accept(h);
    force_front_ = 1 - force_front_;
    former_force_ = m;
    tc.accept();
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
  degenerate_ = net_.degenerate_springs(state());
  std::string why = monitor_.check(net_, state(), inputs_);
  if (why.empty()) {
    if (!monitor_.striking()) {
      checkpoint_ = state();
      checkpoint_time_ = time_;
      checkpoint_steps_ = steps_;
    }
    return;
  }
  // Diverged: go back to the last state that passed a check.
  front() = checkpoint_;
  time_ = checkpoint_time_;
  steps_ = checkpoint_steps_;
  invalidate(Stale::forces);
  status_ = RunStatus::diverged;
  reason_ = std::move(why);
}

}  // namespace neurocloth
