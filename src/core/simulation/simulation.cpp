// Stepping: advance() cuts the time asked for into frames of dt, each frame
// is fixed steps or the adaptive trials of Table 1, and every step is the
// same short list of named stages (begin, start forces, integrate, constrain,
// accept or reject, check), so a reader sees the order a step runs in without
// reading its arithmetic. Building and live edits are in simulation_edits.cpp.
#include "core/simulation/simulation.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/integrators/stability.h"

namespace neurocloth {

RunStatus Simulation::advance(double seconds) {
  budget_exhausted_ = false;
  interrupted_ = false;
  steps_since_ask_ = 0;
  if (run_.status != RunStatus::ok || !(seconds > 0.0)) return run_.status;
  const double t_end = run_.time + seconds;
  const double dt = settings_.dt;
  // step_budget per dt asked for, rounded up, plus one for a round-off remainder.
  const double allowance =
      static_cast<double>(settings_.step_budget) * (std::ceil(seconds / dt) + 1);
  ctx_.budget_left = allowance < 1e18 ? static_cast<long>(allowance) : 1000000000000000000L;
  // The team serves this call only (see StepContext::threads).
  struct LendTeam {
    ForceContext& force;
    ~LendTeam() { force.threads = nullptr; }
  } lend{ctx_.force};
  ctx_.force.threads = ctx_.threads.get();
  while (run_.status == RunStatus::ok && run_.time < t_end) {
    if (ctx_.budget_left <= 0) {
      budget_exhausted_ = true;
      break;
    }
    const double remaining = t_end - run_.time;
    const bool last = remaining <= dt * (1.0 + 1e-9);
    // A remainder within round-off of dt is dt: then advance(k dt) takes the same
    // steps, bit for bit, however it is split into calls.
    const bool whole = std::abs(remaining - dt) <= 1e-9 * dt;
    const bool done = settings_.adaptive ? adaptive_frame(last ? t_end : run_.time + dt)
                                         : fixed_frame(last && !whole ? remaining : dt);
    if (interrupted_) break;  // within the frame: time is where its last step left it
    if (!done && run_.status == RunStatus::ok) budget_exhausted_ = true;
    if (last && done && run_.status == RunStatus::ok) run_.time = t_end;  // no drift at the end
    if (interrupt_ && !last && run_.status == RunStatus::ok && ask_interrupt()) break;
  }
  // Between energy checks, at least never hand out a NaN: a cheap test every call.
  if (run_.status == RunStatus::ok && run_.counters.steps_since_check > 0 && !state().all_finite())
    full_check();
  return run_.status;
}

bool Simulation::fixed_frame(double frame) {
  if (!settings_.substep_above_cap) {  // the plain step: exactly the step asked for
    --ctx_.budget_left;
    advance_ramp();
    fixed_step(frame);
    return true;
  }
  // Guarded: equal substeps under the cap, recounted after each one because a
  // ramp may lower the cap mid-frame. Time lands on start + frame exactly, as
  // an unguarded step of the same frame would.
  const double end = run_.time + frame;
  double left = frame;
  while (run_.status == RunStatus::ok) {
    if (!take_from_budget()) return false;
    advance_ramp();
    const double h =
        StepController(step_cap(), settings_.adaptive_settings.min_step_fraction).equal_piece(left);
    fixed_step(h);
    if (h == left) break;
    left -= h;
  }
  if (run_.status == RunStatus::ok) run_.time = end;
  return true;
}

// A fixed step is never rejected, so an integrator that can may write over
// the current cloth (the checkpoint still guards against divergence).
void Simulation::fixed_step(double h) {
  begin_step();
  if (integrator_->reads_start_force()) start_forces();
  const bool in_place = integrator_->steps_in_place();
  const StepStart before = keep_step_start(in_place);
  ClothState& out = in_place ? run_.cloth() : run_.back();
  integrate(run_.cloth(), h, out);
  constrain(before, out, h);
  invalidate(Stale::forces);
  accept(h, !in_place);
  check_if_due(false);
}

// The paper's Table 1, with a rollback of rejected trials (the back buffer is
// simply not swapped in), a cap on t_c from the stability bound, a floor on t_c,
// and a tolerance on "the force grows".
bool Simulation::adaptive_frame(double frame_end) {
  // Table 1: t_c := t_delta, under the cap.
  StepController tc(step_cap(), settings_.adaptive_settings.min_step_fraction);
  bool accepted = true;
  while (run_.status == RunStatus::ok && run_.time < frame_end) {
    if (!take_from_budget()) return false;
    if (accepted && advance_ramp()) tc.set_cap(step_cap());  // weights moved: a new cap
    accepted = adaptive_trial(tc, frame_end);
  }
  return true;
}

bool Simulation::adaptive_trial(StepController& tc, double frame_end) {
  begin_step();
  start_forces();
  if (ctx_.start_max_force < 0)
    ctx_.start_max_force = net_.max_net_force(ctx_.start_forces(), ctx_.force.threads);
  const double tried = tc.trial(std::numeric_limits<double>::infinity());
  const double h = tc.trial(frame_end - run_.time);
  integrate(run_.cloth(), h, run_.back());
  constrain(run_.cloth(), run_.back(), h);
  const double m = landing_max_force(run_.back());
  const bool grows = force_grows(m);
  const bool forced = grows && tc.at_floor();
  const StepEvent ev{run_.time, tried, h, !grows || forced, forced, m, ctx_.start_max_force};
  if (ev.accepted)
    accept_trial(tc, h, m, frame_end);
  else
    reject_trial(tc);
  if (observer_) observer_(ev);
  if (ev.accepted) check_if_due(!std::isfinite(m));
  return ev.accepted;
}

bool Simulation::take_from_budget() {
  if (ctx_.budget_left <= 0) return false;
  // A frame at the step's floor can be millions of steps (minutes): the
  // interrupt is asked within it too, after every kStepsBetweenAsks steps
  // since it was last asked (before the next one is taken).
  constexpr long kStepsBetweenAsks = 1024;
  if (interrupt_ && steps_since_ask_ >= kStepsBetweenAsks && ask_interrupt()) return false;
  ++steps_since_ask_;
  --ctx_.budget_left;
  return true;
}

bool Simulation::ask_interrupt() {
  steps_since_ask_ = 0;
  interrupted_ = interrupt_(*this);
  return interrupted_;
}

// Applies the ramp's next weights (between two steps); drops what they invalidate.
bool Simulation::advance_ramp() {
  if (!run_.ramp.advance(net_)) return false;
  invalidate(Stale::weights);
  return true;
}

// The step's inputs are frozen at its start; forces cached at the current state
// for an earlier time are stale when a module reads the time (a gust).
void Simulation::begin_step() {
  if (run_.inputs.time == run_.time) return;
  run_.inputs.time = run_.time;
  for (const auto& m : net_.force_modules)
    if (m->time_dependent()) {
      invalidate(Stale::forces);
      return;
    }
}

void Simulation::start_forces() {
  if (ctx_.forces_valid) return;
  net_.net_forces(state(), run_.inputs, ctx_.force, ctx_.forces[ctx_.current_forces]);
  ctx_.forces_valid = true;
}

// With constraints, a step taken in place keeps its start positions aside
// first: copying three arrays costs less than writing the whole step to the
// other buffer.
StepStart Simulation::keep_step_start(bool in_place) {
  const ClothState& in = run_.cloth();
  if (!in_place) return StepStart(in);
  if (!constraints_.empty()) {
    std::copy(in.x.begin(), in.x.end(), ctx_.step_start.x.begin());
    std::copy(in.y.begin(), in.y.end(), ctx_.step_start.y.begin());
    std::copy(in.z.begin(), in.z.end(), ctx_.step_start.z.begin());
  }
  return StepStart(ctx_.step_start);
}

void Simulation::integrate(const ClothState& in, double h, ClothState& out) {
  const StepReport r =
      integrator_->step(net_, run_.inputs, ctx_.force, in, ctx_.start_forces(), h, out);
  run_.counters.force_evaluations += r.force_evaluations;
  run_.counters.cg_iterations += r.cg_iterations;
}

void Simulation::constrain(const StepStart& before, ClothState& after, double h) {
  const StepSpan span{run_.time, h, ctx_.force.threads};
  for (std::size_t k = 0; k < constraints_.size(); ++k) {
    ScopedModuleTimer timer(ctx_.constraint_clocks[k]);
    constraints_[k]->apply(net_, span, before, after, run_.module_states[k].get());
  }
}

// The forces where a trial landed: what Table 1 judges it by, and the next
// step's start forces if it is accepted.
double Simulation::landing_max_force(const ClothState& landed) {
  net_.net_forces(landed, run_.inputs, ctx_.force, ctx_.landing_forces());
  ++run_.counters.force_evaluations;
  return net_.max_net_force(ctx_.landing_forces(), ctx_.force.threads);
}

bool Simulation::force_grows(double m) const {
  const double former = ctx_.start_max_force;
  const double allowed =
      former + settings_.adaptive_settings.growth_tolerance * std::max(former, force_scale_);
  return !(m <= allowed);  // NaN grows
}

void Simulation::accept(double h, bool result_in_back) {
  if (result_in_back) run_.current = 1 - run_.current;
  run_.time += h;
  ++run_.counters.steps;
  ++run_.counters.steps_since_check;
}

void Simulation::accept_trial(StepController& tc, double h, double m, double frame_end) {
  accept(h);
  ctx_.current_forces = 1 - ctx_.current_forces;
  ctx_.start_max_force = m;
  tc.accept();
  if (frame_end - run_.time <= 1e-12 * settings_.dt) run_.time = frame_end;
}

void Simulation::reject_trial(StepController& tc) {
  ++run_.counters.rejected;
  tc.reject();  // rollback: the back buffer is not swapped in
}

void Simulation::check_if_due(bool force_check) {
  if (force_check || run_.counters.steps_since_check >= settings_.divergence.check_interval)
    full_check();
}

RunStatus Simulation::check_now() {
  if (run_.status == RunStatus::ok && run_.counters.steps_since_check > 0) full_check();
  return run_.status;
}

RunStatus Simulation::check_result() {
  if (run_.status == RunStatus::ok &&
      (run_.counters.steps_since_check > 0 || run_.monitor.striking()))
    full_check(true);
  return run_.status;
}

void Simulation::full_check(bool final) {
  run_.counters.steps_since_check = 0;
  run_.counters.degenerate_springs = net_.degenerate_springs(state());
  std::string why = run_.monitor.check(net_, state(), run_.inputs, run_.checkpoint.state, final);
  if (why.empty()) {
    if (!run_.monitor.striking()) run_.checkpoint = {state(), run_.time, run_.counters.steps};
    return;
  }
  // Diverged: go back to the last state that passed a check.
  run_.cloth() = run_.checkpoint.state;
  run_.time = run_.checkpoint.time;
  run_.counters.steps = run_.checkpoint.steps;
  invalidate(Stale::forces);
  run_.status = RunStatus::diverged;
  run_.reason = std::move(why);
}

double Simulation::step_cap() {
  if (ctx_.step_cap < 0) {
    // Recomputed after every weight change, a ramp's steps too: the bound is
    // not monotone along a ramp (damping moves linearly, mass geometrically).
    // A ramp moves the weights at every step, so it takes Gershgorin's bound,
    // which costs a sweep, where the spectral one costs a hundred or so.
    const StepBound kind = ramping() ? StepBound::gershgorin : settings_.step_bound;
    const double bound = integrator_step_bound(net_, *integrator_, ctx_.bound, kind);
    ctx_.step_cap = std::min(settings_.dt, settings_.adaptive_settings.safety * bound);
  }
  return ctx_.step_cap;
}

long Simulation::substeps() {
  if (settings_.adaptive || !settings_.substep_above_cap) return 1;
  const double n = std::ceil(settings_.dt / step_cap() * (1.0 - 1e-12));
  return n >= static_cast<double>(std::numeric_limits<long>::max())
             ? std::numeric_limits<long>::max()
             : std::max(1L, static_cast<long>(n));
}

}  // namespace neurocloth
