#pragma once
// Moves the network's weights from one material to another over a number of
// steps instead of at once. A sudden stiffness or mass change releases (or
// demands) energy in a single step and the cloth visibly jumps — a known
// complaint about other simulators; spread over ~0.05 s it is invisible.
// Stiffness and mass move geometrically (a factor of 10 takes equal factors
// per step), damping and friction linearly (they may be zero); the schedule
// is smoothstep, so the rate of change is zero at both ends.
#include <vector>

#include "cloth_network.h"

namespace neurocloth {

class WeightRamp {
 public:
  // From `net`'s current weights to `target`'s (same topology), over `steps` >= 1.
  void start(const ClothNetwork& net, const ClothNetwork& target, int steps);
  bool active() const { return step_ < steps_; }
  // Writes the next step's weights into `net`; false when there was nothing to do.
  bool advance(ClothNetwork& net);

 private:
  std::vector<double> k0_, k1_, d0_, d1_, w0_, w1_, f0_, f1_;
  int step_ = 0, steps_ = 0;
};

}  // namespace neurocloth
