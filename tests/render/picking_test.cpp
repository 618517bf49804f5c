// Picking is pure math on a snapshot: the shipped hanging cloth at rest is a
// flat 20 x 20 grid at y = 1 (spacing 0.05 m), seen from known cameras.
#include "render/picking.h"

#include <gtest/gtest.h>

#include "support/render_test_support.h"

namespace neurocloth {
namespace {

using render_test::scene_snapshot;
constexpr int kPickWidth = 800, kPickHeight = 600;

// Straight down onto the middle of the flat cloth.
OrbitCamera looking_down() {
  OrbitCamera c;
  c.yaw = 0;
  c.pitch = 1.5707;
  c.distance = 2;
  c.target = Vec3(0.475, 1, 0.475);
  return c;
}

OrbitCamera oblique() {
  OrbitCamera c;
  c.yaw = 0.7;
  c.pitch = 0.6;
  c.distance = 2.2;
  c.target = Vec3(0.475, 1, 0.475);
  return c;
}

TEST(Picking, TheRayThroughANodesPixelPicksThatNode) {
  const FrameSnapshot s = scene_snapshot("hanging", 0);
  ASSERT_EQ(s.position.size(), 3u * 400);
  for (const OrbitCamera& c : {looking_down(), oblique()}) {
    int picked = 0;
    for (std::size_t k = 0; k < 400; ++k) {
      double px, py;
      ASSERT_TRUE(c.project(s.node(k), kPickWidth, kPickHeight, px, py));
      const Pick p = pick_node(c.ray(px, py, kPickWidth, kPickHeight), s, 0.01);
      EXPECT_EQ(p.node, int(k));
      EXPECT_LT((p.point - s.node(k)).norm(), 1e-6);
      EXPECT_NEAR(p.ray_t, (s.node(k) - c.eye()).norm(), 1e-6);
      picked += p.node == int(k);
    }
    EXPECT_EQ(picked, 400);
  }
}

TEST(Picking, AHitInsideATrianglePicksItsNearestCorner) {
  const FrameSnapshot s = scene_snapshot("hanging", 0);
  const OrbitCamera c = looking_down();
  // A point a fifth of the way from node 21 (row 1, col 1) towards node 22: node 21 is nearest.
  const Vec3 p = s.node(21) + 0.2 * (s.node(22) - s.node(21)) + 0.1 * (s.node(41) - s.node(21));
  double px, py;
  ASSERT_TRUE(c.project(p, kPickWidth, kPickHeight, px, py));
  const Pick pick = pick_node(c.ray(px, py, kPickWidth, kPickHeight), s, 0.0);
  EXPECT_EQ(pick.node, 21);
  EXPECT_LT((pick.point - p).norm(), 1e-6);
}

TEST(Picking, TheNearerLayerWinsWhereTheClothOverlapsItself) {
  FrameSnapshot s = scene_snapshot("hanging", 0);
  // Lift the far half (rows 10..19) 0.2 m and slide it over the near half: seen
  // from above, the lifted rows are in front.
  for (std::size_t i = 200; i < 400; ++i) {
    s.position[3 * i + 1] += 0.2f;
    s.position[3 * i + 2] -= 0.5f;
  }
  const OrbitCamera c = looking_down();
  double px, py;
  ASSERT_TRUE(c.project(s.node(5 * 20 + 5), kPickWidth, kPickHeight, px, py));  // under row 15
  const Pick p = pick_node(c.ray(px, py, kPickWidth, kPickHeight), s, 0.01);
  EXPECT_GE(p.node, 200);
  EXPECT_NEAR(p.point.y(), 1.2, 1e-6);
}

TEST(Picking, AMissPicksNothingOrTheNearestNodeWithinTolerance) {
  const FrameSnapshot s = scene_snapshot("hanging", 0);
  const OrbitCamera c = looking_down();
  // A ray down past the corner (0, 1, 0), 0.03 m outside the cloth in x.
  const Ray beside{Vec3(-0.03, 3, 0), Vec3(0, -1, 0)};
  EXPECT_EQ(pick_node(beside, s, 0.01).node, -1);
  const Pick near = pick_node(beside, s, 0.05);
  EXPECT_EQ(near.node, 0);
  EXPECT_EQ(near.point, s.node(0));
  EXPECT_NEAR(near.ray_t, 2, 1e-6);
  // Away from the cloth entirely, or pointing away from it.
  EXPECT_EQ(pick_node(c.ray(2, 2, kPickWidth, kPickHeight), s, 0.01).node, -1);
  EXPECT_EQ(pick_node({Vec3(0.5, 3, 0.5), Vec3(0, 1, 0)}, s, 10.0).node, -1);
  // A snapshot without triangles still picks by distance to the ray.
  FrameSnapshot bare = s;
  bare.geometry.reset();
  EXPECT_EQ(pick_node({Vec3(0.05, 3, 0.001), Vec3(0, -1, 0)}, bare, 0.01).node, 1);
}

TEST(Picking, TheDragPointLiesOnTheRayAndOnThePlaneFacingTheCamera) {
  for (const OrbitCamera& c : {looking_down(), oblique()}) {
    const Vec3 anchor(0.3, 1.0, 0.6);
    for (const auto& [px, py] : std::vector<std::pair<double, double>>{
             {400, 300}, {10, 20}, {790, 590}, {123.5, 456.25}}) {
      const Ray r = c.ray(px, py, kPickWidth, kPickHeight);
      const Vec3 d = drag_point(r, anchor, c);
      EXPECT_NEAR((d - anchor).dot(c.forward()), 0, 1e-9);
      const double t = (d - r.origin).dot(r.direction);
      EXPECT_LT((r.origin + t * r.direction - d).norm(), 1e-9);
    }
    // The ray through the anchor's own pixel leaves it where it is.
    double px, py;
    ASSERT_TRUE(c.project(anchor, kPickWidth, kPickHeight, px, py));
    EXPECT_LT((drag_point(c.ray(px, py, kPickWidth, kPickHeight), anchor, c) - anchor).norm(),
              1e-9);
  }
}

}  // namespace
}  // namespace neurocloth
