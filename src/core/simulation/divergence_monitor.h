#pragma once
// Decides whether a state is still physical: finite, and with kinetic plus
// spring energy within a budget. The budget is the energy the scene can
// legitimately hold — what it started with, what gravity has released since,
// what the external forces and force modules (wind) could put in over the
// cloth's size — so a long
// free fall or a user's drag is not "runaway", while an exploding integrator is.
// One strike above runaway_factor * budget is tolerated (an implicit step on a
// very stiff cloth can lift the energy a few hundred times for a step or two).
#include <string>

#include "core/network/cloth_network.h"
#include "core/simulation/solver_settings.h"

namespace neurocloth {

class DivergenceMonitor {
 public:
  DivergenceMonitor() = default;  // a budget of nothing, until assigned a real one
  DivergenceMonitor(const ClothNetwork& net, const ClothState& initial,
                    const DivergenceSettings& settings);
  // Empty when healthy; otherwise why the run diverged.
  std::string check(const ClothNetwork& net, const ClothState& state, const ForceInputs& inputs);
  bool striking() const { return strikes_ > 0; }
  bool same_bits(const DivergenceMonitor& o) const;

 private:
  DivergenceSettings settings_;
  double size_ = 0;           // cloth bounding-box diagonal at the start, m
  double base_budget_ = 0;    // J
  double gravity_start_ = 0;  // gravity potential at the start, J
  int strikes_ = 0;
};

}  // namespace neurocloth
