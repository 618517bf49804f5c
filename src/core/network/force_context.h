#pragma once
// How a force evaluation runs, as opposed to what it reads (ForceInputs): who
// shares the sweeps, which arithmetic and code evaluate the force neurons, and
// where the modules' wall time goes. None of it is state: a saved run must not
// carry another simulation's threads or clocks, and restoring one must not
// switch the arithmetic its simulation was set to. A simulation keeps one in
// its StepContext and fills it from its SolverSettings; a default one is a
// single thread in double with the damping term, timing nothing.
#include <vector>

#include "core/base/step_threads.h"
#include "core/network/module_clock.h"
#include "core/network/spring_kernel.h"
#include "core/network/spring_precision.h"

namespace neurocloth {

struct ForceContext {
  // Wall time each force module has spent, in the network's module order
  // (empty: none timed). A diagnostic that no result reads; mutable so a
  // const network can be timed through a const context.
  mutable std::vector<ModuleClock> clocks;
  // Who shares the sweeps (not owned; null: the calling thread alone). Results
  // do not depend on it (step_threads.h).
  StepThreads* threads = nullptr;
  // The force neurons' arithmetic (SolverSettings::precision).
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
