// Tests of the self_collision module on whole cloths: layers of one cloth kept
// apart, nothing changed where nothing is near, sliding without sticking, and
// the module present only when a scene declares it. Single contacts, exactly:
// self_collision_contact_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/modules/module_factories.h"
#include "core/scene/scene.h"
#include "support/scene_builder.h"
#include "support/self_collision_fixture.h"
#include "support/test_support.h"

namespace neurocloth {
namespace {
using namespace self_collision_test;

SolverSettings fixed_steps(double dt = 1e-3) {
  SolverSettings s;
  s.integrator = IntegratorKind::network;
  s.dt = dt;
  s.adaptive = false;
  return s;
}

using Constraints = std::vector<std::shared_ptr<const ConstraintModule>>;

Constraints self_collision(const ClothTopology& topology, double thickness = kThickness) {
  Constraints modules;
  modules.push_back(module_for(topology, thickness));
  return modules;
}

// A U-folded strip: rows 0..N-1 lie flat at y = 0 (the bottom layer, pinned),
// rows N..2N-1 come back over them at y = gap (the top layer, free), joined by
// the strip of springs and triangles between rows N-1 and N (the fold). Bend
// springs that would reach across the fold are removed. The top layer is drawn
// at 70% of the bottom's size, centred in x: contact is frictionless, and a
// top layer as wide as the bottom one would slide off its edges as it lands.
struct FoldedCloth {
  static constexpr int kCols = 8, kLayerRows = 8;
  static constexpr double kSpacing = 0.02, kGap = 0.04, kTop = 0.7;
  ClothTopology topology;
  std::vector<int> bottom, top;

  FoldedCloth() {
    GridSpec g;
    g.rows = 2 * kLayerRows;
    g.cols = kCols;
    g.spacing = kSpacing;
    topology = build_grid(g);
    const int N = kLayerRows;
    for (int r = 0; r < 2 * N; ++r)
      for (int c = 0; c < kCols; ++c) {
        const int i = r * kCols + c;
        const bool lower = r < N;
        const double x = lower ? c * kSpacing : (0.15 * (kCols - 1) + kTop * c) * kSpacing;
        const double z = lower ? r * kSpacing : (N - 1 - kTop * (r - N)) * kSpacing;
        topology.rest_positions[i] = Vec3(x, lower ? 0.0 : kGap, z);
        (lower ? bottom : top).push_back(i);
      }
    auto row = [](int node) { return node / kCols; };
    auto& sp = topology.springs;
    sp.erase(std::remove_if(sp.begin(), sp.end(),
                            [&](const SpringSpec& s) {
                              const int lo = std::min(row(s.a), row(s.b));
                              const int hi = std::max(row(s.a), row(s.b));
                              return s.family == SpringFamily::bend && lo < N && hi >= N;
                            }),
             sp.end());
  }

  ClothNetwork network() const {
    Material m;
    m.spring_constant = 50.0;
    m.node_mass = 0.01;
    m.viscosity = 0.05;
    ClothNetwork net = ClothNetwork::build(topology, m);
    for (int i : bottom)
      net.set_pinned(static_cast<std::size_t>(i), true);
    return net;
  }

  ClothState run(bool with_module, double seconds) const {
    Simulation sim(network(), rest_of(topology), fixed_steps(),
                   with_module ? self_collision(topology) : Constraints{});
    EXPECT_EQ(sim.advance(seconds), RunStatus::ok) << sim.divergence_reason();
    return sim.state();
  }
};

double min_y(const ClothState& s, const std::vector<int>& nodes) {
  double m = std::numeric_limits<double>::infinity();
  for (int i : nodes)
    m = std::min(m, s.y[static_cast<std::size_t>(i)]);
  return m;
}

TEST(SelfCollision, FoldedLayersFallThroughEachOtherWithoutTheModule) {
  const FoldedCloth cloth;
  const ClothState s = cloth.run(false, 1.0);
  ASSERT_TRUE(s.all_finite());
  // The top layer swings down through the pinned bottom one and hangs below it.
  EXPECT_LT(min_y(s, cloth.top), -0.5 * FoldedCloth::kLayerRows * FoldedCloth::kSpacing);
}

TEST(SelfCollision, FoldedLayersStayApartWithTheModule) {
  const FoldedCloth cloth;
  const ClothState s = cloth.run(true, 1.0);
  ASSERT_TRUE(s.all_finite());
  const int N = FoldedCloth::kLayerRows, C = FoldedCloth::kCols;
  for (int i : cloth.top) {
    const auto n = static_cast<std::size_t>(i);
    EXPECT_GE(s.y[n], 0.9 * kThickness) << "top-layer node " << i;
    // Still over the bottom layer (which spans x, z in [0, (C-1) h] x [0, (N-1) h]).
    EXPECT_GE(s.x[n], -1e-9);
    EXPECT_LE(s.x[n], (C - 1) * FoldedCloth::kSpacing + 1e-9);
    EXPECT_GE(s.z[n], -1e-9);
    EXPECT_LE(s.z[n], (N - 1) * FoldedCloth::kSpacing + 1e-9);
  }
  // It did come down: the free edge (the last row) rests on the bottom layer.
  for (int c = 0; c < C; ++c) {
    const auto n = static_cast<std::size_t>((2 * N - 1) * C + c);
    EXPECT_LT(s.y[n], 2.0 * kThickness) << "free-edge node " << n;
  }
  // The bottom layer is pinned: the module must not have moved it.
  for (int i : cloth.bottom)
    EXPECT_EQ(s.y[static_cast<std::size_t>(i)], 0.0);
}

// A square grid in the x-z plane with the three spring families.
ClothTopology flat_grid(int n, double spacing) {
  GridSpec g;
  g.rows = g.cols = n;
  g.spacing = spacing;
  return build_grid(g);
}

// Runs the same cloth with and without the module; returns both final states.
std::pair<ClothState, ClothState> with_and_without(const ClothNetwork& net,
                                                   const ClothTopology& topology,
                                                   const ClothState& start, double thickness,
                                                   double seconds) {
  Simulation bare(net, start, fixed_steps());
  Simulation with(net, start, fixed_steps(), self_collision(topology, thickness));
  EXPECT_EQ(bare.advance(seconds), RunStatus::ok);
  EXPECT_EQ(with.advance(seconds), RunStatus::ok);
  return {bare.state(), with.state()};
}

TEST(SelfCollision, SwingingFlatClothIsUnchanged) {
  // A horizontal cloth pinned along its first row swings down: it moves a lot
  // but never comes near itself.
  const ClothTopology t = flat_grid(10, 0.05);
  Material m;
  m.spring_constant = 100.0;
  ClothNetwork net = ClothNetwork::build(t, m);
  for (std::size_t c = 0; c < 10; ++c)
    net.set_pinned(c, true);
  const ClothState start = rest_of(t);
  const auto [bare, with] = with_and_without(net, t, start, kThickness, 0.5);
  EXPECT_LT(min_y(bare, {99}), -0.2);  // it did swing
  EXPECT_EQ(test::state_hash(bare), test::state_hash(with));
}

TEST(SelfCollision, InPlaneNeighboursAreNotContacts) {
  // Thicker than a node's distance to its nearest triangle not its own
  // (spacing / sqrt 2): a module that took in-plane neighbours for contacts
  // would lift nodes out of the plane. The cloth starts stretched unevenly in
  // its plane and vibrates there, without gravity.
  const double h = 0.05;
  const ClothTopology t = flat_grid(8, h);
  ClothNetwork net = ClothNetwork::build(t, Material{});
  net.gravity = Vec3::Zero();
  ClothState start = rest_of(t);
  for (std::size_t i = 0; i < start.size(); ++i) {
    start.x[i] += 0.1 * h * std::sin(3.0 * static_cast<double>(i));
    start.z[i] += 0.1 * h * std::cos(5.0 * static_cast<double>(i));
  }
  const auto [bare, with] = with_and_without(net, t, start, 0.8 * h, 0.3);
  EXPECT_NE(test::state_hash(bare), test::state_hash(start));  // it did move
  EXPECT_EQ(test::state_hash(bare), test::state_hash(with));
}

// A pinned square layer tilted down the slope by `angle` about the x axis, and
// one free node (the last index, in no triangle) resting on it at `height`
// along the layer's upward normal.
struct Slope {
  static constexpr int kN = 12;
  static constexpr double kSpacing = 0.05;
  ClothTopology topology;
  Vec3 down_slope, normal, origin;
  std::size_t node = 0;

  Slope(double angle, double height) {
    GridSpec g;
    g.rows = g.cols = kN;
    g.spacing = kSpacing;
    down_slope = Vec3(0, -std::sin(angle), std::cos(angle));
    g.row_direction = down_slope;
    g.col_direction = Vec3::UnitX();
    topology = build_grid(g);
    normal = Vec3(0, std::cos(angle), std::sin(angle));  // unit, up the slope's face
    origin = Vec3::Zero();
    node = topology.rest_positions.size();
    const double side = (kN - 1) * kSpacing;
    topology.rest_positions.push_back(0.5 * side * Vec3::UnitX() + 0.15 * side * down_slope +
                                      height * normal);
  }
  ClothNetwork network() const {
    ClothNetwork net = ClothNetwork::build(topology, Material{});
    for (std::size_t i = 0; i < node; ++i)
      net.set_pinned(i, true);
    return net;
  }
  double height(const ClothState& s) const { return (s.position(node) - origin).dot(normal); }
  double along(const ClothState& s) const { return (s.position(node) - origin).dot(down_slope); }
};

TEST(SelfCollision, NodeSlidesFreelyDownALayer) {
  const double angle = 0.3;  // rad
  const Slope slope(angle, kThickness);
  ClothNetwork net = slope.network();
  const ClothState start = rest_of(slope.topology);
  Simulation sim(net, start, fixed_steps(), self_collision(slope.topology));
  const double e0 = sim.energy().total();
  const double T = 0.3;
  for (int k = 0; k < 30; ++k) {
    ASSERT_EQ(sim.advance(T / 30), RunStatus::ok);
    const double e = sim.energy().total();
    ASSERT_TRUE(std::isfinite(e));
    EXPECT_LE(e, e0 + 1e-6) << "contact added energy at step " << k;
    // Held on the layer: neither through it nor thrown off it.
    EXPECT_GE(slope.height(sim.state()), 0.9 * kThickness) << k;
    EXPECT_LE(slope.height(sim.state()), 1.5 * kThickness) << k;
  }
  // Frictionless: it slides g sin(angle) t^2 / 2, over many triangle edges.
  const double expected = 0.5 * 9.81 * std::sin(angle) * T * T;
  EXPECT_NEAR(slope.along(sim.state()) - slope.along(start), expected, 0.05 * expected);
  EXPECT_NEAR(sim.state().x[slope.node], start.x[slope.node], 1e-9);
}

TEST(SelfCollision, AllocatesOnceAndReportsItsState) {
  const ClothTopology t = flat_grid(6, 0.05);
  const auto module = module_for(t);
  EXPECT_STREQ(module->type(), "self_collision");
  EXPECT_EQ(module->phase(), ConstraintModule::self_contact);
  const std::size_t bytes = module->state_bytes();
  EXPECT_GE(bytes, t.triangles.size() * 3 * sizeof(std::int32_t));
  const auto state = module->make_state();
  const std::size_t state_bytes = state->bytes();
  EXPECT_GT(state_bytes, 0u);
  // Steps in contact and out of it: the buffers sized at build suffice.
  ClothNetwork net = ClothNetwork::build(t, Material{});
  const ClothState before = rest_of(t);
  for (int k = 0; k < 3; ++k) {
    // Corner node 0 thrown over a triangle far from its own, within thickness.
    ClothState after = before;
    after.set_position(0, Vec3(0.17, 0.003 * (k - 1), 0.16));
    module->apply(net, StepSpan{0.0, 1e-3}, before, after, state.get());
    EXPECT_NE(after.y[0], 0.003 * (k - 1)) << "no contact in round " << k;
  }
  EXPECT_EQ(module->state_bytes(), bytes);
  EXPECT_EQ(state->bytes(), state_bytes);
}

// A 5 x 5 square of structural springs pinned at a corner.
test::SceneBuilder square() {
  return test::SceneBuilder(5, 5, 0.1).name("square").springs({"structural"}).pins({{0, 0}});
}

TEST(SelfCollision, PresentOnlyWhenDeclared) {
  Simulation bare = square().parse("square.json").make_simulation();
  EXPECT_EQ(bare.module_count(), 0u);
  EXPECT_TRUE(bare.module_reports().empty());

  Simulation with = square()
                        .module({{"type", "self_collision"}, {"thickness", 0.02}})
                        .parse("square.json")
                        .make_simulation();
  ASSERT_EQ(with.module_count(), 1u);
  const auto reports = with.module_reports();
  ASSERT_EQ(reports.size(), 1u);
  EXPECT_EQ(reports[0].type, "self_collision");
  EXPECT_GT(reports[0].state_bytes, 0u);
  EXPECT_NE(reports[0].declaration.find("0.02"), std::string::npos);
  ASSERT_EQ(with.advance(0.01), RunStatus::ok);
  EXPECT_GT(with.module_reports()[0].calls, 0);
}

TEST(SelfCollision, RejectsWhatCannotWork) {
  const ClothTopology t = flat_grid(3, 0.1);
  SelfCollisionSpec spec;
  spec.thickness = 0.0;
  EXPECT_THROW(make_self_collision(spec, t), std::invalid_argument);
  spec = SelfCollisionSpec{};
  spec.iterations = 0;
  EXPECT_THROW(make_self_collision(spec, t), std::invalid_argument);
  ClothTopology bad = t;
  bad.triangles.push_back({0, 1, 99});
  EXPECT_THROW(make_self_collision(SelfCollisionSpec{}, bad), std::invalid_argument);
}

}  // namespace
}  // namespace neurocloth
