#pragma once
// A rollout's tape (rollout.h): what the forward run keeps for the backward
// one (every state, or checkpoints and one segment; the states before each
// constraint; the step's scratch), and the copy that writes a state to it.
#include <memory>
#include <vector>

#include "core/integrators/integrator.h"
#include "core/integrators/projective.h"
#include "core/network/cloth_state.h"
#include "core/network/force_context.h"
#include "core/network/force_inputs.h"
#include "learn/fit/rollout.h"

namespace neurocloth {

struct Rollout::Tape {
  std::vector<ClothState> checkpoints;  // states 0, K, 2K, ... (recomputing mode)
  std::vector<ClothState> states;       // one segment: states k0 .. k0 + K
  std::vector<ClothState> pre;          // per step of the segment, before each constraint
  ClothState work[2];                   // the forward run's two states when it keeps every one
  NodeVectors forces, adj_force, adj_before;
  ClothState adj;
  ForceInputs inputs;
  // Double with the damping term is the only step a fit has an adjoint of
  // (fit_problem.cpp refuses the others); one thread, nothing timed; the
  // scene's kernel (RolloutModel::kernel), set by each run.
  ForceContext context;
  std::unique_ptr<Integrator> integrator;
  // A projective run's integrator (the fit's hooks, projective.h), and
  // dE/d(the Chebyshev rate its run measured), carried back to that step.
  ProjectiveIntegrator* projective = nullptr;
  double rate_adjoint = 0;
  IntegratorKind kind = IntegratorKind::network;
};

// `from` copied into `to` (of the same size) by stores that do not first read
// `to`'s memory where the CPU has them; finish_tape() orders them before
// anything that follows.
void write_to_tape(const ClothState& from, ClothState& to);
void finish_tape();

}  // namespace neurocloth
