// Provot's strain limit: every limited spring at or under max_stretch times its
// rest length after each step, corrections that respect pins and momentum.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "core/modules/module_factories.h"
#include "core/scene/scene.h"
#include "support/scene_builder.h"
#include "support/test_support.h"

namespace neurocloth {
namespace {

// A soft 12 x 12 cloth hanging from its whole top row: at rest its top springs
// stretch by about 30%, so a 10% limit has work to do on every step.
std::string hanging_scene(const std::string& integrator, const std::string& modules) {
  return test::SceneBuilder(12, 12, 0.05)
      .origin(Vec3(0, 1, 0))
      .hanging()
      .pin_top_row()
      .material(15.0, 0.01, 0.05)
      .set("/material/bend_constant", 2.0)
      .solver(integrator, 0.001)
      .modules("[" + modules + "]")
      .text();
}

// Largest length / rest length over the springs of the given families.
double max_stretch(const Simulation& sim, bool structural, bool shear, bool bend) {
  const SpringLayer& L = sim.network().springs;
  const bool want[3] = {structural, shear, bend};
  double worst = 0;
  for (std::size_t k = 0; k < L.size(); ++k) {
    if (!want[static_cast<int>(L.family[k])]) continue;
    const double len =
        (sim.state().position(L.node_b[k]) - sim.state().position(L.node_a[k])).norm();
    worst = std::max(worst, len / L.rest_length[k]);
  }
  return worst;
}

TEST(StrainLimit, WithoutItTheSoftCurtainOverstretches) {
  Simulation sim = parse_scene(hanging_scene("network", ""), "t.json").make_simulation();
  sim.advance(1.0);
  EXPECT_GT(max_stretch(sim, true, true, false), 1.2);
}

TEST(StrainLimit, EverySpringStaysAtOrUnderTheLimitAfterEveryStep) {
  for (const char* integrator : {"network", "rk4", "implicit_euler"}) {
    SCOPED_TRACE(integrator);
    Simulation sim =
        parse_scene(hanging_scene(integrator, R"({"type": "strain_limit", "max_stretch": 1.1})"),
                    "t.json")
            .make_simulation();
    double worst = 0;
    for (int step = 0; step < 600; ++step) {
      sim.advance(0.001);
      worst = std::max(worst, max_stretch(sim, true, true, false));
    }
    ASSERT_EQ(sim.status(), RunStatus::ok);
    EXPECT_LE(worst, 1.1 * (1 + 1e-9));
    EXPECT_GT(worst, 1.1 * (1 - 1e-3));  // the limit is reached, not just never approached
  }
}

TEST(StrainLimit, ListedFamiliesOnly) {
  Simulation sim = parse_scene(hanging_scene("network",
                                             R"({"type": "strain_limit", "max_stretch": 1.1,
                                                 "families": ["shear"]})"),
                               "t.json")
                       .make_simulation();
  sim.advance(0.5);
  EXPECT_LE(max_stretch(sim, false, true, false), 1.1 * (1 + 1e-9));
  EXPECT_GT(max_stretch(sim, true, false, false), 1.1);
}

// Two free nodes flying apart: one correction puts the spring at its limit,
// moves each end by the same amount (equal masses) and keeps the momentum.
TEST(StrainLimit, OneCorrectionKeepsMomentumAndMovesVelocities) {
  ClothTopology t;
  t.rest_positions = {Vec3(0, 0, 0), Vec3(1, 0, 0)};
  t.springs = {{0, 1, SpringFamily::structural}};
  const ClothNetwork net = ClothNetwork::build(t, Material{});
  StrainLimitSpec spec;
  spec.max_stretch = 1.5;
  auto module = make_strain_limit(spec, t);
  auto state = module->make_state();
  ClothState before = net.rest_state(t.rest_positions), after = before;
  after.set_position(0, Vec3(-0.5, 0, 0));
  after.set_position(1, Vec3(1.5, 0.1, 0));
  after.set_velocity(0, Vec3(-5, 0, 0));
  after.set_velocity(1, Vec3(5, 1, 0));
  const Vec3 p0 = test::total_momentum(net, after);
  const double h = 0.1;
  module->apply(net, StepSpan{0, h}, before, after, state.get());
  EXPECT_NEAR((after.position(1) - after.position(0)).norm(), 1.5, 1e-12);
  EXPECT_NEAR((test::total_momentum(net, after) - p0).norm(), 0, 1e-12);
  // v changed by exactly the position correction over the step.
  const Vec3 moved = after.position(0) - Vec3(-0.5, 0, 0);
  EXPECT_NEAR((after.velocity(0) - (Vec3(-5, 0, 0) + moved / h)).norm(), 0, 1e-12);
  EXPECT_GT(moved.x(), 0.0);
}

// A chain hanging from a pin: the pinned node never moves, and the correction
// reaches the bottom in one step (pins first, each spring moving its far end).
TEST(StrainLimit, PinsNeverMoveAndAChainIsFixedInOneStep) {
  ClothTopology t;
  const int n = 30;
  for (int i = 0; i < n; ++i)
    t.rest_positions.push_back(Vec3(0, -0.1 * i, 0));
  for (int i = 0; i + 1 < n; ++i)
    t.springs.push_back({i, i + 1, SpringFamily::structural});
  ClothNetwork net = ClothNetwork::build(t, Material{});
  net.set_pinned(0, true);
  StrainLimitSpec spec;
  spec.max_stretch = 1.1;
  spec.iterations = 2;  // one sweep down, one back
  auto module = make_strain_limit(spec, t);
  auto state = module->make_state();
  ClothState before = net.rest_state(t.rest_positions), after = before;
  for (int i = 0; i < n; ++i)
    after.set_position(i, Vec3(0, -0.15 * i, 0));  // every spring 50% long
  module->apply(net, StepSpan{0, 0.01}, before, after, state.get());
  EXPECT_EQ(after.position(0), Vec3(0, 0, 0));
  for (int i = 0; i + 1 < n; ++i)
    EXPECT_LE((after.position(i + 1) - after.position(i)).norm(), 0.11 * (1 + 1e-12)) << i;
  // Unpinning the top re-plans: the same over-long chain now shares the
  // correction, so the top node moves.
  net.set_pinned(0, false);
  for (int i = 0; i < n; ++i)
    after.set_position(i, Vec3(0, -0.15 * i, 0));
  module->apply(net, StepSpan{0, 0.01}, before, after, state.get());
  EXPECT_LT(after.position(0).y(), 0.0);
}

}  // namespace
}  // namespace neurocloth
