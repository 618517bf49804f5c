// The ground grid lies at y = 0 or below the scene, or on a floor plane.
#include "ground_grid.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "render_test_support.h"
#include "snapshot_framing.h"

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
  g->colliders.push_back(floor);
  s.geometry = g;
  EXPECT_DOUBLE_EQ(place_ground_grid(s).centre.y(), 0.3);
}

// Every line at a cell boundary, both directions, tiled end to end by its
// segments (the last one shorter), each segment two triangles spanning both
// sides of the line, the side vector across the line.
TEST(GroundGrid, StripsFollowEveryLineEndToEnd) {
  GroundGrid g;
  g.cells = 4;
  g.cell = 0.5;
  g.centre = Vec3(1, 0.25, 2);
  const int per = 3;  // segments of 3 cells and 1 cell
  const std::vector<float> v = ground_grid_strips(g, per);
  const std::size_t vertices = v.size() / kGridFloatsPerVertex;
  ASSERT_EQ(v.size() % kGridFloatsPerVertex, 0u);
  ASSERT_EQ(vertices, std::size_t(2 * 5 * 2 * 6));
  // For each direction (the axis a line is fixed on) and line: the stretches covered.
  std::map<std::pair<int, int>, std::vector<std::pair<double, double>>> covered;
  for (std::size_t q = 0; q < vertices / 6; ++q) {
    const float* f = &v[q * 6 * kGridFloatsPerVertex];
    auto at = [&](int vertex, int i) { return double(f[vertex * kGridFloatsPerVertex + i]); };
    const int across = at(0, 3) != 0 ? 0 : 2, along = 2 - across;
    double lo = 1e9, hi = -1e9;
    int minus = 0, plus = 0;
    for (int k = 0; k < 6; ++k) {
      EXPECT_FLOAT_EQ(float(at(k, 1)), 0.25f);
      EXPECT_EQ(at(k, 4), 0.0);
      EXPECT_EQ(at(k, 3 + along), 0.0);
      EXPECT_EQ(std::abs(at(k, 3 + across)), 1.0);
      (at(k, 3 + across) < 0 ? minus : plus)++;
      EXPECT_DOUBLE_EQ(at(k, across), at(0, across));  // one line
      lo = std::min(lo, at(k, along));
      hi = std::max(hi, at(k, along));
    }
    EXPECT_EQ(minus, 3);
    EXPECT_EQ(plus, 3);
    const double offset = (at(0, across) - g.centre[across] + g.half_size()) / g.cell;
    EXPECT_NEAR(offset, std::round(offset), 1e-6) << "off the lines";
    covered[{across, int(std::lround(offset))}].push_back(
        {lo - g.centre[along], hi - g.centre[along]});
  }
  ASSERT_EQ(covered.size(), 10u);
  for (auto& [line, stretches] : covered) {
    std::sort(stretches.begin(), stretches.end());
    ASSERT_EQ(stretches.size(), 2u);
    EXPECT_NEAR(stretches[0].first, -1.0, 1e-6);
    EXPECT_NEAR(stretches[0].second, 0.5, 1e-6);
    EXPECT_NEAR(stretches[1].first, 0.5, 1e-6);
    EXPECT_NEAR(stretches[1].second, 1.0, 1e-6);
  }
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
