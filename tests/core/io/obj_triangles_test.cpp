// The OBJ reader every mesh shares: vertices as written, triangles with the
// line of their face, limits refused at the line that goes over them. The
// cloth's own checks on the same reader are tests/core/scene/obj_mesh_builder_test.cpp.
#include "core/io/obj_triangles.h"

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

#include "support/input_error_check.h"
#include "support/scratch_dir.h"

namespace neurocloth {
namespace {
using test::expect_input_error;
using Triangle = std::array<std::int32_t, 3>;

constexpr std::size_t kAny = std::numeric_limits<std::size_t>::max();
const ObjLimits kLoose{1 << 20, kAny, kAny};

ObjTriangles parse(const std::string& text, const ObjLimits& limits = kLoose,
                   const ObjPlacement& place = {}) {
  return parse_obj_triangles(text, "mesh.obj", limits, place);
}

TEST(ObjTriangles, VerticesAsWrittenAndEachTrianglesLine) {
  const ObjTriangles obj = parse(
      "# a tool\nmtllib none.mtl\no thing\nv 0 0 0\nv 2 0 0\nv 2 3 0\r\nv 0 3 -1e-3\n"
      "vt 0 0\ng side\nf 1 2 3\n\nusemtl red\nf 1/1 3/1 4/1\n");
  ASSERT_EQ(obj.vertices.size(), 4u);
  EXPECT_EQ(obj.vertices[1], Vec3(2, 0, 0));
  EXPECT_EQ(obj.vertices[3], Vec3(0, 3, -1e-3));
  ASSERT_EQ(obj.triangles.size(), 2u);
  EXPECT_EQ(obj.triangles[0], (Triangle{0, 1, 2}));
  EXPECT_EQ(obj.triangles[1], (Triangle{0, 2, 3}));
  EXPECT_EQ(obj.lines, (std::vector<int>{10, 13}));
}

// A quad across its shorter diagonal, a pentagon as a fan; every triangle
// keeps its face's line.
TEST(ObjTriangles, PolygonsBecomeTriangles) {
  // A parallelogram whose 2-4 diagonal (1-based) is the shorter.
  const ObjTriangles quad =
      parse("v 0 0 0\nv 2 0 0\nv 3 1 0\nv 1 1 0\nf 1 2 3 4\nv 5 0 0\nf 1 2 5 3 4\n");
  ASSERT_EQ(quad.triangles.size(), 5u);
  EXPECT_EQ(quad.triangles[0], (Triangle{0, 1, 3}));
  EXPECT_EQ(quad.triangles[1], (Triangle{1, 2, 3}));
  EXPECT_EQ(quad.triangles[2], (Triangle{0, 1, 4}));
  EXPECT_EQ(quad.triangles[4], (Triangle{0, 2, 3}));
  EXPECT_EQ(quad.lines, (std::vector<int>{5, 5, 7, 7, 7}));
}

// The shorter diagonal is the one where the caller places the mesh: sheared,
// the same parallelogram's other diagonal is the shorter.
TEST(ObjTriangles, TheShorterDiagonalIsMeasuredWhereTheMeshIsPlaced) {
  const std::string text = "v 0 0 0\nv 2 0 0\nv 3 1 0\nv 1 1 0\nf 1 2 3 4\n";
  const ObjTriangles sheared =
      parse(text, kLoose, [](const Vec3& v) { return Vec3(v.x() - 3 * v.y(), v.y(), v.z()); });
  ASSERT_EQ(sheared.triangles.size(), 2u);
  EXPECT_EQ(sheared.triangles[0], (Triangle{0, 1, 2}));
  EXPECT_EQ(sheared.triangles[1], (Triangle{0, 2, 3}));
  EXPECT_EQ(sheared.vertices[2], Vec3(3, 1, 0)) << "the vertices stay as written";
}

TEST(ObjTrianglesErrors, LimitsAreRefusedAtTheLineThatGoesOver) {
  const std::string text = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 2 3 4\n";
  expect_input_error(
      [&] {
        parse(text, {1 << 20, 3, kAny});
      },
      "mesh.obj", 4, "v", {"more than 3 vertices"});
  // The quad is two triangles: the third goes over.
  expect_input_error(
      [&] {
        parse(text, {1 << 20, kAny, 2});
      },
      "mesh.obj", 6, "f", {"more than 2 triangles"});
  EXPECT_EQ(parse(text, {1 << 20, 4, 3}).triangles.size(), 3u);
  expect_input_error(
      [&] {
        parse(text, {1 << 20, 2'000'000, 0});
      },
      "mesh.obj", 5, "f", {"more than 0 triangles"});
}

TEST(ObjTrianglesErrors, EachIsNamedWithItsLineAndField) {
  expect_input_error([] { parse("v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n"); }, "mesh.obj", 2, "v",
                     {"vertex 2 (x): 'nan' is not a finite number"});
  expect_input_error([] { parse("v 0 0 0\nv 1 0 0\nv 0 1 1e11\nf 1 2 3\n"); }, "mesh.obj", 3, "v",
                     {"vertex 3 (z): 1e11 is beyond +-1e10 in any unit"});
  expect_input_error([] { parse("v 0 0 0\nv 1 0 0\nv 0 1 0\n"); }, "mesh.obj", 0, "f",
                     {"the mesh has no faces"});
  expect_input_error([] { parse("v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 2 4\n"); }, "mesh.obj", 5, "f",
                     {"face refers to vertex 4 but the file has 3"});
  expect_input_error([] { parse("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 2\n"); }, "mesh.obj", 4, "f",
                     {"degenerate face repeats vertex 2"});
  expect_input_error([] { parse("v 0 0 0\nv 1 0 0\nf 1 2\n"); }, "mesh.obj", 3, "f",
                     {"at least 3 corners (got 2)"});
}

// The file's size is checked before it is read: a sparse file past the limit
// costs nothing to refuse.
TEST(ObjTrianglesErrors, AFileBeyondItsBytesIsRefusedUnread) {
  const std::string path = test::scratch_path("large.obj");
  std::ofstream(path) << "v 0 0 0\n";
  std::filesystem::resize_file(path, 4097);
  expect_input_error(
      [&] {
        read_obj_triangles(path, {4096, kAny, kAny});
      },
      path, 0, "", {"larger than 4 KiB"});
}

}  // namespace
}  // namespace neurocloth
