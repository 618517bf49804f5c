// The self_collision module's single contacts, checked exactly on hand-made
// states: a node that crossed a triangle is brought back, pins take no share,
// a node beside a triangle is not its contact, momentum is kept, and
// degenerate input gives no NaN.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <utility>
#include <vector>

#include "support/self_collision_fixture.h"
#include "support/test_support.h"

namespace neurocloth {
namespace {
using namespace self_collision_test;

// One apply() of a fresh module on hand-made states, for exact checks.
struct OneStep {
  ClothTopology topology;
  ClothNetwork net;
  std::unique_ptr<ConstraintModule> module;
  std::unique_ptr<ModuleState> state;
  explicit OneStep(ClothTopology t)
      : topology(std::move(t)),
        net(ClothNetwork::build(topology, Material{})),
        module(module_for(topology)),
        state(module->make_state()) {}
  void apply(const ClothState& before, ClothState& after) {
    module->apply(net, StepSpan{0.0, 1e-3}, before, after, state.get());
  }
};

// Triangle 0-1-2 in the plane y = 0 (normal +y), node 3 over it.
ClothTopology triangle_and_node(const Vec3& node) {
  ClothTopology t;
  t.rest_positions = {Vec3(0, 0, 0), Vec3(0, 0, 1), Vec3(1, 0, 0), node};
  t.triangles = {{0, 1, 2}};
  return t;
}

// Node `i` against triangle `t` in state `s`: the signed distance along the
// triangle's unit normal, and the relative velocity along it.
struct Gap {
  double distance;
  double normal_velocity;
};
Gap gap(const ClothState& s, const std::array<std::int32_t, 3>& t, std::size_t i) {
  const Vec3 a = s.position(t[0]), e1 = s.position(t[1]) - a, e2 = s.position(t[2]) - a;
  const Vec3 n = e1.cross(e2).normalized();
  const Vec3 d = s.position(i) - a;
  // Barycentric coordinates of the projection, by areas.
  const double area = e1.cross(e2).dot(n);
  const double bv = d.cross(e2).dot(n) / area, bw = e1.cross(d).dot(n) / area;
  const Vec3 vt = (1 - bv - bw) * s.velocity(t[0]) + bv * s.velocity(t[1]) + bw * s.velocity(t[2]);
  return {d.dot(n), n.dot(s.velocity(i) - vt)};
}

Vec3 momentum(const ClothNetwork& net, const ClothState& s) {
  return test::total_momentum(net, s);
}

Vec3 mass_moment(const ClothNetwork& net, const ClothState& s) {
  Vec3 m = Vec3::Zero();
  for (std::size_t i = 0; i < s.size(); ++i)
    m += net.mass(i) * s.position(i);
  return m;
}

TEST(SelfCollision, NodeThatCrossedIsBroughtBackToItsSide) {
  const Vec3 over(0.25, 0.004, 0.25);
  OneStep one(triangle_and_node(over));
  const ClothState before = rest_of(one.topology);
  ClothState after = before;
  after.y[3] = -0.003;  // passed through the triangle during the step
  after.vy[3] = -2.0;
  const Vec3 p0 = momentum(one.net, after), x0 = mass_moment(one.net, after);
  one.apply(before, after);
  ASSERT_TRUE(after.all_finite());
  // Back above, a thickness from the (moved and tilted) plane.
  const Gap g = gap(after, one.topology.triangles[0], 3);
  EXPECT_NEAR(g.distance, kThickness, 1e-12);
  EXPECT_GT(after.y[3], 0.0);
  // The triangle (free, equal masses) took its share, downwards.
  for (int v = 0; v < 3; ++v)
    EXPECT_LT(after.y[v], 0.0);
  // An impulse between the pair: momentum and centre of mass unchanged, and
  // no more closing velocity.
  EXPECT_NEAR((momentum(one.net, after) - p0).norm(), 0.0, 1e-12);
  EXPECT_NEAR((mass_moment(one.net, after) - x0).norm(), 0.0, 1e-12);
  EXPECT_NEAR(g.normal_velocity, 0.0, 1e-9);  // of 2 m/s closing
}

TEST(SelfCollision, PinnedTriangleDoesNotMoveAndNodeTakesItAll) {
  OneStep one(triangle_and_node(Vec3(0.2, 0.002, 0.3)));
  for (std::size_t v = 0; v < 3; ++v)
    one.net.set_pinned(v, true);
  const ClothState before = rest_of(one.topology);
  ClothState after = before;
  after.vy[3] = -1.0;
  after.vx[3] = 0.5;  // sliding: kept
  one.apply(before, after);
  for (std::size_t v = 0; v < 3; ++v) {
    EXPECT_EQ(after.position(v), before.position(v));
    EXPECT_EQ(after.velocity(v), Vec3::Zero());
  }
  EXPECT_NEAR(after.y[3], kThickness, 1e-15);
  EXPECT_NEAR(after.vy[3], 0.0, 1e-15);
  EXPECT_EQ(after.vx[3], 0.5);
}

TEST(SelfCollision, PinnedNodeDoesNotKickAnAlmostPinnedTriangle) {
  // A pinned node under a triangle pinned at two corners, near the pinned edge:
  // opening the whole gap at once would throw the free corner 1 / 0.05 = 20
  // gaps; it may move at most 4 gaps a pass (2 passes).
  OneStep one(triangle_and_node(Vec3(0.05, 0.002, 0.45)));  // barycentric (0.5, 0.45, 0.05)
  for (std::size_t v : {0u, 1u, 3u})
    one.net.set_pinned(v, true);
  const ClothState before = rest_of(one.topology);
  ClothState after = before;
  one.apply(before, after);
  ASSERT_TRUE(after.all_finite());
  for (std::size_t v : {0u, 1u, 3u})
    EXPECT_EQ(after.position(v), before.position(v)) << v;
  const double moved = (after.position(2) - before.position(2)).norm();
  EXPECT_GT(moved, 0.0);
  EXPECT_LE(moved, 2 * 4 * (kThickness - 0.002) + 1e-12);
  EXPECT_LT(after.y[2], 0.0);  // away from the node, which is above
}

TEST(SelfCollision, NodeBesideATriangleIsNotItsContact) {
  // Within thickness of the triangle's edge but not over it: left alone.
  OneStep one(triangle_and_node(Vec3(-0.005, 0.0, 0.5)));
  const ClothState before = rest_of(one.topology);
  ClothState after = before;
  one.apply(before, after);
  EXPECT_EQ(test::state_hash(after), test::state_hash(before));
}

TEST(SelfCollision, FindsANodeThatCreptOverATriangleInSmallSteps) {
  // Node 3 starts beside the (pinned) triangle, too far to be a candidate, and
  // slides towards it 1 mm a step, below the thickness above its plane. The
  // module may reuse its candidates while nodes move little, but must see the
  // node once it is over the triangle.
  OneStep one(triangle_and_node(Vec3(-0.0505, 0.005, 0.5)));
  for (std::size_t v = 0; v < 3; ++v)
    one.net.set_pinned(v, true);
  ClothState state = rest_of(one.topology);
  for (int k = 1; k <= 60; ++k) {
    const ClothState before = state;
    state.x[3] += 0.001;
    one.apply(before, state);
    if (state.x[3] < 0.0)
      ASSERT_EQ(state.y[3], 0.005) << "beside the triangle, step " << k;
    else
      ASSERT_NEAR(state.y[3], kThickness, 1e-15) << "over the triangle, step " << k;
  }
}

TEST(SelfCollision, NodeExactlyOnThePlaneAndDegenerateTrianglesGiveNoNaN) {
  ClothTopology t;
  t.rest_positions = {
      Vec3(0, 0, 0),     Vec3(0, 0, 1), Vec3(1, 0, 0),      // 0-2: a proper triangle
      Vec3(0.2, 0, 0.2),                                    // 3: exactly in its plane
      Vec3(5, 0, 5),                                        // 4: on the degenerate ones
      Vec3(4, 0, 4),     Vec3(6, 0, 6), Vec3(5.5, 0, 5.5),  // 5-7: collinear
      Vec3(5, 0, 5),     Vec3(5, 0, 5), Vec3(5, 0, 5),      // 8-10: one point
  };
  t.triangles = {{0, 1, 2}, {5, 6, 7}, {8, 9, 10}, {8, 8, 6}};
  OneStep one(t);
  const ClothState before = rest_of(t);
  ClothState after = before;
  one.apply(before, after);
  ASSERT_TRUE(after.all_finite());
  // Node 3 had no side: it goes to one, a thickness from the plane.
  EXPECT_NEAR(std::abs(gap(after, t.triangles[0], 3).distance), kThickness, 1e-12);
  // Triangles without a normal push nothing.
  for (std::size_t i = 4; i < after.size(); ++i)
    EXPECT_EQ(after.position(i), before.position(i)) << i;

  // A state gone non-finite (a diverged run) is left for the divergence check.
  ClothState bad = before;
  bad.x[1] = std::numeric_limits<double>::quiet_NaN();
  bad.y[4] = std::numeric_limits<double>::infinity();
  ClothState out = bad;
  one.apply(before, out);
  EXPECT_EQ(test::state_hash(out), test::state_hash(bad));
}

}  // namespace
}  // namespace neurocloth
