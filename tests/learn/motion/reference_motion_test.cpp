#include "learn/motion/reference_motion.h"
#include "learn/motion/read_reference.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "support/blender_cache_bytes.h"
#include "support/input_error_check.h"
#include "support/scratch_dir.h"

namespace neurocloth {
namespace {
namespace fs = std::filesystem;
using test::expect_input_error;
using test::scratch_dir;

void write_file(const fs::path& path, const std::string& bytes) {
  fs::create_directories(path.parent_path());
  std::ofstream(path, std::ios::binary) << bytes;
}

ReferenceOptions fps_start(double fps, double start) {
  ReferenceOptions o;
  o.fps = fps;
  o.start = start;
  return o;
}

const std::string kOnePointPly =
    "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
    "property float z\nend_header\n1 2 3\n";

// What the path is decides the reader: a folder or a pattern is a sequence,
// .ply / .xyz one cloud frame, .pc2 / .mdd a cache, anything else by its bytes.
TEST(ReferenceMotion, ReadsEachKindOfPathWithItsReader) {
  const fs::path dir = scratch_dir();
  write_file(dir / "seq" / "f_1.xyz", "0 0 0\n");
  write_file(dir / "seq" / "f_3.xyz", "1 1 1\n");
  const ReferenceMotion folder = read_reference((dir / "seq").string(), 4, fps_start(2, 1));
  EXPECT_EQ(folder.source, ReferenceMotion::Source::cloud);
  ASSERT_EQ(folder.frames.size(), 2u);
  EXPECT_EQ(folder.frames[1].time, 2.0);
  const ReferenceMotion pattern =
      read_reference((dir / "seq" / "f_%d.xyz").string(), 4, fps_start(2, 0));
  EXPECT_EQ(pattern.frames.size(), 2u);

  write_file(dir / "one.ply", kOnePointPly);
  const ReferenceMotion ply = read_reference((dir / "one.ply").string(), 4, fps_start(0, 0.5));
  EXPECT_EQ(ply.source, ReferenceMotion::Source::cloud);
  ASSERT_EQ(ply.frames.size(), 1u);
  EXPECT_EQ(ply.frames[0].time, 0.5);
  EXPECT_EQ(ply.frames[0].positions, std::vector<Vec3>{Vec3(1, 2, 3)});
  write_file(dir / "one.XYZ", "4 5 6\n");
  EXPECT_EQ(read_reference((dir / "one.XYZ").string(), 4).frames[0].positions,
            std::vector<Vec3>{Vec3(4, 5, 6)});

  // A cache of 4 vertices with its mesh: a square at y = 0.5.
  const std::vector<Vec3> square = {Vec3(0, 0.5, 0), Vec3(1, 0.5, 0), Vec3(1, 0.5, 1),
                                    Vec3(0, 0.5, 1)};
  write_file(dir / "square.obj", "v 0 0.5 0\nv 1 0.5 0\nv 1 0.5 1\nv 0 0.5 1\nf 1 2 3\nf 1 3 4\n");
  write_file(dir / "square.pc2", test::blender_pc2({square, square}, 1, 1, false));
  ReferenceOptions o = fps_start(10, 0);
  o.mesh = (dir / "square.obj").string();
  o.scene_positions = square;
  const ReferenceMotion cache = read_reference((dir / "square.pc2").string(), 4, o);
  EXPECT_EQ(cache.source, ReferenceMotion::Source::cache);
  ASSERT_EQ(cache.frames.size(), 2u);
  EXPECT_EQ(cache.frames[1].time, 0.1);
  EXPECT_EQ(cache.frames[1].positions, square);
  EXPECT_FALSE(cache.note.empty());

  write_file(dir / "markers.txt", "time,node,x,y,z\n0,3,1,2,3\n");
  EXPECT_EQ(read_reference((dir / "markers.txt").string(), 4).source,
            ReferenceMotion::Source::markers);
}

// What the command line leaves out is named by its option.
TEST(ReferenceMotionErrors, AMissingOptionIsNamed) {
  const fs::path dir = scratch_dir();
  write_file(dir / "seq" / "f_1.xyz", "0 0 0\n");
  expect_input_error([&] { read_reference((dir / "seq").string(), 4); }, (dir / "seq").string(), 0,
                     "--reference-fps", {"holds no times"});
  write_file(dir / "run.mdd", test::blender_mdd({{Vec3(0, 0, 0)}}, 24));
  expect_input_error([&] { read_reference((dir / "run.mdd").string(), 1); },
                     (dir / "run.mdd").string(), 0, "--reference-mesh");
  write_file(dir / "one.ply", kOnePointPly);
  expect_input_error([&] { read_reference((dir / "one.ply").string(), 1, fps_start(0, -1)); },
                     (dir / "one.ply").string(), 0, "--reference-start");
}

}  // namespace
}  // namespace neurocloth
