// The paper's Step 1, propagation to the local energy minimum, against closed
// forms and against the dynamics it short-cuts.
#include "core/simulation/relaxation.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/simulation/simulation.h"
#include "support/test_support.h"

namespace neurocloth {
namespace {

// A vertical chain of n nodes hanging from node 0: the spring above node i
// carries the weight of nodes i..n-1, so it is stretched by (n - i) m g / k and
// y_i = y_0 - sum_{j=1..i} (L + (n - j) m g / k).
TEST(Relaxation, HangingChainMatchesTheClosedFormTo1e6) {
  const Scene scene = test::asset_scene("chain");
  ASSERT_EQ(scene.topology.rest_positions.size(), 10u);
  const ClothNetwork net = scene.build_network();
  ClothState state = scene.initial_state();
  const RelaxReport r = relax(net, state);
  ASSERT_TRUE(r.converged) << r.residual_force << " " << r.last_step;
  const int n = 10;
  const double m = scene.material.node_mass, k = scene.material.spring_constant, g = 9.81;
  const double L = 0.1;
  double y = scene.topology.rest_positions[0].y(), worst = 0;
  for (int i = 0; i < n; ++i) {
    if (i > 0) y -= L + (n - i) * m * g / k;
    worst = std::max(worst, std::abs(state.y[i] - y));
    EXPECT_NEAR(state.x[i], 0.0, 1e-12);
  }
  EXPECT_LT(worst, 1e-6);
  EXPECT_LT(worst, 1e-9);  // what the default tolerance actually delivers
}

TEST(Relaxation, IsTheRestPointOfTheDampedDynamics) {
  // The hanging cloth relaxed, then simulated from rest: nothing moves.
  const Scene scene = test::asset_scene("hanging");
  const ClothNetwork net = scene.build_network();
  ClothState state = scene.initial_state();
  const RelaxReport r = relax(net, state);
  ASSERT_TRUE(r.converged) << "residual " << r.residual_force << " N, last step " << r.last_step
                           << " m";
  EXPECT_LT(net.energy(state).potential(), net.energy(scene.initial_state()).potential());
  Simulation sim(net, state, scene.solver);
  sim.advance(0.2);
  double moved = 0;
  for (std::size_t i = 0; i < state.size(); ++i)
    moved = std::max(moved, (sim.state().position(i) - state.position(i)).norm());
  EXPECT_LT(moved, 1e-6);
}

TEST(Relaxation, ExternalForcesCount) {
  // A horizontal pull on the chain's end tilts it: the end moves the way it is pulled.
  const Scene scene = test::asset_scene("chain");
  ClothNetwork net = scene.build_network();
  ForceInputs pull;
  pull.external_force.resize(net.node_count());
  pull.external_force.x[9] = 0.5;
  ClothState state = scene.initial_state();
  ASSERT_TRUE(relax(net, state, RelaxSettings{}, pull).converged);
  EXPECT_GT(state.x[9], 0.05);
  // Equilibrium at the end node: spring force balances weight and pull.
  NodeVectors F(state.size());
  net.net_forces(state, pull, ForceContext{}, F);
  EXPECT_NEAR(F.at(9).x(), 0.0, 1e-9);
  EXPECT_NEAR(F.at(9).y() - net.mass(9) * 9.81, 0.0, 1e-9);
}

// Nothing free, nothing to relax: converged as it is, with no step (not "did
// NOT converge ... last step inf m").
TEST(Relaxation, AClothWithEveryNodePinnedIsConvergedAsItIs) {
  const Scene scene = test::asset_scene("hanging");
  ClothNetwork net = scene.build_network();
  for (std::size_t i = 0; i < net.node_count(); ++i)
    net.set_pinned(i, true);
  ClothState state = scene.initial_state();
  const ClothState before = state;
  const RelaxReport r = relax(net, state);
  EXPECT_TRUE(r.converged);
  EXPECT_EQ(r.free_nodes, 0u);
  EXPECT_EQ(r.iterations, 0);
  EXPECT_EQ(r.accepted_steps, 0);
  EXPECT_EQ(r.last_step, 0.0);
  EXPECT_EQ(r.residual_force, 0.0);
  EXPECT_EQ(test::state_hash(state), test::state_hash(before));
}

// A report never holds an infinite step, even when no step was accepted.
TEST(Relaxation, ANonConvergedRunReportsFiniteNumbers) {
  const Scene scene = test::asset_scene("hanging");
  const ClothNetwork net = scene.build_network();
  ClothState state = scene.initial_state();
  RelaxSettings settings;
  settings.max_iterations = 1;
  const RelaxReport r = relax(net, state, settings);
  EXPECT_FALSE(r.converged);
  EXPECT_TRUE(std::isfinite(r.last_step));
  EXPECT_TRUE(std::isfinite(r.residual_force));
  EXPECT_GT(r.free_nodes, 0u);
}

}  // namespace
}  // namespace neurocloth
