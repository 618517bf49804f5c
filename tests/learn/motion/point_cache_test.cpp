#include "learn/motion/point_cache.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "core/io/text_file.h"
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

// The scene's cloth: a 3 x 3 grid lying flat at y = 1 (Y-up), node r * 3 + c;
// frame k lowers it by k / 8 m and shifts each node's x by its number / 16
// (every value exact in float32).
constexpr int kCacheSide = 3;
constexpr std::size_t kCacheNodes = kCacheSide * kCacheSide;

std::vector<Vec3> scene_frame(int k) {
  std::vector<Vec3> p;
  for (int r = 0; r < kCacheSide; ++r)
    for (int c = 0; c < kCacheSide; ++c)
      p.emplace_back(0.5 * c + (k ? (r * kCacheSide + c) / 16.0 : 0), 1 - k / 8.0, 0.5 * r);
  return p;
}

std::vector<std::vector<Vec3>> in_blender(int frames) {
  std::vector<std::vector<Vec3>> out;
  for (int k = 0; k < frames; ++k) {
    out.emplace_back();
    for (const Vec3& p : scene_frame(k))
      out.back().push_back(blender_from_scene(p));
  }
  return out;
}

ReferenceOptions cache_options(double fps, double start = 0) {
  ReferenceOptions o;
  o.fps = fps;
  o.start = start;
  o.mesh = "cloth.obj";
  o.scene_positions = scene_frame(0);
  return o;
}

ReferenceMotion read_cache(const std::string& bytes, PointCacheFormat format,
                           const ReferenceOptions& o) {
  return parse_point_cache(bytes, format == PointCacheFormat::pc2 ? "cloth.pc2" : "cloth.mdd",
                           format, scene_frame(0), "cloth.obj", kCacheNodes, o);
}

void expect_every_node_as_in_the_scene(const ReferenceMotion& m, int frames) {
  EXPECT_EQ(m.source, ReferenceMotion::Source::cache);
  ASSERT_EQ(m.frames.size(), std::size_t(frames));
  for (int k = 0; k < frames; ++k) {
    ASSERT_EQ(m.frames[k].nodes.size(), kCacheNodes);
    const std::vector<Vec3> expected = scene_frame(k);
    for (std::size_t n = 0; n < kCacheNodes; ++n) {
      EXPECT_EQ(m.frames[k].nodes[n], std::int32_t(n));
      EXPECT_EQ(m.frames[k].positions[n], expected[n]) << "frame " << k << " node " << n;
    }
  }
}

// Blender's default PC2 export: its Z-up object turned to Y-up, which is the
// scene's; no frame rate in the file, so --reference-fps spaces the samples.
TEST(PointCache, ReadsAPc2AsBlenderWritesIt) {
  const std::string bytes = blender_pc2(in_blender(3), 1.0f, 1.0f);
  ASSERT_EQ(bytes.size(), 32u + 3 * kCacheNodes * 12);
  const ReferenceMotion m = read_cache(bytes, PointCacheFormat::pc2, cache_options(24, 0.25));
  expect_every_node_as_in_the_scene(m, 3);
  for (int k = 0; k < 3; ++k)
    EXPECT_DOUBLE_EQ(m.frames[k].time, 0.25 + k / 24.0);
  EXPECT_NE(m.note.find("read as written (Y-up)"), std::string::npos) << m.note;
  EXPECT_NE(m.note.find("vertex k is node k"), std::string::npos) << m.note;
}

// Sampling 0.5 frames per sample: two samples a frame.
TEST(PointCache, Pc2SamplingSpacesItsSamples) {
  const ReferenceMotion m =
      read_cache(blender_pc2(in_blender(3), 1.0f, 0.5f), PointCacheFormat::pc2, cache_options(30));
  ASSERT_EQ(m.frames.size(), 3u);
  EXPECT_DOUBLE_EQ(m.frames[2].time, 2 * 0.5 / 30);
}

// "Convert to Y-up" off: the cache is Blender's Z-up, and is turned.
TEST(PointCache, AZUpPc2IsTurned) {
  const ReferenceMotion m = read_cache(blender_pc2(in_blender(2), 1.0f, 1.0f, false),
                                       PointCacheFormat::pc2, cache_options(24));
  expect_every_node_as_in_the_scene(m, 2);
  EXPECT_NE(m.note.find("turned from Z-up"), std::string::npos) << m.note;
}

// Blender's MDD: world space, Z-up, its own times (frame / fps as float32).
TEST(PointCache, ReadsAnMddAsBlenderWritesIt) {
  const ReferenceMotion m =
      read_cache(blender_mdd(in_blender(4), 25.0), PointCacheFormat::mdd, cache_options(0, 1));
  expect_every_node_as_in_the_scene(m, 4);
  for (int k = 0; k < 4; ++k)
    EXPECT_EQ(m.frames[k].time, 1 + double(float(k / 25.0)));
  EXPECT_NE(m.note.find("turned from Z-up to Y-up, (x, y, z) -> (x, z, -y)"), std::string::npos)
      << m.note;
  EXPECT_EQ(m.note.find("--reference-fps"), std::string::npos) << m.note;
}

// A frame rate given beside an MDD's times: the times win, and the note says so.
TEST(PointCache, AnMddKeepsItsTimesOverADisagreeingFrameRate) {
  const std::string bytes = blender_mdd(in_blender(4), 25.0);
  const ReferenceMotion agreeing = read_cache(bytes, PointCacheFormat::mdd, cache_options(25));
  EXPECT_EQ(agreeing.note.find("--reference-fps"), std::string::npos) << agreeing.note;
  const ReferenceMotion m = read_cache(bytes, PointCacheFormat::mdd, cache_options(30));
  EXPECT_EQ(m.frames[3].time, double(float(3 / 25.0)));
  EXPECT_NE(m.note.find("its own times kept, not --reference-fps 30"), std::string::npos) << m.note;
  EXPECT_NE(m.note.find("25 frames per second"), std::string::npos) << m.note;
}

TEST(PointCache, TellsItsFormatByExtension) {
  PointCacheFormat f = PointCacheFormat::mdd;
  EXPECT_TRUE(point_cache_format("a/run.PC2", f));
  EXPECT_EQ(f, PointCacheFormat::pc2);
  EXPECT_TRUE(point_cache_format("run.mdd", f));
  EXPECT_EQ(f, PointCacheFormat::mdd);
  EXPECT_FALSE(point_cache_format("run.obj", f));
}

// The fuzzer's seeds (tests/fuzz/corpus/point_cache) are caches of its
// square mesh (0,1,0) (1,1,0) (1,1,1) (0,1,1) that this reader accepts.
TEST(PointCache, ReadsTheFuzzSeeds) {
  const std::vector<Vec3> square = {Vec3(0, 1, 0), Vec3(1, 1, 0), Vec3(1, 1, 1), Vec3(0, 1, 1)};
  const std::filesystem::path seeds =
      std::filesystem::path(NEUROCLOTH_TEST_DATA) / ".." / "fuzz" / "corpus" / "point_cache";
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(seeds)) {
    const std::string path = entry.path().string();
    PointCacheFormat format = PointCacheFormat::pc2;
    ASSERT_TRUE(point_cache_format(path, format)) << path;
    ReferenceOptions o = cache_options(30);
    o.scene_positions = square;
    const ReferenceMotion m = parse_point_cache(read_text_file(path, "seed", 1 << 20), path, format,
                                                square, "square.obj", 4, o);
    EXPECT_GE(m.frames.size(), 2u) << path;
    EXPECT_EQ(m.frames[0].positions, square) << path;
    ++files;
  }
  EXPECT_EQ(files, 3);
}

// The cache and its mesh as files: the OBJ Blender writes beside it.
void write_obj(const std::string& path, const std::vector<Vec3>& vertices) {
  std::ofstream out(path);
  out << "# Blender 3.4 OBJ File\no Grid\n";
  for (const Vec3& v : vertices)
    out << "v " << v.x() << " " << v.y() << " " << v.z() << "\n";
  out << "f 1 2 5\nf 1 5 4\n";
}

void write_bytes(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

TEST(PointCache, ReadsTheCacheAndItsMeshFromFiles) {
  const std::string mesh = scratch_path("cloth.obj"), cache = scratch_path("cloth.mdd");
  write_obj(mesh, scene_frame(0));
  write_bytes(cache, blender_mdd(in_blender(2), 24.0));
  ReferenceOptions o = cache_options(0);
  o.mesh = mesh;
  expect_every_node_as_in_the_scene(read_point_cache(cache, kCacheNodes, o), 2);
}

TEST(PointCacheErrors, TheMeshIsRequiredAndMustFit) {
  const std::string mesh = scratch_path("cloth.obj"), cache = scratch_path("cloth.pc2");
  write_bytes(cache, blender_pc2(in_blender(2), 1, 1));
  ReferenceOptions o = cache_options(24);
  o.mesh.clear();
  expect_input_error([&] { read_point_cache(cache, kCacheNodes, o); }, cache, 0, "--reference-mesh",
                     {"needs the mesh it deforms"});
  // A mesh of 8 vertices for a cache of 9.
  std::vector<Vec3> fewer = scene_frame(0);
  fewer.pop_back();
  write_obj(mesh, fewer);
  o.mesh = mesh;
  o.scene_positions.clear();
  expect_input_error([&] { read_point_cache(cache, kCacheNodes, o); }, cache, 0, "vertex count",
                     {"the cache has 9 vertices, its mesh '" + mesh + "' 8"});
  // Cache and mesh agree, the scene does not.
  write_obj(mesh, scene_frame(0));
  expect_input_error([&] { read_point_cache(cache, 16, o); }, cache, 0, "vertex count",
                     {"'" + mesh + "' have 9 vertices, the scene's cloth 16 nodes"});
  // A PC2 has no times without a frame rate.
  o.fps = 0;
  expect_input_error([&] { read_point_cache(cache, kCacheNodes, o); }, cache, 0, "--reference-fps",
                     {"a PC2 cache holds no frame rate"});
}

// PC2 bytes with one field changed: `at` the byte, `v` the value.
std::string pc2_with(std::size_t at, std::int32_t v) {
  std::string b = blender_pc2(in_blender(2), 1, 1);
  std::string field;
  pack_i32(field, v, false);
  return b.replace(at, 4, field);
}

std::string pc2_with_float(std::size_t at, float v) {
  std::string b = blender_pc2(in_blender(2), 1, 1);
  std::string field;
  pack_f32(field, v, false);
  return b.replace(at, 4, field);
}

void expect_pc2_error(const std::string& bytes, const std::string& field,
                      std::initializer_list<std::string> mentions) {
  expect_input_error([&] { parse_pc2(bytes, "run.pc2", cache_options(24)); }, "run.pc2", 0, field,
                     mentions);
}

TEST(PointCacheErrors, ABadPc2HeaderIsNamedByField) {
  std::string magic = blender_pc2(in_blender(1), 1, 1);
  magic[10] = '3';
  expect_pc2_error(magic, "magic", {"not a PC2 cache", "'POINTCACHE3\\x00'"});
  expect_pc2_error(pc2_with(12, 2), "version", {"2 at byte 12", "version 1"});
  expect_pc2_error(pc2_with(16, 0), "vertex count", {"0 at byte 16: must be > 0"});
  expect_pc2_error(pc2_with(16, -9), "vertex count", {"-9 at byte 16"});
  expect_pc2_error(pc2_with(28, 0), "sample count", {"0 at byte 28"});
  expect_pc2_error(pc2_with_float(24, 0), "sampling", {"0 at byte 24", "> 0"});
  expect_pc2_error(pc2_with_float(24, -1), "sampling", {"-1 at byte 24"});
  expect_pc2_error(pc2_with_float(24, NAN), "sampling", {"nan at byte 24"});
  expect_pc2_error(pc2_with_float(20, INFINITY), "start frame", {"at byte 20"});
  expect_pc2_error(std::string("POINTCACHE2\0\1\0\0\0", 16), "header",
                   {"ends at byte 16 inside the 32-byte header"});
}

// A header whose counts the file does not hold is refused before anything is
// allocated, where the file ends.
TEST(PointCacheErrors, APc2CountThatLiesIsNamedWithTheByte) {
  std::string b = blender_pc2(in_blender(3), 1, 1);
  std::string ten;
  pack_i32(ten, 10, false);
  b = b.replace(28, 4, ten).substr(0, 32 + kCacheNodes * 12 * 2 + 4 * 12 + 5);
  expect_pc2_error(b, "sample count",
                   {"ends at byte " + std::to_string(b.size()) + " in sample 2 vertex 4 of 10"});
  const std::string tail = blender_pc2(in_blender(2), 1, 1) + "abc";
  expect_pc2_error(tail, "sample count",
                   {"3 bytes after the last sample, from byte " + std::to_string(tail.size() - 3)});
  expect_pc2_error(pc2_with(16, 1 << 30), "vertex count", {"more than the 33554432 positions"});
  expect_pc2_error(pc2_with(28, (1 << 20) + 1), "sample count", {"1048577 at byte 28"});
  expect_pc2_error(pc2_with(28, 1 << 20), "sample count", {"ends at byte"});
}

TEST(PointCacheErrors, BadPc2CoordinatesAreNamedWithSampleVertexAndByte) {
  // Sample 1, vertex 2, y: byte 32 + (9 + 2) * 12 + 4.
  const std::size_t at = 32 + (kCacheNodes + 2) * 12 + 4;
  expect_pc2_error(pc2_with_float(at, NAN), "sample 1 vertex 2",
                   {"y at byte " + std::to_string(at) + ": NaN or infinite"});
  expect_pc2_error(pc2_with_float(at + 4, -3e6f), "sample 1 vertex 2",
                   {"z at byte " + std::to_string(at + 4), "-3e+06 is beyond 1e6 m"});
}

std::string mdd_with_float(std::size_t at, float v) {
  std::string b = blender_mdd(in_blender(3), 25.0);
  std::string field;
  pack_f32(field, v, true);
  return b.replace(at, 4, field);
}

void expect_mdd_error(const std::string& bytes, const std::string& field,
                      std::initializer_list<std::string> mentions) {
  expect_input_error([&] { parse_mdd(bytes, "run.mdd", cache_options(0)); }, "run.mdd", 0, field,
                     mentions);
}

TEST(PointCacheErrors, AnMddFrameGoingBackIsNamed) {
  // Times at bytes 8, 12, 16: frame 2's set back to before frame 1's.
  expect_mdd_error(mdd_with_float(16, 0.01f), "frame 2 time",
                   {"at byte 16 after frame 1's 0.04 s", "going back"});
  expect_mdd_error(mdd_with_float(16, 0.04f), "frame 2 time", {"repeating"});
  expect_mdd_error(mdd_with_float(12, NAN), "frame 1 time", {"NaN or infinite at byte 12"});
  expect_mdd_error(mdd_with_float(8, -1), "frame 0 time", {"before the scene's start"});
}

TEST(PointCacheErrors, AnMddCountThatLiesIsNamedWithTheByte) {
  std::string counts;
  pack_i32(counts, 100, true);
  pack_i32(counts, 9, true);
  expect_mdd_error(counts + std::string(40, '\0'), "frame count",
                   {"ends at byte 48 in the time of frame 10 of 100"});
  const std::string b = blender_mdd(in_blender(3), 25.0);
  expect_mdd_error(b.substr(0, b.size() - 1), "frame count",
                   {"ends at byte " + std::to_string(b.size() - 1) + " in frame 2 vertex 8 of 3"});
  expect_mdd_error(b + "x", "frame count", {"1 byte after the last frame"});
  std::string zero;
  pack_i32(zero, 0, true);
  pack_i32(zero, 9, true);
  expect_mdd_error(zero, "frame count", {"0 at byte 0"});
  std::string no_vertices;
  pack_i32(no_vertices, 1, true);
  pack_i32(no_vertices, -1, true);
  expect_mdd_error(no_vertices, "vertex count", {"-1 at byte 4"});
  std::string huge;
  pack_i32(huge, 1 << 20, true);
  pack_i32(huge, 1 << 20, true);
  expect_mdd_error(huge, "vertex count", {"more than the 33554432 positions"});
  expect_mdd_error(std::string("\0\0\0\1", 4), "header",
                   {"ends at byte 4 inside the 8-byte header"});
}

TEST(PointCacheErrors, BadMddCoordinatesAreNamedWithFrameVertexAndByte) {
  // Frame 1, vertex 0, x: byte 8 + 3 * 4 + 9 * 12.
  const std::size_t at = 8 + 3 * 4 + kCacheNodes * 12;
  expect_mdd_error(mdd_with_float(at, INFINITY), "frame 1 vertex 0",
                   {"x at byte " + std::to_string(at) + ": NaN or infinite"});
}

}  // namespace
}  // namespace neurocloth
