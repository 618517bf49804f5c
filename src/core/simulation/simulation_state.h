#pragma once
// Everything a step writes, as one value (MuJoCo's mjData without its
// scratch): copy it to save a run, same_bits() to compare two, and
// Simulation::restore() to put one back. What a step only reads — the network,
// the constraint modules, the solver settings — is the model and stays in
// Simulation; what a step keeps only to go faster (cached forces, the step
// cap, scratch, threads, clocks) is in StepContext and is rebuilt from model
// and state, so leaving it out of this type changes no result.
#include <array>
#include <string>
#include <vector>

#include "core/base/cloned.h"
#include "core/network/cloth_state.h"
#include "core/network/force_inputs.h"
#include "core/network/scene_module.h"
#include "core/network/weight_ramp.h"
#include "core/simulation/divergence_monitor.h"

namespace neurocloth {

enum class RunStatus { ok, diverged };
const char* to_string(RunStatus s);

// The last state that passed a full check: where a divergence rolls back to.
struct Checkpoint {
  ClothState state;
  double time = 0;
  long steps = 0;
};

struct StepCounters {
  long steps = 0;     // accepted steps
  long rejected = 0;  // adaptive trials rolled back
  long force_evaluations = 0;
  long cg_iterations = 0;      // or projective's local-global iterations, vbd's sweeps
  int steps_since_check = 0;   // accepted steps since the last full check
  int degenerate_springs = 0;  // springs with no length at the last check
};

struct SimulationState {
  // The current cloth and the back buffer a step writes into: a rejected trial
  // is undone by not swapping them, so the pair is state, and `current` with it.
  std::array<ClothState, 2> buffers;
  int current = 0;
  double time = 0;
  StepCounters counters;
  // The external forces and the start time of the step (ForceInputs::time):
  // what a force evaluation reads besides the neurons.
  ForceInputs inputs;
  std::vector<Cloned<ModuleState>> module_states;  // one per constraint (null: keeps nothing)
  Checkpoint checkpoint;
  RunStatus status = RunStatus::ok;
  std::string reason;  // why the run diverged
  DivergenceMonitor monitor;
  WeightRamp ramp;  // the ramp in progress (its weights are written into the model)

  const ClothState& cloth() const { return buffers[current]; }
  ClothState& cloth() { return buffers[current]; }
  ClothState& back() { return buffers[1 - current]; }
};

// True when the two hold the same bits in every member a step reads (a NaN
// equals itself; 0.0 and -0.0 differ).
bool same_bits(const SimulationState& a, const SimulationState& b);
// The first member that differs ("counters.steps", "checkpoint.state", ...),
// empty when none: what a failing comparison prints.
std::string first_difference(const SimulationState& a, const SimulationState& b);

}  // namespace neurocloth
