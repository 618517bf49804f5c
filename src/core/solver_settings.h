#pragma once
// How a scene asks to be propagated. Defaults are documented in docs/scenes.md.
#include "integrator.h"

namespace neurocloth {

// The paper's Table 1 plus what it lacks (see docs/network.md, "Adaptive step").
struct AdaptiveSettings {
  double safety = 0.5;  // t_c never exceeds safety * stable_step_bound
  // "The force grows" means max|F| > former + growth_tolerance * max(former, weight scale).
  double growth_tolerance = 0.05;
  double min_step_fraction = 1.0 / 1024.0;  // floor on t_c, as a fraction of its cap
};

struct DivergenceSettings {
  int check_interval = 64;      // accepted steps between checks (and checkpoints)
  double runaway_factor = 1e4;  // energy above factor * budget is a strike
  int runaway_checks = 2;       // consecutive strikes that make a divergence
  double hard_factor = 1e10;    // above this, one strike is enough
};

struct SolverSettings {
  IntegratorKind integrator = IntegratorKind::network;
  double dt = 1e-3;  // fixed step, or the refresh interval t_delta when adaptive
  bool adaptive = false;
  AdaptiveSettings adaptive_settings;
  DivergenceSettings divergence;
};

}  // namespace neurocloth
