#include "learn/motion/cache_vertex_match.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>

#include "support/input_error_check.h"

namespace neurocloth {
namespace {
using test::expect_input_error;

// A 4 x 5 grid of 0.25 m in the scene's y = 2 plane (Y-up), node r * 5 + c.
std::vector<Vec3> grid() {
  std::vector<Vec3> p;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 5; ++c)
      p.emplace_back(0.25 * c, 2, 0.25 * r);
  return p;
}

// The grid's nodes in another program's order: column by column, each column
// from the far row to the near one (as a grid primitive may number them).
std::vector<std::int32_t> column_order() {
  std::vector<std::int32_t> order;
  for (int c = 0; c < 5; ++c)
    for (int r = 3; r >= 0; --r)
      order.push_back(r * 5 + c);
  return order;
}

std::vector<Vec3> in_order(const std::vector<Vec3>& points,
                           const std::vector<std::int32_t>& order) {
  std::vector<Vec3> out;
  for (const std::int32_t k : order)
    out.push_back(points[k]);
  return out;
}

// A cache of two frames of the mesh's vertices, frame 1 moved by each vertex's
// number so that a wrong mapping shows.
ReferenceMotion cache_of(const std::vector<Vec3>& mesh) {
  ReferenceMotion m;
  m.path = "run.pc2";
  m.source = ReferenceMotion::Source::cache;
  for (int f = 0; f < 2; ++f) {
    ReferenceFrame frame;
    frame.time = f / 24.0;
    for (std::size_t k = 0; k < mesh.size(); ++k) {
      frame.nodes.push_back(std::int32_t(k));
      frame.positions.push_back(mesh[k] + f * Vec3(0, -0.01 * double(k), 0));
    }
    m.frames.push_back(frame);
  }
  return m;
}

TEST(CacheVertexMatch, AMeshInTheScenesOrderIsTakenAsIs) {
  std::string note;
  EXPECT_TRUE(mesh_nodes(grid(), grid(), "run.pc2", "cloth.obj", note).empty());
  EXPECT_NE(note.find("vertex k is node k"), std::string::npos) << note;
  // Six decimals of an OBJ are well within the tolerance.
  std::vector<Vec3> rounded = grid();
  for (Vec3& p : rounded)
    p += Vec3(4e-7, -4e-7, 4e-7);
  EXPECT_TRUE(mesh_nodes(rounded, grid(), "run.pc2", "cloth.obj", note).empty());
}

TEST(CacheVertexMatch, AMeshInAnotherOrderIsMatchedByPosition) {
  const std::vector<std::int32_t> order = column_order();
  std::string note;
  EXPECT_EQ(mesh_nodes(in_order(grid(), order), grid(), "run.pc2", "cloth.obj", note), order);
  EXPECT_NE(note.find("by position"), std::string::npos) << note;
  // Any order: a shuffle.
  std::vector<std::int32_t> shuffled(20);
  std::iota(shuffled.begin(), shuffled.end(), 0);
  std::shuffle(shuffled.begin(), shuffled.end(), std::mt19937(7));
  EXPECT_EQ(mesh_nodes(in_order(grid(), shuffled), grid(), "run.pc2", "cloth.obj", note), shuffled);
}

// A seam: two scene nodes at one place, two mesh vertices there too. Each
// vertex takes a node of its own.
TEST(CacheVertexMatch, CoincidentNodesEachGetAVertex) {
  std::vector<Vec3> scene = grid();
  scene[7] = scene[6];
  std::vector<Vec3> mesh = scene;
  std::swap(mesh[0], mesh[19]);
  std::string note;
  const std::vector<std::int32_t> nodes = mesh_nodes(mesh, scene, "run.pc2", "cloth.obj", note);
  ASSERT_EQ(nodes.size(), 20u);
  std::vector<std::int32_t> sorted = nodes;
  std::sort(sorted.begin(), sorted.end());
  for (std::int32_t k = 0; k < 20; ++k)
    EXPECT_EQ(sorted[k], k);
  EXPECT_EQ(nodes[0], 19);
  EXPECT_TRUE((nodes[6] == 6 && nodes[7] == 7) || (nodes[6] == 7 && nodes[7] == 6));
}

TEST(CacheVertexMatchErrors, AMeshThatIsNotTheScenesClothIsRefused) {
  std::vector<Vec3> moved = in_order(grid(), column_order());
  moved[3] += Vec3(0, 0.01, 0);  // 1 cm off: the tolerance is 1e-4 of 1.25 m
  std::string note;
  expect_input_error(
      [&] { mesh_nodes(moved, grid(), "run.pc2", "cloth.obj", note); }, "run.pc2", 0,
      "--reference-mesh",
      {"not the scene's cloth", "vertex 3 of the mesh 'cloth.obj'", "0.01 m", "0.000125 m"});
  // Two vertices on one node, none on another.
  std::vector<Vec3> doubled = grid();
  doubled[5] = doubled[4];
  expect_input_error([&] { mesh_nodes(doubled, grid(), "run.pc2", "cloth.obj", note); }, "run.pc2",
                     0, "--reference-mesh", {"vertices 4 and 5", "both sit on scene node 4"});
}

TEST(CacheVertexMatch, TellsAZUpCacheByItsFirstFrame) {
  std::vector<Vec3> z_up;
  for (const Vec3& p : grid())
    z_up.emplace_back(p.x(), -p.z(), p.y());  // Blender's coordinates of the scene's point
  double as_written = 0, turned = 0;
  EXPECT_TRUE(cache_is_z_up(z_up, grid(), as_written, turned));
  EXPECT_NEAR(turned, 0, 1e-15);
  EXPECT_GT(as_written, 1);
  EXPECT_FALSE(cache_is_z_up(grid(), grid(), as_written, turned));
  EXPECT_EQ(as_written, 0);
}

// The whole: a Z-up cache of a mesh in column order becomes the scene's
// nodes, Y-up, frame by frame.
TEST(CacheVertexMatch, MakesACacheTheScenes) {
  const std::vector<std::int32_t> order = column_order();
  const std::vector<Vec3> mesh = in_order(grid(), order);
  const ReferenceMotion expected = cache_of(mesh);
  ReferenceMotion m = cache_of(mesh);
  for (ReferenceFrame& f : m.frames)
    for (Vec3& p : f.positions)
      p = Vec3(p.x(), -p.z(), p.y());  // as Blender writes an MDD
  match_cache_to_scene(m, mesh, "cloth.obj", 20, grid());
  for (std::size_t f = 0; f < 2; ++f)
    for (std::size_t k = 0; k < 20; ++k) {
      EXPECT_EQ(m.frames[f].nodes[order[k]], order[k]);
      EXPECT_EQ(m.frames[f].positions[order[k]], expected.frames[f].positions[k])
          << "frame " << f << " mesh vertex " << k;
    }
  EXPECT_NE(m.note.find("turned from Z-up"), std::string::npos) << m.note;
  EXPECT_NE(m.note.find("by position"), std::string::npos) << m.note;
}

TEST(CacheVertexMatchErrors, CountsThatDisagreeNameBothFiles) {
  ReferenceMotion m = cache_of(grid());
  std::vector<Vec3> fewer = grid();
  fewer.pop_back();
  expect_input_error([&] { match_cache_to_scene(m, fewer, "cloth.obj", 20, {}); }, "run.pc2", 0,
                     "vertex count", {"the cache has 20 vertices, its mesh 'cloth.obj' 19"});
  expect_input_error([&] { match_cache_to_scene(m, grid(), "cloth.obj", 21, {}); }, "run.pc2", 0,
                     "vertex count", {"'cloth.obj' have 20 vertices, the scene's cloth 21 nodes"});
}

}  // namespace
}  // namespace neurocloth
