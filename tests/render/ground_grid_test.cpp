// The ground grid lies at y = 0 or below the scene, or on a floor plane.
#include "render/ground_grid.h"

#include <gtest/gtest.h>

#include <utility>

#include "render/snapshot_framing.h"
#include "support/render_test_support.h"

namespace neurocloth {
namespace {

using render_test::scene_snapshot;

TEST(GroundGrid, LiesAtZeroUnderAClothAboveIt) {
  const GroundGrid g = place_ground_grid(scene_snapshot("table_drape", 0));
  EXPECT_EQ(g.centre.y(), 0.0);
  EXPECT_DOUBLE_EQ(g.cell, 0.1);  // a scene a metre or so across
  EXPECT_GT(g.half_size(), 2.0);
}

TEST(GroundGrid, GoesBelowAClothThatReachesUnderZero) {
  FrameSnapshot s = scene_snapshot("hanging", 0);
  s.position[1] = -0.7f;
  EXPECT_FLOAT_EQ(float(place_ground_grid(s).centre.y()), -0.7f);
}

TEST(GroundGrid, LiesOnAFloorPlane) {
  FrameSnapshot s = scene_snapshot("hanging", 0);
  auto g = std::make_shared<SceneGeometry>(*s.geometry);
  PlaneSpec floor;
  floor.point = Vec3(0, 0.3, 0);
  g->colliders.emplace_back(std::in_place_type<PlaneSpec>, floor);
  s.geometry = g;
  EXPECT_DOUBLE_EQ(place_ground_grid(s).centre.y(), 0.3);
}

TEST(GroundGrid, TheSquareSpansTheGrid) {
  GroundGrid g;
  g.cells = 4;
  g.cell = 0.5;
  g.centre = Vec3(1, 0.25, 2);
  const std::vector<float> v = ground_grid_square(g);
  ASSERT_EQ(v.size(), 12u);
  const std::vector<float> expected = {0, 0.25, 1, 2, 0.25, 1, 0, 0.25, 3, 2, 0.25, 3};
  for (std::size_t i = 0; i < v.size(); ++i)
    EXPECT_FLOAT_EQ(v[i], expected[i]) << i;
}

TEST(GroundGrid, CoversTheSceneManyTimesOver) {
  for (const char* name : {"table_drape", "hanging", "sphere_drop", "chain"}) {
    const FrameSnapshot s = scene_snapshot(name, 0);
    const GroundGrid g = place_ground_grid(s);
    const Bounds b = snapshot_bounds(s);
    const double size = (b.hi - b.lo).maxCoeff();
    EXPECT_GE(g.half_size(), 3.5 * size) << name;
    EXPECT_LE(g.cell, size) << name;
    EXPECT_GE(g.cell, size / 100) << name;
    EXPECT_EQ(g.cells % 20, 0) << name;
  }
}

}  // namespace
}  // namespace neurocloth
