#pragma once
// Moves the network's weights from one material to another over a number of
// steps instead of at once. A sudden stiffness or mass change releases (or
// demands) energy in a single step and the cloth visibly jumps — a known
// complaint about other simulators; spread over ~0.05 s it is invisible.
// Stiffness and mass move geometrically (a factor of 10 takes equal factors
// per step), damping and friction linearly (they may be zero); the schedule
// is smoothstep, so the rate of change is zero at both ends.
#include <cstdint>
#include <vector>

#include "core/network/cloth_network.h"

namespace neurocloth {

class WeightRamp {
 public:
  // From `net`'s current weights to `target` (for the same network), over `steps` >= 1.
  void start(const ClothNetwork& net, const MaterialWeights& target, int steps);
  bool active() const { return step_ < steps_; }
  // Writes the next step's weights into `net`; false when there was nothing to do.
  bool advance(ClothNetwork& net);
  bool same_bits(const WeightRamp& o) const;

  // One weight array's path. Geometric where both ends are positive, linear
  // otherwise. A material change scales whole families of weights by one
  // factor, so the geometric ratios take a few distinct values: each step
  // raises each distinct ratio to its power once, not once per weight.
  class Path {
   public:
    void start(const std::vector<double>& from, const std::vector<double>& to, bool geometric);
    void write(double s, std::vector<double>& out);  // s in [0, 1]; out = to at s = 1
    bool same_bits(const Path& o) const;             // factors_ is scratch, rewritten by write()
   private:
    std::vector<double> from_, to_;
    std::vector<std::int32_t> ratio_of_;  // per weight: its ratio's index, or -1 (linear)
    std::vector<double> ratios_, factors_;
  };

 private:
  Path stiffness_, damping_, inverse_mass_, friction_;
  int step_ = 0, steps_ = 0;
};

}  // namespace neurocloth
