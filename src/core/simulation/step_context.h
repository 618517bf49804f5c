#pragma once
// What a step needs that is neither model nor state (Box2D's b2StepContext,
// Jolt's SoftBodyUpdateContext): who shares the sweeps, how the forces are
// evaluated, where the modules' wall time goes, and caches and scratch rebuilt
// from model and state. No result depends on anything here but the force
// evaluation's arithmetic, which is a copy of the settings (the model):
// dropping every cache (drop()) and recomputing gives the same bits, which is
// why Simulation::restore() may.
// Allocated at construction or on a settings change, never by a step.
#include <array>
#include <vector>

#include "core/base/step_threads.h"
#include "core/integrators/stability.h"
#include "core/network/cloth_state.h"
#include "core/network/force_context.h"
#include "core/network/module_clock.h"

namespace neurocloth {

struct StepContext {
  // Who shares the sweeps (SolverSettings::threads; a copy gets its own team).
  // force.threads points at it only inside advance(): a copy of the
  // simulation, made between steps, never borrows the original's team.
  OwnedStepThreads threads;
  // How every force evaluation of a step runs: the settings' precision, kernel
  // and damping, the team above, and one clock per force module.
  ForceContext force;
  std::vector<ModuleClock> constraint_clocks;  // one per constraint, a diagnostic

  // forces[current_forces] = net_forces(current cloth) when forces_valid; an
  // adaptive trial writes its landing forces into the other and swaps on accept.
  std::array<NodeVectors, 2> forces;
  int current_forces = 0;
  bool forces_valid = false;
  double start_max_force = -1;  // max |sum f| at the current cloth; < 0 unknown
  double step_cap = -1;         // safety * stability bound, at most dt; < 0 stale

  // Where the nodes were when a fixed step taken in place began: what the
  // constraints read as the start (sized only when there are constraints).
  NodeVectors step_start;
  StepBoundScratch bound;  // scratch of the stability bound
  long budget_left = 0;    // trial steps this advance() may still take

  // What a change leaves stale: `weights` (the network's weights or the
  // integrator) also drops the step cap; `forces` (the cloth, an external
  // force, a gust's time) only the forces cached at the current cloth.
  enum class Stale { forces, weights };
  void drop(Stale what) {
    forces_valid = false;
    start_max_force = -1;
    if (what == Stale::weights) step_cap = -1;
  }
  const NodeVectors& start_forces() const { return forces[current_forces]; }
  NodeVectors& landing_forces() { return forces[1 - current_forces]; }
};

}  // namespace neurocloth
