#include "core/scene/grid_builder.h"

#include <gtest/gtest.h>

#include "core/network/cloth_network.h"
#include "support/test_support.h"

namespace neurocloth {
namespace {

using test::count;

TEST(GridBuilder, SpringCountsPerFamily) {
  GridSpec g;
  g.rows = 5;
  g.cols = 7;
  const ClothTopology t = build_grid(g);
  EXPECT_EQ(t.rest_positions.size(), 35u);
  EXPECT_EQ(count(t, SpringFamily::structural), 5 * 6 + 4 * 7);
  EXPECT_EQ(count(t, SpringFamily::shear), 2 * 4 * 6);
  EXPECT_EQ(count(t, SpringFamily::bend), 5 * 5 + 3 * 7);
  EXPECT_EQ(t.triangles.size(), 2u * 4 * 6);
}

TEST(GridBuilder, FamiliesAreOptional) {
  GridSpec g;
  g.rows = g.cols = 4;
  g.families = {true, false, false};
  const ClothTopology t = build_grid(g);
  EXPECT_EQ(count(t, SpringFamily::shear) + count(t, SpringFamily::bend), 0);
  EXPECT_EQ(count(t, SpringFamily::structural), 24);
}

TEST(GridBuilder, NodeIndexIsRowTimesColsPlusCol) {
  GridSpec g;
  g.rows = 3;
  g.cols = 4;
  g.spacing = 0.5;
  g.origin = Vec3(1, 2, 3);
  g.row_direction = Vec3(0, 0, 2);  // normalised by the builder
  g.col_direction = Vec3(1, 0, 0);
  const ClothTopology t = build_grid(g);
  EXPECT_TRUE(t.rest_positions[2 * 4 + 3].isApprox(Vec3(1 + 1.5, 2, 3 + 1.0)));
}

TEST(GridBuilder, SpringsFormLongStencilRuns) {
  // Every family of a grid becomes a few long runs, which is what lets the
  // spring layer vectorise: at most one run per row per family, and the vertical
  // families one run each.
  GridSpec g;
  g.rows = g.cols = 16;
  ClothNetwork net = ClothNetwork::build(build_grid(g), Material{});
  EXPECT_LE(net.springs.runs.size(), 16u * 4 + 2);
  std::int32_t covered = 0;
  for (const SpringRun& r : net.springs.runs) {
    for (std::int32_t k = 0; k < r.count; ++k) {
      EXPECT_EQ(net.springs.node_a[r.first + k], r.node_a + k);
      EXPECT_EQ(net.springs.node_b[r.first + k], r.node_b + k);
    }
    covered += r.count;
  }
  EXPECT_EQ(static_cast<std::size_t>(covered), net.spring_count());
}

TEST(GridBuilder, RejectsBadShapes) {
  GridSpec g;
  g.rows = 0;
  EXPECT_THROW(build_grid(g), std::invalid_argument);
  g.rows = 2;
  g.spacing = 0;
  EXPECT_THROW(build_grid(g), std::invalid_argument);
}

TEST(GridBuilder, SingleNodeHasNoSprings) {
  GridSpec g;
  g.rows = g.cols = 1;
  EXPECT_TRUE(build_grid(g).springs.empty());
}

}  // namespace
}  // namespace neurocloth
