// A mesh obstacle's files read and placed: the OBJ scaled, rotated and moved;
// a PC2 or MDD cache's frames placed alike, turned Y-up when Blender wrote
// them Z-up, timed from 0; every bad file refused with its name and the line,
// field or byte. The files are written here, small, into the test's folder.
#include "core/modules/obstacle_mesh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/io/input_error.h"
#include "support/blender_cache_bytes.h"
#include "support/input_error_check.h"
#include "support/scratch_dir.h"

namespace neurocloth {
namespace {
using test::blender_from_scene;
using test::blender_mdd;
using test::blender_pc2;
using test::expect_input_error;
using test::pack_f32;
using test::pack_i32;
using test::scratch_path;

// The cube [-1, 1]^3 in quads wound counter-clockwise seen from outside.
const std::vector<Vec3> kCube = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                                 {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
const char* const kCubeFaces = "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 4 8 7 3\nf 1 5 8 4\nf 2 3 7 6\n";

std::string write_file(const std::string& name, const std::string& bytes) {
  const std::string path = scratch_path(name);
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
  return path;
}

std::string obj_text(const std::vector<Vec3>& vertices, const std::string& faces) {
  std::string text = "# Blender 4.1\no Cube\n";
  for (const Vec3& v : vertices)
    text += "v " + std::to_string(v.x()) + " " + std::to_string(v.y()) + " " +
            std::to_string(v.z()) + "\n";
  return text + faces;
}

std::string cube_obj() {
  return write_file("cube.obj", obj_text(kCube, kCubeFaces));
}

// Half size, a quarter turn about y, then moved.
ObstacleFiles placed(const std::string& obj) {
  ObstacleFiles f;
  f.obj = obj;
  f.scale = 0.5;
  f.placement.rotation = euler_xyz_degrees(Vec3(0, 90, 0));
  f.placement.translation = Vec3(1, 2, 3);
  return f;
}

// Where `placed` puts a point of the file (y-rotation by 90 degrees: (x, y, z)
// -> (z, y, -x)), worked out by hand.
Vec3 by_hand(const Vec3& p) {
  return Vec3(0.5 * p.z() + 1, 0.5 * p.y() + 2, -0.5 * p.x() + 3);
}

void expect_near(const std::vector<Vec3>& got, const std::vector<Vec3>& want, const char* what) {
  ASSERT_EQ(got.size(), want.size()) << what;
  for (std::size_t k = 0; k < got.size(); ++k)
    EXPECT_LT((got[k] - want[k]).norm(), 1e-14)
        << what << " vertex " << k << ": " << got[k].transpose();
}

std::vector<Vec3> placed_by_hand(const std::vector<Vec3>& points) {
  std::vector<Vec3> out;
  for (const Vec3& p : points)
    out.push_back(by_hand(p));
  return out;
}

TEST(ObstacleMesh, TheObjIsScaledThenRotatedThenMoved) {
  const std::string obj = cube_obj();
  const auto mesh = read_obstacle_mesh(placed(obj));
  EXPECT_EQ(mesh->obj_path, obj);
  EXPECT_FALSE(mesh->deforms());
  EXPECT_TRUE(mesh->note.empty()) << mesh->note;
  expect_near(mesh->surface.vertices, placed_by_hand(kCube), "placed");
  // Two triangles a quad, each of its own face's corners.
  const std::vector<std::vector<int>> faces = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                               {3, 7, 6, 2}, {0, 4, 7, 3}, {1, 2, 6, 5}};
  ASSERT_EQ(mesh->surface.triangles.size(), 12u);
  for (std::size_t t = 0; t < 12; ++t)
    for (std::int32_t v : mesh->surface.triangles[t])
      EXPECT_NE(std::find(faces[t / 2].begin(), faces[t / 2].end(), v), faces[t / 2].end())
          << "triangle " << t;
}

// Needs finish_surface (core/geometry/triangle_surface.cpp): a cube read from
// quads is closed and its normals point out.
TEST(ObstacleMesh, ACubeOfQuadsIsClosed) {
  const auto mesh = read_obstacle_mesh(placed(cube_obj()));
  const TriangleSurface& s = mesh->surface;
  EXPECT_TRUE(s.closed);
  ASSERT_EQ(s.face_normals.size(), s.triangles.size());
  const Vec3 centre = by_hand(Vec3::Zero());
  for (std::size_t t = 0; t < s.triangles.size(); ++t)
    EXPECT_GT(s.face_normals[t].dot(s.vertices[s.triangles[t][0]] - centre), 0) << "triangle " << t;
}

// A triangle of zero area beside good ones is kept (finish_surface gives it no
// normal); a mesh of nothing else is refused.
TEST(ObstacleMesh, ADegenerateTriangleBesideGoodOnesIsKept) {
  const auto mesh = read_obstacle_mesh(
      placed(write_file("sliver.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\nf 1 2 3\nf 1 2 4\n")));
  EXPECT_EQ(mesh->surface.triangles.size(), 2u);
}

TEST(ObstacleMeshErrors, AnObjWithoutASurfaceIsNamedWithItsLine) {
  const std::string head = "# a tool\nv 0 0 0\nv 1 0 0\nv 0 1 0\n";
  std::string path = write_file("no_faces.obj", head);
  expect_input_error([&] { read_obstacle_mesh(placed(path)); }, path, 0, "f", {"no faces"});
  path = write_file("nan.obj", head + "v 0 nan 1\nf 1 2 3\n");
  expect_input_error([&] { read_obstacle_mesh(placed(path)); }, path, 5, "v",
                     {"vertex 4 (y): 'nan' is not a finite number"});
  path = write_file("word.obj", "v 0 0 0\nv one 0 0\nv 0 1 0\nf 1 2 3\n");
  expect_input_error([&] { read_obstacle_mesh(placed(path)); }, path, 2, "v",
                     {"vertex 2 (x): 'one'"});
  path = write_file("inf.obj", "v 0 0 0\nv 1 0 0\nv 0 1 inf\nf 1 2 3\n");
  expect_input_error([&] { read_obstacle_mesh(placed(path)); }, path, 3, "v", {"'inf'"});
  // Collinear corners, and corners that coincide: no triangle has an area.
  path = write_file("line.obj", head + "v 0.3 0.6 0.9\nv 0.1 0.2 0.3\nf 1 4 5\nv 0 1 0\nf 5 4 1\n");
  expect_input_error([&] { read_obstacle_mesh(placed(path)); }, path, 0, "f",
                     {"every one of its 2 triangles (lines 7 to 9) has zero area"});
  path = write_file("point.obj", "v 1 1 1\nv 1 1 1\nv 1 1 1\nf 1 2 3\n");
  expect_input_error([&] { read_obstacle_mesh(placed(path)); }, path, 0, "f", {"zero area"});
}

TEST(ObstacleMeshErrors, AnObjBeyondTheLimitsIsRefused) {
  // 256-corner faces make 254 triangles each: one more face than the limit allows.
  std::string face = "f";
  for (int k = 1; k <= 256; ++k)
    face += " " + std::to_string(k);
  face += "\n";
  std::string text;
  for (int k = 0; k < 256; ++k)
    text += "v " + std::to_string(std::cos(k)) + " " + std::to_string(std::sin(k)) + " 0\n";
  const std::size_t faces = kMaxObstacleTriangles / 254 + 1;
  text.reserve(text.size() + faces * face.size());
  for (std::size_t k = 0; k < faces; ++k)
    text += face;
  std::string path = write_file("many.obj", text);
  expect_input_error([&] { read_obstacle_mesh(placed(path)); }, path, static_cast<int>(256 + faces),
                     "f", {"more than 2 million triangles"});
  // Its size is refused before it is read (a sparse file).
  path = write_file("large.obj", "v 0 0 0\n");
  std::filesystem::resize_file(path, kMaxObstacleBytes + 1);
  expect_input_error([&] { read_obstacle_mesh(placed(path)); }, path, 0, "",
                     {"larger than 256 MiB"});
}

// The cube deforming: frame k grows it by k / 4 (every value exact in float32).
std::vector<std::vector<Vec3>> growing_cube(int frames) {
  std::vector<std::vector<Vec3>> out;
  for (int k = 0; k < frames; ++k) {
    out.emplace_back();
    for (const Vec3& v : kCube)
      out.back().push_back((1 + k / 4.0) * v);
  }
  return out;
}

// The same in Blender's coordinates (Z-up).
std::vector<std::vector<Vec3>> in_blender(const std::vector<std::vector<Vec3>>& frames) {
  std::vector<std::vector<Vec3>> out;
  for (const auto& frame : frames) {
    out.emplace_back();
    for (const Vec3& p : frame)
      out.back().push_back(blender_from_scene(p));
  }
  return out;
}

ObstacleFiles with_cache(const std::string& name, const std::string& bytes, double fps = 0) {
  ObstacleFiles f = placed(cube_obj());
  f.cache = write_file(name, bytes);
  f.cache_fps = fps;
  return f;
}

void expect_frames(const ObstacleMesh& mesh, const std::vector<std::vector<Vec3>>& frames) {
  ASSERT_EQ(mesh.frames.size(), frames.size());
  ASSERT_EQ(mesh.frame_times.size(), frames.size());
  for (std::size_t k = 0; k < frames.size(); ++k)
    expect_near(mesh.frames[k], placed_by_hand(frames[k]), ("frame " + std::to_string(k)).c_str());
}

// Blender's default PC2: Y-up already. Sample k at k * sampling / cache_fps.
TEST(ObstacleMesh, APc2IsPlacedAndTimedFromZero) {
  const ObstacleFiles f =
      with_cache("cube.pc2", blender_pc2(in_blender(growing_cube(3)), 7, 2), 24);
  const auto mesh = read_obstacle_mesh(f);
  EXPECT_TRUE(mesh->deforms());
  EXPECT_EQ(mesh->cache_path, f.cache);
  expect_frames(*mesh, growing_cube(3));
  EXPECT_EQ(mesh->frame_times, (std::vector<double>{0, 2 / 24.0, 4 / 24.0}));
  EXPECT_NE(mesh->note.find("read as written (Y-up)"), std::string::npos) << mesh->note;
  expect_near(mesh->surface.vertices, placed_by_hand(kCube), "the undeformed surface");
}

// Blender's MDD: world space, Z-up, its own times (here from frame 10 at 24
// frames per second): turned to Y-up, its times shifted to start at 0.
TEST(ObstacleMesh, ABlenderMddIsTurnedYUpAndStartsAtZero) {
  std::string bytes = blender_mdd(in_blender(growing_cube(3)), 24);
  for (int k = 0; k < 3; ++k) {
    std::string t;
    pack_f32(t, static_cast<float>((10 + k) / 24.0), true);
    bytes.replace(8 + 4 * k, 4, t);
  }
  const auto mesh = read_obstacle_mesh(with_cache("cube.mdd", bytes, 30));
  expect_frames(*mesh, growing_cube(3));
  ASSERT_EQ(mesh->frame_times.size(), 3u);
  EXPECT_EQ(mesh->frame_times[0], 0);
  for (int k = 1; k < 3; ++k)
    EXPECT_NEAR(mesh->frame_times[k], k / 24.0, 1e-6) << "frame " << k;
  EXPECT_NE(mesh->note.find("turned from Z-up to Y-up"), std::string::npos) << mesh->note;
}

// "Convert to Y-up" off in Blender's PC2 exporter: Z-up, turned.
TEST(ObstacleMesh, AZUpPc2IsTurned) {
  const auto mesh = read_obstacle_mesh(
      with_cache("cube.pc2", blender_pc2(in_blender(growing_cube(2)), 1, 1, false), 25));
  expect_frames(*mesh, growing_cube(2));
  EXPECT_NE(mesh->note.find("turned from Z-up"), std::string::npos) << mesh->note;
}

TEST(ObstacleMeshErrors, ACacheThatIsNotTheObjsIsNamed) {
  std::vector<std::vector<Vec3>> fewer = growing_cube(2);
  for (auto& frame : fewer)
    frame.pop_back();
  ObstacleFiles f = with_cache("cube.pc2", blender_pc2(fewer, 1, 1), 24);
  expect_input_error([&] { read_obstacle_mesh(f); }, f.cache, 0, "vertex count",
                     {"the cache has 7 vertices, its mesh '" + f.obj + "' 8"});
  f = with_cache("cube.pc2", blender_pc2(growing_cube(2), 1, 1));
  expect_input_error([&] { read_obstacle_mesh(f); }, f.cache, 0, "cache_fps",
                     {"a PC2 cache holds no frame rate"});
  f.cache_fps = 1e9;
  expect_input_error([&] { read_obstacle_mesh(f); }, f.cache, 0, "cache_fps", {"1e+09"});
  f = with_cache("cube.abc", "Alembic");
  expect_input_error([&] { read_obstacle_mesh(f); }, f.cache, 0, "cache", {".pc2 or .mdd"});
  f.cache = scratch_path("missing.mdd");
  expect_input_error([&] { read_obstacle_mesh(f); }, f.cache, 0, "", {"cannot open point cache"});
}

TEST(ObstacleMeshErrors, ABadCacheIsNamedWithItsFieldAndByte) {
  // Frame 2's time set back before frame 1's.
  std::string bytes = blender_mdd(growing_cube(3), 24);
  std::string t;
  pack_f32(t, 0.01f, true);
  ObstacleFiles f = with_cache("cube.mdd", bytes.replace(16, 4, t));
  expect_input_error([&] { read_obstacle_mesh(f); }, f.cache, 0, "frame 2 time",
                     {"at byte 16", "going back"});
  // Frame 1, vertex 3, z: NaN.
  bytes = blender_mdd(growing_cube(3), 24);
  const std::size_t at = 8 + 3 * 4 + (8 + 3) * 12 + 8;
  std::string nan;
  pack_f32(nan, NAN, true);
  f = with_cache("cube.mdd", bytes.replace(at, 4, nan));
  expect_input_error([&] { read_obstacle_mesh(f); }, f.cache, 0, "frame 1 vertex 3",
                     {"z at byte " + std::to_string(at) + ": NaN or infinite"});
  // More frames than an obstacle's cache may hold, refused from the header.
  std::string header;
  pack_i32(header, static_cast<std::int32_t>(kMaxObstacleCacheFrames + 1), true);
  pack_i32(header, 8, true);
  f = with_cache("long.mdd", header);
  expect_input_error([&] { read_obstacle_mesh(f); }, f.cache, 0, "frame count",
                     {"more than the 100000 frames an obstacle's cache may hold"});
  // A coordinate beyond what any unit allows.
  std::vector<std::vector<Vec3>> far = growing_cube(2);
  far[1][0].x() = 3e10;
  f = with_cache("far.pc2", blender_pc2(far, 1, 1, false), 24);
  expect_input_error([&] { read_obstacle_mesh(f); }, f.cache, 0, "sample 1 vertex 0",
                     {"x at byte " + std::to_string(32 + 8 * 12), "beyond +-1e10 in any unit"});
}

}  // namespace
}  // namespace neurocloth
