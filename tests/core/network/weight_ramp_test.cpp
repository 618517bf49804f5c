// A material ramp moves every weight along its own path: geometric where both
// ends are positive, linear otherwise, on a smoothstep schedule, landing on the
// target exactly. The ramp raises each distinct ratio to its power once per
// step; these tests check that the result is the per-weight formula, bit for bit.
#include <gtest/gtest.h>

#include <cmath>

#include "core/network/weight_ramp.h"
#include "support/test_support.h"

namespace neurocloth {
namespace {

double smoothstep(int step, int steps) {
  const double t = static_cast<double>(step) / steps;
  return step == steps ? 1.0 : t * t * (3.0 - 2.0 * t);
}

double expected(double a, double b, double s, bool geometric) {
  if (s == 1.0) return b;  // the last step lands on the target, not on a * (b / a)
  return geometric && a > 0 && b > 0 ? a * std::pow(b / a, s) : a + s * (b - a);
}

void expect_on_path(const std::vector<double>& from, const std::vector<double>& to,
                    const std::vector<double>& now, double s, bool geometric, const char* what) {
  ASSERT_EQ(now.size(), from.size());
  for (std::size_t i = 0; i < now.size(); ++i)
    ASSERT_EQ(now[i], expected(from[i], to[i], s, geometric)) << what << "[" << i << "] at s=" << s;
}

// Learned weights differ per spring: every weight then has a ratio of its own,
// and some damping is zero (a linear path).
TEST(WeightRamp, EveryWeightFollowsItsOwnPathAndLandsOnTheTarget) {
  ClothNetwork net = test::asset_scene("hanging").build_network();
  for (std::size_t k = 0; k < net.spring_count(); ++k) {
    net.springs.stiffness[k] *= 1.0 + 0.01 * static_cast<double>(k % 17);
    net.springs.damping[k] = k % 5 == 0 ? 0.0 : net.springs.damping[k];
  }
  const ClothNetwork start = net;
  Material m;
  m.spring_constant = 900;
  m.node_mass = 0.002;
  m.viscosity = 0.2;
  m.friction = 0.6;
  const MaterialWeights target = net.material_weights(m);
  const int steps = 8;
  WeightRamp ramp;
  ramp.start(net, target, steps);
  for (int step = 1; step <= steps; ++step) {
    ASSERT_TRUE(ramp.active());
    ASSERT_TRUE(ramp.advance(net));
    const double s = smoothstep(step, steps);
    expect_on_path(start.springs.stiffness, target.stiffness, net.springs.stiffness, s, true,
                   "stiffness");
    expect_on_path(start.springs.damping, target.damping, net.springs.damping, s, false, "damping");
    expect_on_path(start.masses.inverse_mass, target.inverse_mass, net.masses.inverse_mass, s, true,
                   "inverse_mass");
    expect_on_path(start.masses.friction, target.friction, net.masses.friction, s, false,
                   "friction");
  }
  EXPECT_FALSE(ramp.active());
  EXPECT_FALSE(ramp.advance(net));
  EXPECT_EQ(net.springs.stiffness, target.stiffness);
  EXPECT_EQ(net.masses.inverse_mass, target.inverse_mass);
}

TEST(WeightRamp, RefusesWeightsForAnotherNetwork) {
  ClothNetwork net = test::asset_scene("hanging").build_network();
  MaterialWeights target = net.material_weights(Material{});
  target.stiffness.pop_back();
  WeightRamp ramp;
  EXPECT_THROW(ramp.start(net, target, 4), std::invalid_argument);
}

}  // namespace
}  // namespace neurocloth
