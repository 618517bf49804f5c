#include "core/scene/obj_mesh_builder.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <optional>
#include <random>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "core/io/input_error.h"
#include "core/network/spring_layer.h"
#include "core/scene/grid_builder.h"
#include "core/scene/mesh_node_order.h"
#include "core/scene/obj_mesh_writer.h"
#include "core/scene/scene.h"
#include "support/scratch_dir.h"
#include "support/test_support.h"

namespace neurocloth {
namespace {
namespace fs = std::filesystem;

using Edge = std::pair<int, int>;

std::string square_obj() {
  return assets_directory() + "/meshes/square.obj";
}

// Writes `text` to a file in the scratch folder and returns its path.
std::string temp_obj(const std::string& name, const std::string& text) {
  const std::string path = test::scratch_path(name);
  std::ofstream(path, std::ios::binary | std::ios::trunc) << text;
  return path;
}

std::set<Edge> springs_of(const ClothTopology& t, SpringFamily family) {
  std::set<Edge> s;
  for (const auto& spring : t.springs)
    if (spring.family == family)
      s.insert({std::min(spring.a, spring.b), std::max(spring.a, spring.b)});
  return s;
}

using test::count;

ClothTopology build(const std::string& path, double scale = 1.0,
                    const Vec3& translate = Vec3::Zero(), bool bend = true) {
  ObjMeshSpec spec;
  spec.path = path;
  spec.scale = scale;
  spec.translate = translate;
  spec.bend = bend;
  return build_obj_mesh(spec);
}

std::optional<InputError> build_error(const std::string& path) {
  try {
    build(path);
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << path << " was accepted";
  return std::nullopt;
}

// square.obj: vertices 1..9 (1-based, as in the file) form a 3 x 3 grid,
// row by row along x, rows along z; 8 triangles (two per quad, split along
// the 2-4, 3-5, 5-7 and 6-8 diagonals).
TEST(ObjMesh, SquareHasNineNodesAndSixteenEdges) {
  const ClothTopology t = build(square_obj());
  EXPECT_EQ(t.rest_positions.size(), 9u);
  EXPECT_EQ(t.triangles.size(), 8u);
  EXPECT_EQ(t.rows, 0);  // not a grid: pins are node indices
  EXPECT_EQ(count(t, SpringFamily::structural), 16);
  EXPECT_EQ(count(t, SpringFamily::shear), 0);
  // 0-based: 6 along x, 6 along z, 4 diagonals. No edge twice.
  const std::set<Edge> expected = {{0, 1}, {1, 2}, {3, 4}, {4, 5}, {6, 7}, {7, 8}, {0, 3}, {3, 6},
                                   {1, 4}, {4, 7}, {2, 5}, {5, 8}, {1, 3}, {2, 4}, {4, 6}, {5, 7}};
  EXPECT_EQ(springs_of(t, SpringFamily::structural), expected);
}

TEST(ObjMesh, SquareHasOneBendSpringPerInteriorEdge) {
  const ClothTopology t = build(square_obj());
  // 16 edges, 8 on the boundary: 8 interior edges, each shared by two triangles.
  EXPECT_EQ(count(t, SpringFamily::bend), 8);
  EXPECT_EQ(t.springs.size(), 24u);
  // By hand (1-based): edge 2-4 is in "f 1 4 2" and "f 2 4 5", whose third
  // vertices are 1 and 5, so the bend spring joins the corner to the centre.
  const std::set<Edge> bends = springs_of(t, SpringFamily::bend);
  EXPECT_EQ(bends.count({0, 4}), 1u);
  // The rest of them, worked out the same way per interior edge:
  // 2-5 -> 4,3; 3-5 -> 2,6; 4-5 -> 2,7; 5-6 -> 3,8; 5-7 -> 4,8; 5-8 -> 7,6; 6-8 -> 5,9.
  const std::set<Edge> expected = {{0, 4}, {2, 3}, {1, 5}, {1, 6}, {2, 7}, {3, 7}, {5, 6}, {4, 8}};
  EXPECT_EQ(bends, expected);
}

TEST(ObjMesh, BendSpringsAreOptional) {
  const ClothTopology t = build(square_obj(), 1.0, Vec3::Zero(), /*bend=*/false);
  EXPECT_EQ(count(t, SpringFamily::bend), 0);
  EXPECT_EQ(count(t, SpringFamily::structural), 16);
}

TEST(ObjMesh, ReadsVertexPositions) {
  const ClothTopology t = build(square_obj());
  // Vertex 5 (index 4) is the centre, vertex 6 (index 5) the middle of the x = 1 side.
  EXPECT_EQ(t.rest_positions[4], Vec3(0.5, 0, 0.5));
  EXPECT_EQ(t.rest_positions[5], Vec3(1, 0, 0.5));
}

TEST(ObjMesh, ScaleThenTranslate) {
  const ClothTopology t = build(square_obj(), 2.0, Vec3(1, 2, 3));
  // p' = scale * p + translate.
  EXPECT_EQ(t.rest_positions[0], Vec3(1, 2, 3));
  EXPECT_EQ(t.rest_positions[4], Vec3(2, 2, 4));
  EXPECT_EQ(t.rest_positions[8], Vec3(3, 2, 5));
}

TEST(ObjMesh, QuadIsTriangulated) {
  const std::string path = temp_obj("quad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n");
  const ClothTopology t = build(path);
  EXPECT_EQ(t.rest_positions.size(), 4u);
  EXPECT_EQ(t.triangles.size(), 2u);
  EXPECT_EQ(count(t, SpringFamily::structural), 5);  // 4 sides + the diagonal
  ASSERT_EQ(count(t, SpringFamily::bend), 1);
  // The bend spring crosses the diagonal: it joins the two corners the diagonal does not.
  const std::set<Edge> structural = springs_of(t, SpringFamily::structural);
  const Edge bend = *springs_of(t, SpringFamily::bend).begin();
  EXPECT_EQ(structural.count(bend), 0u);
  for (const Edge& diagonal : {Edge{0, 2}, Edge{1, 3}}) {
    if (structural.count(diagonal) == 0) continue;
    EXPECT_EQ(bend, (diagonal == Edge{0, 2} ? Edge{1, 3} : Edge{0, 2}));
  }
}

TEST(ObjMesh, NegativeIndicesCountFromTheEnd) {
  const std::string path = temp_obj("relative.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\n");
  const ClothTopology t = build(path);
  ASSERT_EQ(t.triangles.size(), 1u);
  EXPECT_EQ(t.triangles[0], (std::array<std::int32_t, 3>{0, 1, 2}));
}

TEST(ObjMesh, UnreadableFileNamesThePath) {
  const std::string path = test::scratch_path("no_such_file.obj");
  fs::remove(path);
  const auto e = build_error(path);
  ASSERT_TRUE(e);
  EXPECT_EQ(e->file(), path);
  EXPECT_NE(std::string(e->what()).find(path), std::string::npos) << e->what();
}

TEST(ObjMesh, FaceReferringToMissingVertex) {
  const std::string path = temp_obj("vertex99.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99\n");
  const auto e = build_error(path);
  ASSERT_TRUE(e);
  EXPECT_EQ(e->file(), path);
  EXPECT_EQ(e->field(), "f");
  const std::string what = e->what();
  EXPECT_NE(what.find(path), std::string::npos) << what;
  EXPECT_NE(what.find("99"), std::string::npos) << what;
  EXPECT_NE(what.find("has 3"), std::string::npos) << what;
}

TEST(ObjMesh, NegativeIndexBeforeTheFirstVertex) {
  const std::string path = temp_obj("relative_bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -9\n");
  const auto e = build_error(path);
  ASSERT_TRUE(e);
  EXPECT_EQ(e->file(), path);
  EXPECT_EQ(e->field(), "f");
}

TEST(ObjMesh, ZeroIndexIsAParseErrorWithALine) {
  // OBJ indices start at 1; the parser rejects 0 and says on which line.
  const std::string path = temp_obj("zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n");
  const auto e = build_error(path);
  ASSERT_TRUE(e);
  EXPECT_EQ(e->file(), path);
  EXPECT_EQ(e->line(), 4);
  EXPECT_NE(std::string(e->what()).find(path + ":4:"), std::string::npos) << e->what();
}

TEST(ObjMesh, NoFaces) {
  const std::string path = temp_obj("no_faces.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
  const auto e = build_error(path);
  ASSERT_TRUE(e);
  EXPECT_EQ(e->file(), path);
  EXPECT_EQ(e->field(), "f");
  EXPECT_NE(std::string(e->what()).find("no faces"), std::string::npos) << e->what();
}

TEST(ObjMesh, EmptyFile) {
  const std::string path = temp_obj("empty.obj", "");
  const auto e = build_error(path);
  ASSERT_TRUE(e);
  EXPECT_EQ(e->file(), path);
}

TEST(ObjMesh, DegenerateFace) {
  const std::string path = temp_obj("degenerate.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 1 2\n");
  const auto e = build_error(path);
  ASSERT_TRUE(e);
  EXPECT_EQ(e->file(), path);
  EXPECT_EQ(e->field(), "f");
  EXPECT_NE(std::string(e->what()).find("degenerate"), std::string::npos) << e->what();
}

TEST(ObjMesh, NonFiniteVertex) {
  const std::string path = temp_obj("huge.obj", "v 1e999 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  const auto e = build_error(path);
  ASSERT_TRUE(e);
  EXPECT_EQ(e->file(), path);
  EXPECT_EQ(e->field(), "v");
}

// tinyobjloader reads a coordinate it cannot parse as 0, silently: each is
// checked first and refused with its line (a NaN vertex ran as 0 before).
TEST(ObjMesh, ACoordinateThatIsNotAFiniteNumberIsNamedWithItsLine) {
  for (const char* bad : {"v nan 0 0", "v 1 inf 0", "v 0 0 0x1p3", "v 1 2", "v 1e999 0 0",
                          "v 1.5. 0 0", "v -e5 0 0", "v 0 -1e308 0"}) {
    SCOPED_TRACE(bad);
    const auto e = build_error(temp_obj(
        "bad.obj", std::string("# from a tool\nv 0 0 0\n") + bad + "\nv 0 1 0\nf 1 2 3\n"));
    ASSERT_TRUE(e);
    EXPECT_EQ(e->field(), "v");
    EXPECT_EQ(e->line(), 3);
    EXPECT_NE(e->message().find("vertex 2"), std::string::npos) << e->what();
  }
  // What tools write: signs, exponents, a w, a colour, tabs, CRLF.
  const ClothTopology t = build(
      temp_obj("good.obj",
               "v -1.000000 +2.5e-1 3E2 1.0\r\nv\t1 0 0 0.5 0.5 0.5\r\nv .5 1. 0\r\nf 1 2 3\r\n"));
  ASSERT_EQ(t.rest_positions.size(), 3u);
  EXPECT_EQ(t.rest_positions[0], Vec3(-1, 0.25, 300));
  EXPECT_EQ(t.rest_positions[2], Vec3(0.5, 1, 0));
}

// Triangulating a polygon costs its corners (60,000 corners would take some
// 15 s); past 256 a face is refused before anything is parsed.
TEST(ObjMesh, AFaceWithTooManyCornersIsRefusedWithItsLine) {
  std::string obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\n# a comment\nf";
  for (int i = 0; i < 60000; ++i)
    obj += " 1";
  const auto e = build_error(temp_obj("long.obj", obj + "\n"));
  ASSERT_TRUE(e);
  EXPECT_EQ(e->field(), "f");
  EXPECT_EQ(e->line(), 5);
  EXPECT_NE(e->message().find("more than 256 corners"), std::string::npos) << e->what();
}

TEST(ObjMesh, AFaceWithFewerThanThreeCornersIsRefusedWithItsLine) {
  const auto e = build_error(temp_obj("short.obj", "v 0 0 0\nv 1 0 0\r\nv 0 1 0\rf 1 2\n"));
  ASSERT_TRUE(e);
  EXPECT_EQ(e->line(), 4);  // \n, \r\n and \r each end one line
  EXPECT_NE(e->message().find("at least 3 corners"), std::string::npos) << e->what();
}

// Errors found after parsing name the face's line, across groups and objects.
TEST(ObjMesh, FaceErrorsNameTheirLine) {
  const std::string head = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\no first\nf 1 2 3\ng second\n";
  auto e = build_error(temp_obj("repeat.obj", head + "f 2 4 3\nf 2 4 2\n"));
  ASSERT_TRUE(e);
  EXPECT_EQ(e->line(), 9);
  EXPECT_NE(e->message().find("degenerate"), std::string::npos) << e->what();
  e = build_error(temp_obj("missing.obj", head + "f 2 4 3\nf 2 4 9\n"));
  ASSERT_TRUE(e);
  EXPECT_EQ(e->line(), 9);
  EXPECT_NE(e->message().find("vertex 9"), std::string::npos) << e->what();
}

// What a cloth does not use is never parsed: a material library is not
// opened (this one would never end), a skin weight's huge joint id not cast
// to int (undefined behaviour inside tinyobjloader, found by fuzzing).
TEST(ObjMesh, StatementsAClothDoesNotUseAreNotParsed) {
  const ClothTopology t = build(temp_obj(
      "extras.obj",
      "mtllib /dev/zero\nusemtl cloth\no sheet\ng front\ns 1\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"
      "vt 0 0\nvt 1 0\nvt 0 1\nvn 0 0 1\nvw 1 1e10 0.5\nl 1 2\np 3\nf 1/1/1 2/2/1 3/3/1\n"));
  EXPECT_EQ(t.rest_positions.size(), 3u);
  EXPECT_EQ(t.triangles.size(), 1u);
}

// A polygon beyond a quad becomes a fan from its first corner.
TEST(ObjMesh, APentagonBecomesThreeTriangles) {
  const ClothTopology t = build(temp_obj(
      "pentagon.obj", "v 0 0 0\nv 1 0 0\nv 1.3 1 0\nv 0.5 1.6 0\nv -0.3 1 0\nf 1 2 3 4 5\n"));
  ASSERT_EQ(t.triangles.size(), 3u);
  EXPECT_EQ(t.triangles[2], (std::array<std::int32_t, 3>{0, 3, 4}));
  EXPECT_EQ(count(t, SpringFamily::structural), 7);  // 5 sides, 2 diagonals
}

ClothTopology grid_mesh(int n, const std::vector<std::int32_t>& order = {}) {
  GridSpec g;
  g.rows = g.cols = n;
  g.spacing = 0.05;
  const ClothTopology grid = build_grid(g);
  const std::string path = test::scratch_path("grid.obj");
  write_obj_mesh(order.empty() ? grid : renumbered(grid, order), path);
  return build(path);
}

// A grid written as an OBJ file row by row gives its springs in runs about a
// row long, as the grid builder does: the force loop vectorises (spring_layer.h).
// Springs per run, as the spring layer forms runs from the builder's order.
double mean_run(const ClothTopology& t) {
  SpringLayer layer;
  for (const SpringSpec& s : t.springs) {
    layer.node_a.push_back(s.a);
    layer.node_b.push_back(s.b);
  }
  layer.rebuild_runs();
  return static_cast<double>(layer.size()) / static_cast<double>(layer.runs.size());
}

// A vertex order that scatters neighbours, the same on every run.
std::vector<std::int32_t> shuffled_order(int vertices) {
  std::vector<std::int32_t> order(static_cast<std::size_t>(vertices));
  std::iota(order.begin(), order.end(), 0);
  std::shuffle(order.begin(), order.end(), std::mt19937(7));
  return order;
}

TEST(ObjMesh, AGridMeshFormsLongRuns) {
  const ClothTopology t = grid_mesh(32);
  EXPECT_GT(mean_run(t), 24.0) << t.springs.size() << " springs";
  EXPECT_TRUE(t.numbering.identity()) << "a mesh in row order keeps the file's order";
}

// Shuffled, the same grid has no runs in its file's order; renumbered at load
// it has them back, about a level of the breadth-first order long (the
// levels run across the grid's diagonal: 1 to 32 nodes and back; in the
// file's order a run is about one spring).
TEST(ObjMesh, AShuffledGridMeshIsRenumberedIntoLongRuns) {
  const ClothTopology t = grid_mesh(32, shuffled_order(32 * 32));
  EXPECT_FALSE(t.numbering.identity());
  EXPECT_GT(mean_run(t), 10.0) << t.springs.size() << " springs";
}

// An independent count of what the builder must produce: every triangle edge
// once (structural) and, for every two triangles sharing an edge, a bend
// spring between their other corners; found by comparing every pair of
// triangles, in a mesh whose vertex order scatters neighbours.
TEST(ObjMesh, EveryEdgeOnceAndABendAcrossEverySharedEdge) {
  std::vector<std::int32_t> order(36);
  for (int k = 0; k < 36; ++k)
    order[k] = (k * 7) % 36;  // 7 is prime to 36: a permutation
  const ClothTopology t = grid_mesh(6, order);
  std::multiset<std::pair<Edge, SpringFamily>> expected, built;
  std::set<Edge> edges;
  for (const auto& tri : t.triangles)
    for (int k = 0; k < 3; ++k)
      edges.insert({std::min(tri[k], tri[(k + 1) % 3]), std::max(tri[k], tri[(k + 1) % 3])});
  for (const Edge& e : edges)
    expected.insert({e, SpringFamily::structural});
  for (std::size_t i = 0; i < t.triangles.size(); ++i)
    for (std::size_t j = i + 1; j < t.triangles.size(); ++j) {
      std::vector<int> only_i, only_j;
      for (int v : t.triangles[i])
        if (std::find(t.triangles[j].begin(), t.triangles[j].end(), v) == t.triangles[j].end())
          only_i.push_back(v);
      for (int v : t.triangles[j])
        if (std::find(t.triangles[i].begin(), t.triangles[i].end(), v) == t.triangles[i].end())
          only_j.push_back(v);
      if (only_i.size() == 1 && only_j.size() == 1)
        expected.insert(
            {{std::min(only_i[0], only_j[0]), std::max(only_i[0], only_j[0])}, SpringFamily::bend});
    }
  for (const SpringSpec& s : t.springs)
    built.insert({{s.a, s.b}, s.family});
  EXPECT_EQ(built, expected);
}

// Node k may be any node, but the numbering says which file vertex it is:
// pins, pin_motion and RESULT.json count nodes as the file counts its vertices.
TEST(ObjMesh, TheNumberingNamesEachNodesFileVertex) {
  GridSpec g;
  g.rows = g.cols = 12;
  g.spacing = 0.05;
  const ClothTopology grid = build_grid(g);
  const std::vector<std::int32_t> order = shuffled_order(144);
  const ClothTopology t = grid_mesh(12, order);
  ASSERT_EQ(t.rest_positions.size(), 144u);
  ASSERT_FALSE(t.numbering.identity());
  for (int k = 0; k < 144; ++k) {
    EXPECT_EQ(t.numbering.source(t.numbering.node(k)), k);
    EXPECT_LT((t.rest_positions[t.numbering.node(k)] - grid.rest_positions[order[k]]).norm(), 1e-15)
        << "file vertex " << k;
  }
}

// /dev/zero never ends: refused as a device, not read until memory runs out.
TEST(ObjMesh, AnEndlessFileIsRefused) {
  const auto e = build_error("/dev/zero");
  ASSERT_TRUE(e);
  EXPECT_EQ(e->file(), "/dev/zero");
  EXPECT_NE(e->message().find("is a device"), std::string::npos) << e->what();
}

}  // namespace
}  // namespace neurocloth
