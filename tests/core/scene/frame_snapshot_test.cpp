// What the renderer is given of a scene (frame_snapshot.h): here, the coarse
// triangles a large grid is also drawn with, on grids whose rows and columns
// differ (tests/render/renderer_test.cpp draws them, on square grids).
#include "core/scene/frame_snapshot.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "core/scene/scene.h"
#include "support/scene_builder.h"

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

}  // namespace
}  // namespace neurocloth
