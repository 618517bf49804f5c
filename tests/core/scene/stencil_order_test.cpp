#include "core/scene/stencil_order.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <tuple>
#include <vector>

#include "core/network/spring_layer.h"
#include "core/scene/grid_builder.h"
#include "core/scene/obj_mesh_builder.h"
#include "core/scene/obj_mesh_writer.h"
#include "support/scene_test_support.h"
#include "support/test_support.h"

namespace neurocloth {
namespace {
bool by_nodes(const SpringSpec& x, const SpringSpec& y) {
  return std::tie(x.a, x.b, x.family) < std::tie(y.a, y.b, y.family);
}

std::vector<SpringSpec> sorted_by_nodes(std::vector<SpringSpec> springs) {
  std::sort(springs.begin(), springs.end(), by_nodes);
  return springs;
}

bool same(const SpringSpec& x, const SpringSpec& y) {
  return x.a == y.a && x.b == y.b && x.family == y.family;
}

bool same_set(const std::vector<SpringSpec>& x, const std::vector<SpringSpec>& y) {
  const auto sx = sorted_by_nodes(x), sy = sorted_by_nodes(y);
  return std::equal(sx.begin(), sx.end(), sy.begin(), sy.end(), same);
}

std::size_t run_count(const std::vector<SpringSpec>& springs) {
  SpringLayer layer;
  for (const SpringSpec& s : springs) {
    layer.node_a.push_back(s.a);
    layer.node_b.push_back(s.b);
  }
  layer.rebuild_runs();
  return layer.runs.size();
}

GridSpec grid(int rows, int cols) {
  GridSpec g;
  g.rows = rows;
  g.cols = cols;
  g.spacing = 0.1;
  return g;
}

TEST(StencilOrder, ShuffledGridSpringsGetTheGridsRunsBack) {
  const ClothTopology t = build_grid(grid(12, 17));
  std::vector<SpringSpec> springs = t.springs;
  std::shuffle(springs.begin(), springs.end(), std::mt19937(12));
  ASSERT_GT(run_count(springs), springs.size() / 2);  // shuffled: no runs to speak of
  sort_into_stencil_runs(springs);
  EXPECT_TRUE(same_set(springs, t.springs));
  // The builder's order is a run per row and family (a whole family for the
  // ones along columns): the fewest runs these springs make.
  EXPECT_EQ(run_count(springs), run_count(t.springs));
}

TEST(StencilOrder, SpringsInNoLongStretchFollowInNodeOrder) {
  // A stretch of 10 (kept together) and 3 springs that belong to no stretch.
  std::vector<SpringSpec> springs = {{40, 45, SpringFamily::bend},
                                     {7, 30, SpringFamily::structural},
                                     {2, 9, SpringFamily::structural}};
  for (int k = 9; k >= 0; --k)
    springs.push_back({100 + k, 101 + k, SpringFamily::structural});
  const std::vector<SpringSpec> before = springs;
  sort_into_stencil_runs(springs);
  EXPECT_TRUE(same_set(springs, before));
  ASSERT_EQ(springs.size(), 13u);
  for (int k = 0; k < 10; ++k)
    EXPECT_EQ(springs[k].a, 100 + k);
  EXPECT_EQ(springs[10].a, 2);
  EXPECT_EQ(springs[11].a, 7);
  EXPECT_EQ(springs[12].a, 40);
}

TEST(StencilOrder, SameSetGivesTheSameOrder) {
  std::vector<SpringSpec> springs = build_grid(grid(6, 9)).springs;
  springs.push_back({3, 50, SpringFamily::bend});
  std::vector<SpringSpec> other = springs;
  std::shuffle(other.begin(), other.end(), std::mt19937(3));
  sort_into_stencil_runs(springs);
  sort_into_stencil_runs(other);
  EXPECT_TRUE(std::equal(springs.begin(), springs.end(), other.begin(), other.end(), same));
}

// The order changes only the order in which spring forces are summed: a mesh
// cloth hanging for 0.3 s ends where the same springs sorted by their nodes
// (next to no runs) take it, to rounding.
TEST(StencilOrder, MeshClothMovesAsWithSpringsInNodeOrder) {
  Scene scene = test::asset_scene("hanging");  // 20 x 20, pinned at nodes 0 and 19
  ObjMeshSpec spec;
  spec.path = test::scratch_path("hanging.obj");
  write_obj_mesh(scene.topology, spec.path);
  scene.topology = build_obj_mesh(spec);
  scene.grid.reset();
  ASSERT_LT(run_count(scene.topology.springs), scene.topology.springs.size() / 8);

  Scene plain = scene;
  std::sort(plain.topology.springs.begin(), plain.topology.springs.end(), by_nodes);
  ASSERT_GT(run_count(plain.topology.springs), plain.topology.springs.size() / 2);

  Simulation a = scene.make_simulation(), b = plain.make_simulation();
  ASSERT_EQ(a.advance(0.3), RunStatus::ok);
  ASSERT_EQ(b.advance(0.3), RunStatus::ok);
  double moved = 0, apart = 0;
  for (std::size_t i = 0; i < a.state().size(); ++i) {
    moved = std::max(moved, (a.state().position(i) - scene.topology.rest_positions[i]).norm());
    apart = std::max(apart, (a.state().position(i) - b.state().position(i)).norm());
  }
  EXPECT_GT(moved, 0.1);  // it swung: the forces were anything but zero
  EXPECT_LT(apart, 1e-9);
}

}  // namespace
}  // namespace neurocloth
