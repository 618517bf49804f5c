#include "learn/motion/motion_recording.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>

#include "core/base/same_bits.h"
#include "core/io/text_file.h"
#include "learn/motion/read_reference.h"
#include "support/reference_error.h"
#include "support/scene_test_support.h"

namespace neurocloth {
namespace {
namespace fs = std::filesystem;
using test::expect_reference_error;
using test::scratch_path;

constexpr std::size_t kRecordedNodes = 3;

// Doubles whose decimal forms would not survive a text round trip unchanged.
std::vector<Vec3> awkward_positions(double t) {
  return {Vec3(0.1 + t, 1.0 / 3.0, -0.0),
          Vec3(4.9406564584124654e-324, 999999.99999999988, -2.5e-17 * t),
          Vec3(std::nextafter(1.0, 2.0), -7.0, t)};
}

std::string record(const std::string& name, const std::vector<double>& times) {
  const std::string path = scratch_path(name);
  RecordingWriter w(path, {"awkward", kRecordedNodes, 60});
  for (double t : times)
    w.add_frame(t, awkward_positions(t));
  w.finish();
  return path;
}

TEST(MotionRecording, RoundTripsEveryDoubleBitForBit) {
  const std::vector<double> times = {0.0, 1.0 / 60, 2.0 / 60, 0.7};
  const std::string path = record("round.motion", times);
  const ReferenceMotion m = read_reference(path, kRecordedNodes);
  EXPECT_EQ(m.source, ReferenceMotion::Source::recording);
  EXPECT_EQ(m.path, path);
  ASSERT_EQ(m.frames.size(), times.size());
  EXPECT_EQ(m.observations(), times.size() * kRecordedNodes);
  for (std::size_t f = 0; f < times.size(); ++f) {
    EXPECT_TRUE(same_bits(m.frames[f].time, times[f])) << f;
    const auto expected = awkward_positions(times[f]);
    ASSERT_EQ(m.frames[f].nodes, (std::vector<std::int32_t>{0, 1, 2}));
    for (std::size_t k = 0; k < kRecordedNodes; ++k)
      for (int a = 0; a < 3; ++a)
        EXPECT_TRUE(same_bits(m.frames[f].positions[k][a], expected[k][a]))
            << "frame " << f << " node " << k << " axis " << a;
  }
}

// The first two lines are text a person can read with `head -2`.
TEST(MotionRecording, StartsWithTheMagicLineAndAJsonHeader) {
  const std::string bytes = read_text_file(record("head.motion", {0.0, 0.5}), "t", 1 << 20);
  ASSERT_EQ(bytes.compare(0, 20, "NEUROCLOTH-MOTION 1\n"), 0);
  const std::size_t eol = bytes.find('\n', 20);
  const std::string header = bytes.substr(20, eol - 20);
  for (const char* key : {"\"node_count\":3", "\"frame_count\":2", "\"units\":\"m\"",
                          "\"node_order\":\"file\"", "\"scene\":\"awkward\""})
    EXPECT_NE(header.find(key), std::string::npos) << key << " not in " << header;
  EXPECT_EQ(bytes.size() - eol - 1, 2 * 8 * (1 + 3 * kRecordedNodes));
}

TEST(MotionRecording, NothingIsAtThePathUntilFinishedAndNothingIsLeftWithout) {
  const fs::path dir = scratch_path("unfinished");
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string path = (dir / "r.motion").string();
  {
    RecordingWriter w(path, {"s", kRecordedNodes, 60});
    w.add_frame(0, awkward_positions(0));
    EXPECT_FALSE(fs::exists(path));
  }
  EXPECT_TRUE(fs::is_empty(dir)) << "a temporary file was left behind";
}

TEST(MotionRecording, RefusesANonFinitePositionAndWritesNoneOfIt) {
  const std::string path = scratch_path("nan.motion");
  fs::remove(path);
  RecordingWriter w(path, {"s", kRecordedNodes, 60});
  w.add_frame(0, awkward_positions(0));
  auto bad = awkward_positions(0.1);
  bad[2].y() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(w.add_frame(0.1, bad), std::runtime_error);
  bad[2].y() = std::numeric_limits<double>::infinity();
  EXPECT_THROW(w.add_frame(0.1, bad), std::runtime_error);
  bad[2].y() = -1.5e6;  // finite, but a unit mistake the reader would refuse
  EXPECT_THROW(w.add_frame(0.1, bad), std::runtime_error);
  w.add_frame(0.2, awkward_positions(0.2));
  w.finish();
  const ReferenceMotion m = read_reference(path, kRecordedNodes);
  ASSERT_EQ(m.frames.size(), 2u);
  EXPECT_EQ(m.frames[1].time, 0.2);
}

TEST(MotionRecording, DropsTheFramesAfterARollback) {
  const std::string path = scratch_path("rollback.motion");
  RecordingWriter w(path, {"s", kRecordedNodes, 60});
  for (double t : {0.0, 0.1, 0.2, 0.3})
    w.add_frame(t, awkward_positions(t));
  w.drop_frames_after(0.15);
  EXPECT_EQ(w.frame_count(), 2u);
  w.add_frame(0.25, awkward_positions(0.25));
  w.finish();
  const ReferenceMotion m = read_reference(path, kRecordedNodes);
  ASSERT_EQ(m.frames.size(), 3u);
  EXPECT_EQ(m.frames[2].time, 0.25);
  EXPECT_TRUE(same_bits(m.frames[2].positions[0].x(), 0.1 + 0.25));
}

TEST(MotionRecording, AnUnwritableFolderIsNamed) {
  const std::string path = scratch_path("no/such/folder/r.motion");
  try {
    RecordingWriter w(path, {"s", kRecordedNodes, 60});
    FAIL() << "opened " << path;
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
}

// A valid recording's bytes, to break one thing at a time.
std::string valid_bytes() {
  return read_text_file(record("valid.motion", {0.0, 0.1, 0.2}), "t", 1 << 20);
}

constexpr std::size_t kStride = 8 * (1 + 3 * kRecordedNodes);
std::size_t body_start(const std::string& bytes) {
  return bytes.find('\n', 20) + 1;
}

void put_double(std::string& bytes, std::size_t at, double v) {
  unsigned char b[8];
  std::uint64_t bits;
  std::memcpy(&bits, &v, 8);
  put_le64(b, bits);
  bytes.replace(at, 8, reinterpret_cast<const char*>(b), 8);
}

// The header line replaced by `header` (padding kept out of it).
std::string with_header(const std::string& header) {
  const std::string bytes = valid_bytes();
  return "NEUROCLOTH-MOTION 1\n" + header + "\n" + bytes.substr(body_start(bytes));
}

const char* kGoodHeader =
    R"({"node_count":3,"frame_count":3,"fps":60,"units":"m","scene":"s","version":1})";

TEST(MotionRecordingErrors, AGoodHeaderWrittenByHandIsRead) {
  EXPECT_EQ(parse_reference(with_header(kGoodHeader), "x", kRecordedNodes).frames.size(), 3u);
}

TEST(MotionRecordingErrors, ATruncatedFileIsNamed) {
  const std::string bytes = valid_bytes();
  expect_reference_error(bytes.substr(0, bytes.size() - 8), kRecordedNodes, 2, "frame_count",
                         "truncated");
  expect_reference_error(bytes.substr(0, body_start(bytes) + kStride), kRecordedNodes, 2,
                         "frame_count", "truncated");
  expect_reference_error(bytes.substr(0, body_start(bytes) - 5), kRecordedNodes, 2, "header");
  expect_reference_error(bytes + "x", kRecordedNodes, 2, "frame_count", "after the last");
}

TEST(MotionRecordingErrors, ANodeCountOtherThanTheScenesIsNamed) {
  expect_reference_error(valid_bytes(), kRecordedNodes + 1, 2, "node_count", "3 nodes");
  expect_reference_error(valid_bytes(), kRecordedNodes - 1, 2, "node_count");
}

TEST(MotionRecordingErrors, ABrokenHeaderIsNamed) {
  expect_reference_error(with_header(R"({"node_count":3,"frame_count":3,)"), kRecordedNodes, 2,
                         "header");
  expect_reference_error(with_header("[1,2]"), kRecordedNodes, 2, "header");
  expect_reference_error(with_header(R"({"node_count":3,"frame_count":3,"fps":60})"),
                         kRecordedNodes, 2, "units");
  expect_reference_error(with_header(R"({"node_count":3,"frame_count":3,"units":"m"})"),
                         kRecordedNodes, 2, "fps");
  expect_reference_error(with_header(R"({"node_count":-3,"frame_count":3,"fps":60,"units":"m"})"),
                         kRecordedNodes, 2, "node_count");
  expect_reference_error(with_header(R"({"node_count":3,"frame_count":2.5,"fps":60,"units":"m"})"),
                         kRecordedNodes, 2, "frame_count");
  expect_reference_error(with_header(R"({"node_count":3,"fps":60,"units":"m"})"), kRecordedNodes, 2,
                         "frame_count");
  expect_reference_error(with_header(R"({"node_count":3,"frame_count":0,"fps":60,"units":"m"})"),
                         kRecordedNodes, 2, "frame_count", "no frames");
}

TEST(MotionRecordingErrors, AnotherVersionIsNamed) {
  std::string bytes = valid_bytes();
  bytes[18] = '2';
  expect_reference_error(bytes, kRecordedNodes, 1, "version", "version 1");
}

// A count the file states is checked against the file's size before anything
// is allocated from it: 10^15 frames must fail at once, not exhaust memory.
TEST(MotionRecordingErrors, AHugeFrameCountIsRefusedBeforeAllocating) {
  expect_reference_error(
      with_header(R"({"node_count":3,"frame_count":1000000000000000,"fps":60,"units":"m"})"),
      kRecordedNodes, 2, "frame_count", "more than");
  expect_reference_error(
      with_header(R"({"node_count":3,"frame_count":1000000,"fps":60,"units":"m"})"), kRecordedNodes,
      2, "frame_count", "truncated");
  expect_reference_error(
      with_header(R"({"node_count":3,"frame_count":18446744073709551615,"fps":60,"units":"m"})"),
      kRecordedNodes, 2, "frame_count");
}

// A frame costs far more than its positions: a recording of one node may hold
// 2^20 frames, not 2^25 (10 GB of frames for a 800 MB file).
TEST(MotionRecordingErrors, MoreFramesThanAReferenceMayHoldAreRefused) {
  expect_reference_error(
      with_header(R"({"node_count":1,"frame_count":1048577,"fps":60,"units":"m"})"), 1, 2,
      "frame_count", "1048576");
}

TEST(MotionRecordingErrors, ANonFinitePositionOrTimeIsNamed) {
  std::string bytes = valid_bytes();
  put_double(bytes, body_start(bytes) + kStride + 8 * (1 + 3 * 2 + 1),
             std::numeric_limits<double>::quiet_NaN());
  expect_reference_error(bytes, kRecordedNodes, 0, "frame 1 node 2", "NaN");
  bytes = valid_bytes();
  put_double(bytes, body_start(bytes) + 8, -std::numeric_limits<double>::infinity());
  expect_reference_error(bytes, kRecordedNodes, 0, "frame 0 node 0");
  bytes = valid_bytes();
  put_double(bytes, body_start(bytes) + 2 * kStride + 8 * 3, 3.7e254);  // its square overflows
  expect_reference_error(bytes, kRecordedNodes, 0, "frame 2 node 0", "1e6 m");
  bytes = valid_bytes();
  put_double(bytes, body_start(bytes) + 2 * kStride, std::numeric_limits<double>::infinity());
  expect_reference_error(bytes, kRecordedNodes, 0, "frame 2 time");
}

TEST(MotionRecordingErrors, TimeGoingBackOrRepeatingIsNamed) {
  std::string bytes = valid_bytes();
  put_double(bytes, body_start(bytes) + 2 * kStride, 0.05);
  expect_reference_error(bytes, kRecordedNodes, 0, "frame 2 time", "goes back");
  bytes = valid_bytes();
  put_double(bytes, body_start(bytes) + 2 * kStride, 0.1);
  expect_reference_error(bytes, kRecordedNodes, 0, "frame 2 time");
  bytes = valid_bytes();
  put_double(bytes, body_start(bytes), -1);
  expect_reference_error(bytes, kRecordedNodes, 0, "frame 0 time");
}

}  // namespace
}  // namespace neurocloth
