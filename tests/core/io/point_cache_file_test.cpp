// The PC2 and MDD decoders the learning stage and deforming obstacles share:
// what they give from Blender's bytes, the clock's choices, the caller's
// limits in the messages. Every other refusal, field by field and byte by
// byte, is tested through the learning stage's reader
// (tests/learn/motion/point_cache_test.cpp).
#include "core/io/point_cache_file.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "support/blender_cache_bytes.h"
#include "support/input_error_check.h"

namespace neurocloth {
namespace {
using test::blender_mdd;
using test::blender_pc2;
using test::expect_input_error;
using test::pack_f32;
using test::pack_i32;

constexpr PointCacheLimits kLimits{10, 100, 1e3, "a test", "1e3 in a test"};

// Three vertices, frame k moved by k / 4 along x (exact in float32).
std::vector<std::vector<Vec3>> frames(int count) {
  std::vector<std::vector<Vec3>> out;
  for (int k = 0; k < count; ++k)
    out.push_back({Vec3(k / 4.0, 0, 0), Vec3(1 + k / 4.0, 0, 0.5), Vec3(k / 4.0, 2, -1)});
  return out;
}

TEST(PointCacheFile, DecodesAPc2AsWritten) {
  PointCacheClock clock;
  clock.fps = 24;
  clock.start = 0.5;
  const PointCacheFrames c =
      decode_pc2(blender_pc2(frames(3), 1.0f, 2.0f, false), "a.pc2", clock, kLimits);
  ASSERT_EQ(c.times.size(), 3u);
  ASSERT_EQ(c.positions.size(), 3u);
  EXPECT_EQ(c.vertices(), 3u);
  for (int k = 0; k < 3; ++k) {
    EXPECT_DOUBLE_EQ(c.times[k], 0.5 + k * 2.0 / 24);
    EXPECT_EQ(c.positions[k], frames(3)[k]);
  }
}

// An MDD's times with the start added, or shifted so its first is at the start.
TEST(PointCacheFile, AnMddsTimesFromItsFirstOrAsWritten) {
  std::string bytes = blender_mdd(frames(3), 4.0);  // 0, 0.25, 0.5 s
  std::string late;
  pack_f32(late, 10.0f, true);
  bytes.replace(8, 4, late);  // frame 0 at 10 s: going back
  PointCacheClock clock;
  expect_input_error([&] { decode_mdd(bytes, "a.mdd", clock, kLimits); }, "a.mdd", 0,
                     "frame 1 time", {"after frame 0's 10 s", "going back"});
  std::string early;
  pack_f32(early, -1.0f, true);
  bytes.replace(8, 4, early);  // -1, 0.25, 0.5 s
  clock.start_field = "--start";
  expect_input_error([&] { decode_mdd(bytes, "a.mdd", clock, kLimits); }, "a.mdd", 0,
                     "frame 0 time",
                     {"-1 s at byte 8 is before the scene's start (with --start 0)"});
  clock.start = 2;
  EXPECT_EQ(decode_mdd(bytes, "a.mdd", clock, kLimits).times, (std::vector<double>{1, 2.25, 2.5}));
  clock.mdd_from_first = true;
  const PointCacheFrames c = decode_mdd(bytes, "a.mdd", clock, kLimits);
  EXPECT_EQ(c.times, (std::vector<double>{2, 3.25, 3.5}));
  EXPECT_EQ(c.positions[2], frames(3)[2]);
}

TEST(PointCacheFile, TheCallersLimitsAreItsWords) {
  PointCacheClock clock;
  expect_input_error([&] { decode_mdd(blender_mdd(frames(11), 4.0), "a.mdd", clock, kLimits); },
                     "a.mdd", 0, "frame count",
                     {"11 at byte 0: more than the 10 frames a test may hold"});
  std::string wide;
  pack_i32(wide, 2, true);
  pack_i32(wide, 51, true);
  expect_input_error([&] { decode_mdd(wide, "a.mdd", clock, kLimits); }, "a.mdd", 0, "vertex count",
                     {"more than the 100 positions a test may hold"});
  std::vector<std::vector<Vec3>> far = frames(2);
  far[1][2].y() = -2000;
  expect_input_error([&] { decode_mdd(blender_mdd(far, 4.0), "a.mdd", clock, kLimits); }, "a.mdd",
                     0, "frame 1 vertex 2",
                     {"y at byte " + std::to_string(8 + 2 * 4 + (3 + 2) * 12 + 4) +
                      ": -2000 is beyond 1e3 in a test"});
}

TEST(PointCacheFile, TellsItsFormatByExtension) {
  PointCacheFormat f = PointCacheFormat::pc2;
  EXPECT_TRUE(point_cache_format("dir.pc2/run.MDD", f));
  EXPECT_EQ(f, PointCacheFormat::mdd);
  EXPECT_FALSE(point_cache_format("run.pc2.obj", f));
  EXPECT_FALSE(point_cache_format("pc2", f));
}

TEST(PointCacheFile, AVertexCountThatDiffersFromTheMeshsNamesBoth) {
  check_cache_vertex_count("a.mdd", 4, "m.obj", 4);
  expect_input_error([] { check_cache_vertex_count("a.mdd", 4, "m.obj", 5); }, "a.mdd", 0,
                     "vertex count",
                     {"the cache has 4 vertices, its mesh 'm.obj' 5: not the mesh it deforms"});
}

TEST(PointCacheFile, AZUpCacheIsToldByItsFirstFrame) {
  const std::vector<Vec3> mesh = frames(1)[0];
  std::vector<Vec3> z_up;
  for (const Vec3& p : mesh)
    z_up.push_back(test::blender_from_scene(p));
  double as_written = 0, turned = 0;
  EXPECT_TRUE(cache_is_z_up(z_up, mesh, as_written, turned));
  EXPECT_EQ(turned, 0);
  EXPECT_GT(as_written, 1);
  EXPECT_EQ(z_up_to_y_up(z_up[2]), mesh[2]);
  EXPECT_FALSE(cache_is_z_up(mesh, mesh, as_written, turned));
}

}  // namespace
}  // namespace neurocloth
