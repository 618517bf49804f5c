#pragma once
// Runs a network forward in time: fixed steps or the paper's adaptive
// propagation (Table 1), with rollback of rejected steps and divergence
// detection that keeps the last good state. The integrator writes into a back
// buffer which becomes current only when the step is accepted, so a rejection
// costs nothing to undo.
//
// A simulation is a model, a state and a step context (MuJoCo's mjModel /
// mjData, Box2D's b2StepContext). The model — the network, the constraint
// modules, the solver settings — is read by a step and changes only between
// steps, through the calls below. The state (SimulationState) is everything a
// step writes; run_state() and restore() save and put it back. The context
// (StepContext) holds threads, clocks, how forces are evaluated, and caches
// rebuilt from the other two.
// Every member is a value: a copy of a running simulation continues exactly as
// the original would, bit for bit, and stepping one leaves the other alone.
#include <array>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/base/cloned.h"
#include "core/integrators/integrator.h"
#include "core/network/cloth_network.h"
#include "core/network/material.h"
#include "core/network/parameter_id.h"
#include "core/network/weight_ramp.h"
#include "core/simulation/divergence_monitor.h"
#include "core/simulation/simulation_state.h"
#include "core/simulation/solver_settings.h"
#include "core/simulation/step_context.h"

namespace neurocloth {

// What one active module has cost so far.
struct ModuleReport {
  std::string type;
  std::string declaration;  // the scene's JSON for it
  double seconds = 0;       // wall time inside the module
  long calls = 0;
  std::size_t state_bytes = 0;
};

// One trial step of the adaptive propagation, for tests and diagnostics.
struct StepEvent {
  double time;  // time at the start of the trial
  double tc;    // the time constant t_c tried
  double step;  // the step taken (t_c clipped to the frame end)
  bool accepted;
  bool forced;              // accepted only because t_c was at its floor
  double max_force;         // max |sum f| after the trial
  double former_max_force;  // the same before it
};

class Simulation {
 public:
  // `constraints` run after every integrator step, in order (see ConstraintModule);
  // force modules travel inside the network.
  Simulation(ClothNetwork network, ClothState initial, SolverSettings settings,
             std::vector<std::shared_ptr<const ConstraintModule>> constraints = {});

  // Propagates `seconds` of simulated time (0 does nothing). Stops early, with
  // the last good state, when the run diverges. The full check (finite state,
  // energy within budget) runs every check_interval steps; the state returned
  // is always finite. Stops early too, still ok, when the step budget runs out
  // (settings().step_budget trial steps per dt): then budget_exhausted().
  RunStatus advance(double seconds);
  // True when the last advance() ended before the time it was asked for because
  // it ran out of step budget (the state is finite and healthy, only behind;
  // time() says how far it got). Cleared by the next advance().
  bool budget_exhausted() const { return budget_exhausted_; }
  // Asked between frames (after every dt of simulated time) inside advance(),
  // and every 1024 steps within a frame (one at the step's floor can take
  // minutes); when it returns true, advance() returns there, ok and short of
  // the time asked: interrupted() (cleared by the next advance()). The steps
  // taken are exactly those of an uninterrupted run, up to where it stopped.
  // For progress lines, Ctrl-C and a thread's stop.
  void set_interrupt(std::function<bool(const Simulation&)> interrupt) {
    interrupt_ = std::move(interrupt);
  }
  bool interrupted() const { return interrupted_; }
  // Runs the full divergence check now (e.g. each frame of a live run).
  RunStatus check_now();
  // The check of a state about to be written or measured (a result file, a
  // trade's last sample, a fit's rollout): a strike there, or one left by the
  // last periodic check, is a divergence at once, since no later check can
  // confirm or clear it.
  RunStatus check_result();

  const ClothNetwork& network() const { return net_; }
  // For parameter changes between steps; drops cached forces and step bounds.
  ClothNetwork& mutable_network();
  // A live change of force module `index`'s parameter `id` (SceneModule::
  // set_parameter): the module is replaced by a changed copy, so copies of
  // this simulation keep theirs. False when the module has no such parameter.
  bool set_module_parameter(std::size_t index, const ParameterId& id, double value);
  void set_external_force(std::size_t node, const Vec3& force);
  // External forces and the clock the next step's force evaluations read.
  const ForceInputs& force_inputs() const { return run_.inputs; }
  // Moves every spring's and node's weights to `material`'s over `steps`
  // accepted steps (a live change of a linguistic input: no jolt).
  void ramp_to_material(const Material& material, int steps = 64);
  bool ramping() const { return run_.ramp.active(); }
  // A new cloth state at the current time; it becomes the checkpoint too.
  void set_state(const ClothState& state);
  // Everything a step writes, to save (copy it), compare (same_bits) or restore.
  const SimulationState& run_state() const { return run_; }
  // Puts a saved state back: the run continues as it did from that point, bit
  // for bit, as long as the model is unchanged since (restore does not touch
  // the network, the constraints or the settings; a ramp in progress rewrites
  // the weights at its next step). The integrator's own history (the implicit
  // step's preconditioner, projective's convergence rate) stays; it changes
  // bits only within the solver tolerance. Refuses, with std::invalid_argument
  // naming what differs, a state of another node count or module count.
  // Drops the cached forces and step cap.
  void restore(const SimulationState& state);
  // Between steps (a live control): a new dt, integrator or adaptive switch. The
  // integrator is rebuilt (its scratch and any cache belong to the old settings)
  // and cached forces and the step cap are dropped; state and time carry on.
  void set_solver_settings(const SolverSettings& settings);
  // Pins or frees a node between steps. The mass layer masks only a pinned node's
  // acceleration, so a node pinned while moving would drift on: its velocity is
  // cleared (in the checkpoint too, so a rollback does not revive it).
  void set_pinned(std::size_t node, bool pinned);
  // After a live change of what the divergence budget was measured against
  // (gravity, wind): the budget restarts from the current state, as at
  // construction. Otherwise energy released under the old gravity (a long
  // fall) would count as runaway once gravity changes.
  void rebase_divergence_check();

  const ClothState& state() const { return run_.cloth(); }
  const SolverSettings& settings() const { return settings_; }
  RunStatus status() const { return run_.status; }
  const std::string& divergence_reason() const { return run_.reason; }
  // The largest unexplained rise of the energy the divergence check has seen,
  // in allowances (DivergenceMonitor::largest_growth; above 1 is a strike).
  double largest_energy_growth() const { return run_.monitor.largest_growth(); }
  double time() const { return run_.time; }
  long steps() const { return run_.counters.steps; }
  long rejected_steps() const { return run_.counters.rejected; }
  long force_evaluations() const { return run_.counters.force_evaluations; }
  long cg_iterations() const { return run_.counters.cg_iterations; }
  // Springs with no length (skipped by the force evaluation) at the last check.
  int degenerate_springs() const { return run_.counters.degenerate_springs; }
  // The adaptive cap on t_c (safety * stability bound, at most dt); with
  // substep_above_cap, the largest fixed (sub)step too. Recomputed after any
  // weight change (mutable_network, a ramp step, new solver settings).
  double step_cap();
  // How many equal substeps one fixed step of dt takes now: ceil(dt / step_cap())
  // with substep_above_cap, else 1 (also when adaptive or implicit).
  long substeps();
  Energy energy() const { return net_.energy(state()); }

  // The active modules (force modules first, then constraints in run order).
  std::vector<ModuleReport> module_reports() const;
  std::size_t module_count() const { return net_.force_modules.size() + constraints_.size(); }
  // What the simulation itself holds for modules, besides each module's own
  // state_bytes: the module lists and the step-start buffer constraints read.
  // 0 for a scene that declares none.
  std::size_t module_overhead_bytes() const;

  void set_observer(std::function<void(const StepEvent&)> observer) {
    observer_ = std::move(observer);
  }

 private:
  using Stale = StepContext::Stale;

  // The stages of a step, in the order advance() calls them.
  // One fixed frame of h: a single step, or equal substeps under the cap when
  // guarded. False when the step budget ran out before the frame's end.
  bool fixed_frame(double h);
  // One fixed step of h from the current cloth (never rejected).
  void fixed_step(double h);
  // False when the step budget ran out before frame_end.
  bool adaptive_frame(double frame_end);
  // One trial of Table 1 over at most t_c; true when it was accepted.
  bool adaptive_trial(StepController& tc, double frame_end);
  bool take_from_budget();
  // Asks the interrupt (set) now: true, and interrupted(), when it says stop.
  bool ask_interrupt();
  bool advance_ramp();
  void begin_step();
  void start_forces();
  StepStart keep_step_start(bool in_place);
  void integrate(const ClothState& in, double h, ClothState& out);
  // The modules' hooks after one integrator step from `before` (at time()) over h.
  void constrain(const StepStart& before, ClothState& after, double h);
  double landing_max_force(const ClothState& landed);
  bool force_grows(double landed_max_force) const;
  // The step's result is in the back buffer (swap it in) or already current.
  void accept(double h, bool result_in_back = true);
  void accept_trial(StepController& tc, double h, double landed_max_force, double frame_end);
  void reject_trial(StepController& tc);
  void check_if_due(bool force_check);
  void full_check(bool final = false);
  void invalidate(Stale what) { ctx_.drop(what); }

  // The model: read by a step, changed only between steps.
  ClothNetwork net_;
  std::vector<std::shared_ptr<const ConstraintModule>> constraints_;
  SolverSettings settings_;
  double force_scale_ = 0;  // largest node weight, for the absolute growth tolerance
  // Made from the settings: its scratch, and a history that only speeds it up.
  Cloned<Integrator> integrator_;

  SimulationState run_;  // everything a step writes
  StepContext ctx_;      // threads, clocks, caches and scratch

  // The outcome of the last advance(), and callbacks: no step result depends on them.
  bool budget_exhausted_ = false;
  bool interrupted_ = false;
  long steps_since_ask_ = 0;  // steps taken since the interrupt was last asked
  std::function<void(const StepEvent&)> observer_;
  std::function<bool(const Simulation&)> interrupt_;
};

}  // namespace neurocloth
