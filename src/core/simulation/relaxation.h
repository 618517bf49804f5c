#pragma once
// The paper's propagation Step 1: "the network was propagated until a local
// energy minimum was reached". We propagate with velocities quenched and an
// implicit step that grows without bound, which is Newton's method on the
// potential energy, regularised by M / h^2 and guarded by an energy line search:
//   (K + mu M) dx = F(x),  mu = 1/h^2;  accept if E(x + dx) <= E(x), then mu /= 4,
//   else mu *= 8.
// Near the minimum mu -> 0 and convergence is quadratic, which is what lets the
// static drape be converged to 1e-9 m instead of "until it looks still". The
// Hessian is the exact one (compressed springs included), so CG may meet
// negative curvature far from the minimum: it then stops early (Steihaug) and
// the line search and mu take care of the rest.
#include "core/network/cloth_network.h"

namespace neurocloth {

struct RelaxSettings {
  int max_iterations = 500;
  // Converged when max |F| over free nodes <= force_tolerance and the last
  // accepted step moved no node more than position_tolerance.
  double force_tolerance = -1;        // N; < 0: 1e-10 times the heaviest node's weight (or 1e-12 N)
  double position_tolerance = 1e-10;  // m
  double cg_tolerance = 1e-12;
};

struct RelaxReport {
  bool converged = false;
  int iterations = 0;
  int cg_iterations = 0;
  double residual_force = 0;  // N, max over free nodes
  double last_step = 0;       // m, max node displacement of the last accepted step (0: none)
  int accepted_steps = 0;
  std::size_t free_nodes = 0;  // none: nothing can move, so the state is converged as it is
};

// Relaxes `state` in place (velocities set to zero). External forces in `inputs`
// count, as a potential -f.p; the forces are evaluated as `context` says.
// Never leaves NaN in `state`: a failed trial is not accepted.
RelaxReport relax(const ClothNetwork& net, ClothState& state, const RelaxSettings& settings = {},
                  const ForceInputs& inputs = {}, const ForceContext& context = {});

}  // namespace neurocloth
