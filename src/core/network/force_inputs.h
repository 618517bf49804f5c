#pragma once
// What a force evaluation reads besides the neurons' outputs and the model: the
// state's other inputs to the acceleration neurons. They change between steps
// (a user drags a node, the clock moves the gust) and are frozen for one step,
// so every stage of an RK4 step and every solve of an implicit one sees the
// same inputs. A simulation owns them beside its ClothState; a copy of the
// simulation has its own.
#include <vector>

#include "core/base/step_threads.h"
#include "core/network/cloth_state.h"
#include "core/network/module_clock.h"
#include "core/network/spring_kernel.h"
#include "core/network/spring_precision.h"

namespace neurocloth {

struct ForceInputs {
  // N per node, the acceleration neurons' bias input. Empty (no memory, no
  // work) until a force is set on some node.
  NodeVectors external_force;
  // Start of the step being taken: time-dependent force modules (a gust) read it.
  double time = 0;
  // Wall time each force module has spent, in the network's module order. A
  // diagnostic that no result reads; kept here so a const network can be timed.
  mutable std::vector<ModuleClock> clocks;
  // Who shares the sweeps of a step (not owned; null: the calling thread
  // alone). Results do not depend on it (step_threads.h). A simulation points
  // it at its own team before each step.
  StepThreads* threads = nullptr;
  // The force neurons' arithmetic (SolverSettings::precision); a simulation
  // sets it from its settings.
  SpringPrecision precision = SpringPrecision::float64;
  // The code that evaluates them (SolverSettings::kernel; spring_kernel.h):
  // the same forces to round-off, other last bits.
  SpringKernel kernel = SpringKernel::automatic;
  // Whether the force neurons add their damping term (the velocity-force
  // neuron). False where the integrator damps the springs itself, after the
  // velocity neurons' update (SolverSettings::damping, spring_damping.h): the
  // sum then holds the springs' elastic part and everything else.
  bool spring_damping = true;
};

}  // namespace neurocloth
