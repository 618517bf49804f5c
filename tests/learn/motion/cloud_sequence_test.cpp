#include "learn/motion/cloud_sequence.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "support/input_error_check.h"
#include "support/scratch_dir.h"

namespace neurocloth {
namespace {
namespace fs = std::filesystem;
using test::expect_input_error;
using test::scratch_dir;

void write(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream(path, std::ios::binary) << text;
}

// An XYZ frame whose points say which file they came from.
std::string xyz_frame(int number) {
  return std::to_string(number) + " 1 0\n" + std::to_string(number) + " 1 1\n";
}

std::string ply_frame(int number) {
  return "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
         "property float z\nend_header\n" +
         std::to_string(number) + " 2 3\n";
}

ReferenceOptions at_fps(double fps, double start = 0) {
  ReferenceOptions o;
  o.fps = fps;
  o.start = start;
  return o;
}

// frame_9 before frame_10 (not as names sort), frame 11 missing: a dropped
// frame, its time left out. Files of other kinds in the folder are left alone.
TEST(CloudSequence, AFolderIsReadInNumberOrderWithDroppedFrames) {
  const fs::path dir = scratch_dir() / "scans";
  for (int n : {12, 9, 10})
    write(dir / ("frame_" + std::to_string(n) + ".xyz"), xyz_frame(n));
  write(dir / "notes.txt", "captured on a Tuesday\n");
  write(dir / "camera.json", "{}\n");
  const ReferenceMotion m = read_cloud_sequence(dir.string(), at_fps(10, 0.5));
  EXPECT_EQ(m.source, ReferenceMotion::Source::cloud);
  EXPECT_EQ(m.path, dir.string());
  ASSERT_EQ(m.frames.size(), 3u);
  const int numbers[] = {9, 10, 12};
  const double times[] = {0.5, 0.6, 0.8};
  for (std::size_t f = 0; f < 3; ++f) {
    EXPECT_DOUBLE_EQ(m.frames[f].time, times[f]);
    EXPECT_TRUE(m.frames[f].nodes.empty());
    ASSERT_EQ(m.frames[f].positions.size(), 2u);
    EXPECT_EQ(m.frames[f].positions[1], Vec3(numbers[f], 1, 1));
  }
}

// A pattern picks its files out of a folder that holds others: "%04d" wants
// at least four digits, the prefix and the extension must match.
TEST(CloudSequence, APatternReadsTheFilesItNames) {
  const fs::path dir = scratch_dir() / "scans";
  write(dir / "frame_0001.ply", ply_frame(1));
  write(dir / "frame_0003.ply", ply_frame(3));
  write(dir / "frame_12345.ply", ply_frame(12345));
  write(dir / "frame_2.ply", "not read\n");
  write(dir / "frame_0002.xyz", "not read\n");
  write(dir / "other_0002.ply", "not read\n");
  const std::vector<FrameFile> files = list_frame_files((dir / "frame_%04d.ply").string());
  ASSERT_EQ(files.size(), 3u);
  EXPECT_EQ(files[0].path, (dir / "frame_0001.ply").string());
  EXPECT_EQ(files[1].number, 3u);
  EXPECT_EQ(files[2].number, 12345u);
  write(dir / "frame_12345.ply", ply_frame(12345));
  const ReferenceMotion m = read_cloud_sequence((dir / "frame_%04d.ply").string(), at_fps(25));
  ASSERT_EQ(m.frames.size(), 3u);
  EXPECT_EQ(m.frames[0].time, 0.0);
  EXPECT_DOUBLE_EQ(m.frames[1].time, 2.0 / 25);
  EXPECT_DOUBLE_EQ(m.frames[2].time, 12344.0 / 25);
  EXPECT_EQ(m.frames[1].positions, std::vector<Vec3>{Vec3(3, 2, 3)});
  // "%d" takes any number of digits.
  EXPECT_EQ(list_frame_files((dir / "frame_%d.ply").string()).size(), 4u);
}

TEST(CloudSequence, TellsPatternsFromNames) {
  EXPECT_TRUE(is_frame_pattern("scans/frame_%04d.ply"));
  EXPECT_TRUE(is_frame_pattern("%d.xyz"));
  EXPECT_FALSE(is_frame_pattern("scans/frame_0001.ply"));
  EXPECT_FALSE(is_frame_pattern("100%/scan.ply"));  // a folder's name is not the pattern
  EXPECT_FALSE(is_frame_pattern("50%.ply"));
  EXPECT_EQ(cloud_file_kind("a/B.PLY"), CloudFileKind::ply);
  EXPECT_EQ(cloud_file_kind("b.Xyz"), CloudFileKind::xyz);
  EXPECT_EQ(cloud_file_kind("c.csv"), CloudFileKind::none);
}

TEST(CloudSequence, OneFileIsOneFrameAtTheStart) {
  const fs::path file = scratch_dir() / "scan.ply";
  write(file, ply_frame(7));
  const ReferenceMotion m = read_cloud_file(file.string(), at_fps(0, 1.5));
  EXPECT_EQ(m.source, ReferenceMotion::Source::cloud);
  ASSERT_EQ(m.frames.size(), 1u);
  EXPECT_EQ(m.frames[0].time, 1.5);
  EXPECT_EQ(m.frames[0].positions, std::vector<Vec3>{Vec3(7, 2, 3)});
}

TEST(CloudSequenceErrors, AFrameRateIsRequired) {
  const fs::path dir = scratch_dir() / "scans";
  write(dir / "frame_1.xyz", xyz_frame(1));
  expect_input_error([&] { read_cloud_sequence(dir.string(), at_fps(0)); }, dir.string(), 0,
                     "--reference-fps", {"frames per second"});
  expect_input_error([&] { read_cloud_sequence(dir.string(), at_fps(30, -1)); }, dir.string(), 0,
                     "--reference-start", {">= 0"});
}

TEST(CloudSequenceErrors, FoldersThatAreNotASequenceAreNamed) {
  const fs::path empty = scratch_dir() / "empty";
  write(empty / "notes.txt", "no clouds here\n");
  expect_input_error([&] { read_cloud_sequence(empty.string(), at_fps(30)); }, empty.string(), 0,
                     "", {"no PLY or XYZ file"});

  const fs::path mixed = scratch_dir() / "mixed";
  write(mixed / "a_1.ply", ply_frame(1));
  write(mixed / "a_2.xyz", xyz_frame(2));
  expect_input_error([&] { read_cloud_sequence(mixed.string(), at_fps(30)); }, mixed.string(), 0,
                     "", {"a_1.ply' is PLY", "a_2.xyz' is XYZ"});

  const fs::path twice = scratch_dir() / "twice";
  write(twice / "frame_1.xyz", xyz_frame(1));
  write(twice / "frame_01.xyz", xyz_frame(1));
  expect_input_error([&] { read_cloud_sequence(twice.string(), at_fps(30)); }, twice.string(), 0,
                     "", {"frame_01.xyz' and '", "frame_1.xyz' have the same frame number 1"});

  const fs::path unnumbered = scratch_dir() / "unnumbered";
  write(unnumbered / "frame_1.xyz", xyz_frame(1));
  write(unnumbered / "scan.xyz", xyz_frame(2));
  expect_input_error([&] { read_cloud_sequence(unnumbered.string(), at_fps(30)); },
                     unnumbered.string(), 0, "", {"scan.xyz' has no frame number"});

  const fs::path long_number = scratch_dir() / "long";
  write(long_number / "frame_1234567890123456789.xyz", xyz_frame(1));
  expect_input_error([&] { read_cloud_sequence(long_number.string(), at_fps(30)); },
                     long_number.string(), 0, "", {"more than 18 digits"});
}

TEST(CloudSequenceErrors, PatternsThatNameNoFilesAreNamed) {
  const fs::path dir = scratch_dir() / "scans";
  write(dir / "frame_1.ply", ply_frame(1));
  const std::string none = (dir / "frame_%04d.ply").string();
  expect_input_error([&] { read_cloud_sequence(none, at_fps(30)); }, none, 0, "",
                     {"no file matches"});
  const std::string two = (dir / "frame_%d_%d.ply").string();
  expect_input_error([&] { read_cloud_sequence(two, at_fps(30)); }, two, 0, "",
                     {"two frame numbers"});
  const std::string other = (dir / "frame_%d.obj").string();
  expect_input_error([&] { read_cloud_sequence(other, at_fps(30)); }, other, 0, "",
                     {".ply or .xyz"});
}

// Each file's time is start + (number - first number) / fps. A rate so high
// that a later number adds nothing to the start (1 + 1e-300 is 1), or so low
// that it gives an infinite time, is refused, naming the file whose frame
// would not come after the one before it, before that file is read.
TEST(CloudSequenceErrors, AFrameRateThatGivesNoLaterTimeIsNamed) {
  const fs::path dir = scratch_dir() / "scans";
  write(dir / "frame_1.xyz", xyz_frame(1));
  write(dir / "frame_2.xyz", "not read: refused before its points\n");
  const std::string second = (dir / "frame_2.xyz").string();
  expect_input_error([&] { read_cloud_sequence(dir.string(), at_fps(1e300, 1)); }, second, 0,
                     "--reference-fps", {"frame number 2 at", "no later time"});
  expect_input_error([&] { read_cloud_sequence(dir.string(), at_fps(1e-310)); }, second, 0,
                     "--reference-fps", {"frame number 2 at", "no later time"});
  // The same files at a rate that separates them are read (the second file
  // made readable), so it is the rate the error is about.
  write(dir / "frame_2.xyz", xyz_frame(2));
  const ReferenceMotion m = read_cloud_sequence(dir.string(), at_fps(1e6, 1));
  ASSERT_EQ(m.frames.size(), 2u);
  EXPECT_GT(m.frames[1].time, m.frames[0].time);
}

// More files than a reference may hold frames, or more points in all than it
// may hold, are refused: the files before any is read, the points at the file
// that passes the limit. The limits (2^20 frames, 2^25 points:
// reference_motion.h) are held here to 2 files and 5 points.
TEST(CloudSequenceErrors, MoreFilesOrPointsThanAReferenceMayHoldAreRefused) {
  const fs::path dir = scratch_dir() / "scans";
  for (int n : {1, 2, 3})
    write(dir / ("frame_" + std::to_string(n) + ".xyz"), xyz_frame(n));  // 2 points each
  ReferenceOptions two_files = at_fps(30);
  two_files.limits.frames = 2;
  expect_input_error([&] { read_cloud_sequence(dir.string(), two_files); }, dir.string(), 0, "",
                     {"more than 2 files"});
  const std::string pattern = (dir / "frame_%d.xyz").string();
  expect_input_error([&] { read_cloud_sequence(pattern, two_files); }, pattern, 0, "",
                     {"more than 2 files"});
  two_files.limits.frames = 3;
  EXPECT_EQ(read_cloud_sequence(dir.string(), two_files).frames.size(), 3u);
  ReferenceOptions five_points = at_fps(30);
  five_points.limits.observations = 5;
  expect_input_error([&] { read_cloud_sequence(dir.string(), five_points); },
                     (dir / "frame_3.xyz").string(), 0, "", {"passes 5 points"});
  five_points.limits.observations = 6;
  EXPECT_EQ(read_cloud_sequence(dir.string(), five_points).observations(), 6u);
  // One file past the limit alone: its own reader refuses it at the point too many.
  ReferenceOptions one_point = at_fps(30);
  one_point.limits.observations = 1;
  expect_input_error([&] { read_cloud_file((dir / "frame_1.xyz").string(), one_point); },
                     (dir / "frame_1.xyz").string(), 2, "", {"more than 1 points"});
}

// A bad file is named by its own error: the file, the line, the field.
TEST(CloudSequenceErrors, ABadFileIsNamedByItsOwnError) {
  const fs::path dir = scratch_dir() / "scans";
  write(dir / "frame_1.xyz", xyz_frame(1));
  write(dir / "frame_2.xyz", "1 2 3\n1 2 nan\n");
  write(dir / "frame_3.xyz", xyz_frame(3));
  expect_input_error([&] { read_cloud_sequence(dir.string(), at_fps(30)); },
                     (dir / "frame_2.xyz").string(), 2, "z", {"NaN or infinite"});
}

}  // namespace
}  // namespace neurocloth
