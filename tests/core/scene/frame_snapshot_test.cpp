// What the renderer is given of a scene (frame_snapshot.h): the coarse
// triangles a large grid is also drawn with, on grids whose rows and columns
// differ (tests/render/renderer_test.cpp draws them, on square grids), and
// where the colliders are at the snapshot's moment.
#include "core/scene/frame_snapshot.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "core/modules/collider_motion.h"
#include "core/scene/scene.h"
#include "support/scene_builder.h"
#include "support/test_support.h"
#include "support/triangle_meshes.h"

namespace neurocloth {
namespace {

// 0, 2, 4, ... and the last: the rows (or columns) a coarse grid keeps.
std::vector<int> coarse_lines(int count) {
  std::vector<int> kept;
  for (int k = 0; k < count; k += 2)
    kept.push_back(k);
  if (kept.back() != count - 1) kept.push_back(count - 1);
  return kept;
}

// A grid of `rows` x `cols` nodes whose coarse triangles are checked against
// where its nodes are: each triangle's corners on kept rows and columns, one
// coarse cell a triangle, wound as the full mesh, covering the cloth once.
void expect_coarse_grid(int rows, int cols) {
  SCOPED_TRACE(std::to_string(rows) + " x " + std::to_string(cols));
  const double spacing = 0.01;
  const Scene scene = test::SceneBuilder(rows, cols, spacing).hanging().parse();
  const auto g = make_geometry(scene);
  const std::vector<int> kept_rows = coarse_lines(rows), kept_cols = coarse_lines(cols);
  ASSERT_EQ(g->coarse_triangles.size(), 2 * (kept_rows.size() - 1) * (kept_cols.size() - 1));

  // A node's row and column from its rest position: rows run down -y from the
  // origin, columns along +x (SceneBuilder::hanging).
  const auto& p = scene.topology.rest_positions;
  auto place = [&](std::int32_t i) {
    return std::pair<int, int>{int(std::lround(-p[std::size_t(i)].y() / spacing)),
                               int(std::lround(p[std::size_t(i)].x() / spacing))};
  };
  auto kept_index = [](const std::vector<int>& kept, int line) {
    for (std::size_t k = 0; k < kept.size(); ++k)
      if (kept[k] == line) return int(k);
    return -1;
  };
  auto normal = [&](const std::array<std::int32_t, 3>& t) {
    return (p[t[1]] - p[t[0]]).cross(p[t[2]] - p[t[0]]).normalized();
  };
  const Vec3 facing = normal(g->triangles.front());
  std::set<std::pair<int, int>> corners;
  std::set<std::pair<int, int>> halves;  // (coarse cell, which half)
  double area = 0;
  for (const auto& t : g->coarse_triangles) {
    int row_lo = rows, row_hi = -1, col_lo = cols, col_hi = -1;
    for (const std::int32_t i : t) {
      ASSERT_TRUE(i >= 0 && std::size_t(i) < p.size());
      const auto [r, c] = place(i);
      ASSERT_GE(kept_index(kept_rows, r), 0) << "row " << r << " is not kept";
      ASSERT_GE(kept_index(kept_cols, c), 0) << "column " << c << " is not kept";
      corners.insert({r, c});
      row_lo = std::min(row_lo, r);
      row_hi = std::max(row_hi, r);
      col_lo = std::min(col_lo, c);
      col_hi = std::max(col_hi, c);
    }
    // Within one coarse cell: two neighbouring kept rows and columns.
    const int cell_row = kept_index(kept_rows, row_lo), cell_col = kept_index(kept_cols, col_lo);
    EXPECT_EQ(kept_index(kept_rows, row_hi), cell_row + 1);
    EXPECT_EQ(kept_index(kept_cols, col_hi), cell_col + 1);
    const int cell = cell_row * int(kept_cols.size()) + cell_col;
    const int half = place(t[0]) == std::pair<int, int>{row_lo, col_lo} ? 0 : 1;
    EXPECT_TRUE(halves.insert({cell, half}).second) << "cell " << cell << " half " << half;
    EXPECT_GT(normal(t).dot(facing), 0.999);
    area += 0.5 * (p[t[1]] - p[t[0]]).cross(p[t[2]] - p[t[0]]).norm();
  }
  EXPECT_EQ(corners.size(), kept_rows.size() * kept_cols.size());
  // The whole cloth, no more: every cell's two halves are there and do not overlap.
  const double whole = spacing * spacing * (rows - 1) * (cols - 1);
  EXPECT_NEAR(area, whole, 1e-9 * whole);
}

// Long in one direction, short in the other, and each with an even count
// (whose last line is kept beside the every-other ones) and an odd one.
TEST(CoarseTriangles, FollowTheGridOnANonSquareGrid) {
  ASSERT_GT(163, kCoarseGridFrom);
  expect_coarse_grid(6, 163);
  expect_coarse_grid(162, 7);
}

// Below kCoarseGridFrom rows and columns there are none: the window draws
// every triangle.
TEST(CoarseTriangles, NoneForAGridUpToTheirSize) {
  EXPECT_TRUE(make_geometry(test::SceneBuilder(kCoarseGridFrom, 7, 0.01).hanging().parse())
                  ->coarse_triangles.empty());
  EXPECT_FALSE(make_geometry(test::SceneBuilder(kCoarseGridFrom + 1, 7, 0.01).hanging().parse())
                   ->coarse_triangles.empty());
}

// A geometry of one collider of each kind: a still plane, a rotated box, a
// sphere moved by keys, and a mesh deformed by two frames.
std::shared_ptr<SceneGeometry> posed_geometry() {
  auto g = std::make_shared<SceneGeometry>();
  g->colliders.push_back(PlaneSpec{});
  BoxSpec box;
  box.center = Vec3(0, 0.5, 0);
  box.rotate = Vec3(0, 30, 0);
  g->colliders.push_back(box);
  SphereSpec sphere;
  sphere.motion.keys = {{0.0, Vec3::Zero(), Vec3::Zero()}, {1.0, Vec3(2, 0, 0), Vec3(0, 90, 0)}};
  g->colliders.push_back(sphere);
  auto mesh = std::make_shared<ObstacleMesh>();
  mesh->surface = test::cube_surface(0.5);
  mesh->frame_times = {0.0, 2.0};
  mesh->frames = {mesh->surface.vertices, mesh->surface.vertices};
  for (Vec3& v : mesh->frames[1])
    v *= 2;  // grows to twice its size over 2 s
  MeshSpec spec;
  spec.mesh = mesh;
  g->colliders.push_back(spec);
  return g;
}

TEST(ColliderPlacements, EachColliderWhereItsDeclarationPutsItAtTheTime) {
  const auto g = posed_geometry();
  std::vector<FrameSnapshot::ColliderPlacement> at;
  place_colliders(g.get(), 0.5, at);
  ASSERT_EQ(at.size(), 4u);
  EXPECT_TRUE(at[0].pose.identity());
  for (std::size_t i = 1; i < 3; ++i) {
    const RigidPose expected = collider_pose(g->colliders[i], 0.5);
    EXPECT_EQ(at[i].pose.rotation, expected.rotation) << i;
    EXPECT_EQ(at[i].pose.translation, expected.translation) << i;
    EXPECT_TRUE(at[i].vertices.empty()) << i;
  }
  EXPECT_LT((at[2].pose.translation - Vec3(1, 0, 0)).norm(), 1e-12);  // half way
  // The mesh at a quarter of its growth: 1.25 times its size, as floats.
  const std::vector<Vec3>& rest = std::get<MeshSpec>(g->colliders[3]).mesh->surface.vertices;
  ASSERT_EQ(at[3].vertices.size(), 3 * rest.size());
  for (std::size_t v = 0; v < rest.size(); ++v)
    for (int d = 0; d < 3; ++d)
      EXPECT_EQ(at[3].vertices[3 * v + std::size_t(d)], float(1.25 * rest[v][d])) << v;
  place_colliders(nullptr, 0.5, at);
  EXPECT_TRUE(at.empty());
}

// Placed again at another time, nothing is reallocated.
TEST(ColliderPlacements, AFrameAllocatesNothingOnceSized) {
  const auto g = posed_geometry();
  std::vector<FrameSnapshot::ColliderPlacement> at;
  place_colliders(g.get(), 0.25, at);
  const FrameSnapshot::ColliderPlacement* list = at.data();
  const float* vertices = at[3].vertices.data();
  const float first = at[3].vertices[0];
  place_colliders(g.get(), 1.5, at);
  EXPECT_EQ(at.data(), list);
  EXPECT_EQ(at[3].vertices.data(), vertices);
  EXPECT_NE(at[3].vertices[0], first);
}

// capture() places the snapshot's own geometry's colliders at the run's time.
TEST(ColliderPlacements, CaptureFillsThemForTheSnapshotsGeometry) {
  const Scene scene = test::asset_scene("sphere_drop");
  Simulation sim = scene.make_simulation();
  FrameSnapshot s;
  capture(sim, s);
  EXPECT_TRUE(s.colliders.empty());  // no geometry, nothing to place
  s.geometry = make_geometry(scene);
  capture(sim, s);
  ASSERT_EQ(s.colliders.size(), s.geometry->colliders.size());
  for (const auto& c : s.colliders)
    EXPECT_TRUE(c.pose.identity());
}

}  // namespace
}  // namespace neurocloth
