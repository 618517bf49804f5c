// The step bound the adaptive propagation respects.
#include "core/integrators/stability.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/simulation/simulation.h"
#include "support/test_support.h"

namespace neurocloth {
namespace {

TEST(Stability, SingleSpringBoundByHand) {
  // One free node on one spring to a pin: Gershgorin gives omega^2 = 2 k / m
  // (twice the true k / m: the bound is safe, never optimistic), gamma = 2 c / m.
  Scene scene = test::asset_scene("spring_mass");
  scene.material.viscosity = 0.3;
  const ClothNetwork net = scene.build_network();
  const double k = 40, m = 0.1, c = 0.3;
  const double omega2 = 2 * k / m, gamma = 2 * c / m;
  const double L = 2.0;
  EXPECT_NEAR(stable_step_bound(net, L),
              L * L / (gamma + std::sqrt(gamma * gamma + L * L * omega2)), 1e-15);
  EXPECT_TRUE(std::isinf(stable_step_bound(net, INFINITY)));
}

TEST(Stability, NetworkPropagationIsStableBelowTheBoundAndNotFarAboveIt) {
  Scene scene = test::asset_scene("hanging");
  scene.material.viscosity = 0.0;
  const ClothNetwork net = scene.build_network();
  const double bound = stable_step_bound(net, 2.0);
  ASSERT_GT(bound, 0);
  scene.solver.dt = 0.99 * bound;
  Simulation below = scene.make_simulation();
  EXPECT_EQ(below.advance(3.0), RunStatus::ok);
  // The bound is conservative, but not by more than the Gershgorin factor of
  // about two: six times above it the explicit propagation explodes.
  scene.solver.dt = 6 * bound;
  Simulation above = scene.make_simulation();
  EXPECT_EQ(above.advance(3.0), RunStatus::diverged);
}

TEST(Stability, PinnedAndSpringlessNodesDoNotLimitTheStep) {
  const Scene scene = test::asset_scene("free_fall");
  EXPECT_TRUE(std::isinf(stable_step_bound(scene.build_network(), 2.0)));
}

}  // namespace
}  // namespace neurocloth
