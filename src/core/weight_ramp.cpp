#include "weight_ramp.h"

#include <cmath>
#include <stdexcept>

namespace neurocloth {

void WeightRamp::start(const ClothNetwork& net, const ClothNetwork& target, int steps) {
  if (net.spring_count() != target.spring_count() || net.node_count() != target.node_count())
    throw std::invalid_argument("a weight ramp needs two networks of the same topology");
  k0_ = net.springs.stiffness;
  k1_ = target.springs.stiffness;
  d0_ = net.springs.damping;
  d1_ = target.springs.damping;
  w0_ = net.masses.inverse_mass;
  w1_ = target.masses.inverse_mass;
  f0_ = net.masses.friction;
  f1_ = target.masses.friction;
  step_ = 0;
  steps_ = std::max(1, steps);
}

namespace {
// Geometric where both ends are positive, linear otherwise.
void blend(const std::vector<double>& a, const std::vector<double>& b, double s, bool geometric,
           std::vector<double>& out) {
  for (std::size_t i = 0; i < out.size(); ++i)
    out[i] = geometric && a[i] > 0 && b[i] > 0 ? a[i] * std::pow(b[i] / a[i], s)
                                               : a[i] + s * (b[i] - a[i]);
}
}  // namespace

bool WeightRamp::advance(ClothNetwork& net) {
  if (!active()) return false;
  ++step_;
  const double t = static_cast<double>(step_) / steps_;
  const double s = step_ == steps_ ? 1.0 : t * t * (3.0 - 2.0 * t);  // smoothstep; exact at the end
  blend(k0_, k1_, s, true, net.springs.stiffness);
  blend(d0_, d1_, s, false, net.springs.damping);
  blend(w0_, w1_, s, true, net.masses.inverse_mass);
  blend(f0_, f1_, s, false, net.masses.friction);
  if (step_ == steps_) {  // land exactly on the target
    net.springs.stiffness = k1_;
    net.springs.damping = d1_;
    net.masses.inverse_mass = w1_;
    net.masses.friction = f1_;
  }
  return true;
}

}  // namespace neurocloth
