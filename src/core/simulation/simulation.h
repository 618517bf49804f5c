#pragma once
// Runs a network forward in time: fixed steps or the paper's adaptive
// propagation (Table 1), with rollback of rejected steps and divergence
// detection that keeps the last good state. The integrator writes into a back
// buffer which becomes current only when the step is accepted, so a rejection
// costs nothing to undo.
//
// A simulation is a model and a state (MuJoCo's mjModel / mjData). The model —
// the network, the constraint modules, the solver settings — is read by a step
// and never written by it; it changes only between steps, through the calls
// below. The state — the neurons' outputs, the external forces and the clock
// (ForceInputs), what each constraint keeps between steps, the checkpoint, the
// ramp in progress — is everything a step writes. The rest is cache (forces at
// the current state, the step cap), dropped by one function, invalidate().
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
#include "core/simulation/solver_settings.h"

namespace neurocloth {

enum class RunStatus { ok, diverged };
const char* to_string(RunStatus s);

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
  // Asked between frames (after every dt of simulated time) inside advance();
  // when it returns true, advance() returns there, ok and short of the time
  // asked: interrupted() (cleared by the next advance()). The steps taken are
  // exactly those of an uninterrupted run. For progress lines and Ctrl-C.
  void set_interrupt(std::function<bool(const Simulation&)> interrupt) {
    interrupt_ = std::move(interrupt);
  }
  bool interrupted() const { return interrupted_; }
  // Runs the full divergence check now (e.g. before writing a result).
  RunStatus check_now();

  const ClothNetwork& network() const { return net_; }
  // For parameter changes between steps; drops cached forces and step bounds.
  ClothNetwork& mutable_network();
  // A live change of force module `index`'s parameter `id` (SceneModule::
  // set_parameter): the module is replaced by a changed copy, so copies of
  // this simulation keep theirs. False when the module has no such parameter.
  bool set_module_parameter(std::size_t index, const ParameterId& id, double value);
  void set_external_force(std::size_t node, const Vec3& force);
  // External forces and the clock the next step's force evaluations read.
  const ForceInputs& force_inputs() const { return inputs_; }
  // Moves every spring's and node's weights to `material`'s over `steps`
  // accepted steps (a live change of a linguistic input: no jolt).
  void ramp_to_material(const Material& material, int steps = 64);
  bool ramping() const { return ramp_.active(); }
  void set_state(const ClothState& state);
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

  const ClothState& state() const { return states_[front_]; }
  const SolverSettings& settings() const { return settings_; }
  RunStatus status() const { return status_; }
  const std::string& divergence_reason() const { return reason_; }
  double time() const { return time_; }
  long steps() const { return steps_; }
  long rejected_steps() const { return rejected_; }
  long force_evaluations() const { return force_evaluations_; }
  long cg_iterations() const { return cg_iterations_; }
  // Springs with no length (skipped by the force evaluation) at the last check.
  int degenerate_springs() const { return degenerate_; }
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
  // One fixed frame of h: a single step, or equal substeps under the cap when
  // guarded. False when the step budget ran out before the frame's end.
  bool fixed_frame(double h);
  void fixed_step(double h);  // advances the ramp, then steps
  void fixed_step_now(double h);
  // The modules' hooks around one integrator step from *front_ (at time_) over h.
  void begin_step();
  void constrain(const StepStart& before, ClothState& after, double h);
  // False when the step budget ran out before frame_end.
  bool adaptive_frame(double frame_end);
  void ensure_front_forces();
  // The step's result is in the back buffer (swap it in) or already in front.
  void accept(double h, bool result_in_back = true);
  void after_accept(bool force_check);
  void run_check();
  bool advance_ramp();
  // What a change leaves stale: `weights` (the network's weights or the
  // integrator) also drops the step cap; `forces` (the state, an external force,
  // a gust's time) only the forces cached at the current state.
  enum class Stale { forces, weights };
  void invalidate(Stale what);
  ClothState& front() { return states_[front_]; }
  ClothState& back() { return states_[1 - front_]; }

  // The model: read by a step, changed only between steps.
  ClothNetwork net_;
  std::vector<std::shared_ptr<const ConstraintModule>> constraints_;
  SolverSettings settings_;
  double force_scale_ = 0;  // largest node weight, for the absolute growth tolerance

  // The state: everything a step writes.
  std::array<ClothState, 2> states_;  // the current state and the back buffer
  int front_ = 0;
  ForceInputs inputs_;
  std::vector<Cloned<ModuleState>> module_states_;  // one per constraint (null: keeps nothing)
  ClothState checkpoint_;
  DivergenceMonitor monitor_;
  WeightRamp ramp_;
  RunStatus status_ = RunStatus::ok;
  std::string reason_;
  double time_ = 0, checkpoint_time_ = 0;
  long steps_ = 0, checkpoint_steps_ = 0, rejected_ = 0;
  long force_evaluations_ = 0, cg_iterations_ = 0;
  int steps_since_check_ = 0;
  int degenerate_ = 0;
  long budget_left_ = 0;  // trial steps this advance() may still take
  bool budget_exhausted_ = false;
  bool interrupted_ = false;

  // Caches and scratch, derived from the two above (invalidate()).
  Cloned<Integrator> integrator_;
  // Who shares the sweeps (settings_.threads; a copy gets its own team).
  // inputs_.threads points at it only inside advance(), so the inputs handed
  // out never lend the team to another caller.
  OwnedStepThreads threads_;
  // Where the nodes were when a fixed step taken in place began: what the
  // constraints read as the start (sized only when there are constraints).
  NodeVectors start_;
  std::array<NodeVectors, 2> forces_;  // forces_[force_front_] = net_forces(state()) when valid
  int force_front_ = 0;
  bool front_forces_valid_ = false;
  double cap_ = -1;                        // cached step cap; < 0 means stale
  double former_force_ = -1;               // max |sum f| at the current state; < 0 means unknown
  std::vector<double> bound_k_, bound_d_;  // scratch of the stability bound

  // Diagnostics and callbacks: no step result depends on them.
  std::vector<ModuleClock> constraint_clocks_;
  std::function<void(const StepEvent&)> observer_;
  std::function<bool(const Simulation&)> interrupt_;
};

}  // namespace neurocloth
