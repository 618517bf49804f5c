#include "learn/motion/marker_csv.h"

#include <gtest/gtest.h>

#include "learn/motion/read_reference.h"
#include "support/input_error_check.h"
#include "support/reference_error.h"

namespace neurocloth {
namespace {
using test::expect_input_error;
using test::expect_reference_error;

constexpr std::size_t kNodes = 10;

ReferenceMotion parse(const std::string& text) {
  return parse_reference(text, "markers.csv", kNodes);
}

// Any subset of nodes per frame, at times off any step grid, in any order
// within a frame.
TEST(MarkerCsv, ReadsASubsetOfNodesAtOddTimes) {
  const ReferenceMotion m = parse(
      "time,node,x,y,z\n"
      "0,0,0,1,0\n"
      "0,9,0.45,1,0.45\n"
      "0.0333,5,0.25,0.99,0\n"
      "0.0333,2,1e-3,-2.5E+0,.5\n"
      "0.0334,7,1,2,3\n");
  EXPECT_EQ(m.source, ReferenceMotion::Source::markers);
  ASSERT_EQ(m.frames.size(), 3u);
  EXPECT_EQ(m.observations(), 5u);
  EXPECT_EQ(m.frames[0].time, 0.0);
  EXPECT_EQ(m.frames[0].nodes, (std::vector<std::int32_t>{0, 9}));
  EXPECT_EQ(m.frames[1].time, 0.0333);
  EXPECT_EQ(m.frames[1].nodes, (std::vector<std::int32_t>{5, 2}));
  EXPECT_EQ(m.frames[1].positions[1], Vec3(1e-3, -2.5, 0.5));
  EXPECT_EQ(m.frames[2].time, 0.0334);
  EXPECT_EQ(m.frames[2].positions[0], Vec3(1, 2, 3));
}

// What spreadsheets and capture tools write: a byte order mark, CRLF, spaces
// around fields, comments, blank lines, no final newline, "3.0" for a node.
TEST(MarkerCsv, ReadsCsvTheWayRealToolsWriteIt) {
  const ReferenceMotion m = parse(
      "\xEF\xBB\xBF# exported by a tracker\r\n"
      "\r\n"
      " Time , Node , X , Y , Z \r\n"
      "# frame 0\r\n"
      "0.0 , 3.0 , 1 , 2 , 3\r\n"
      "\r\n"
      "  \t\r\n"
      "0.5,\t4, -1, -2 ,-3");
  ASSERT_EQ(m.frames.size(), 2u);
  EXPECT_EQ(m.frames[0].nodes, std::vector<std::int32_t>{3});
  EXPECT_EQ(m.frames[0].positions[0], Vec3(1, 2, 3));
  EXPECT_EQ(m.frames[1].time, 0.5);
  EXPECT_EQ(m.frames[1].nodes, std::vector<std::int32_t>{4});
  EXPECT_EQ(m.frames[1].positions[0], Vec3(-1, -2, -3));
}

// A depth camera's or a scanner's points: no node column, a frame's rows
// sharing its time, points in no order and possibly repeated; read as leniently
// as markers.
TEST(CloudCsv, ReadsPointsWithoutNodesFrameByFrame) {
  const ReferenceMotion m = parse(
      "\xEF\xBB\xBF# depth camera, 2 frames\r\n"
      " Time , X , Y , Z \r\n"
      "0, 0.5, 1, 0\r\n"
      "\r\n"
      "0, 0.5, 1, 0\r\n"
      "0,-1,2,3e-3\r\n"
      "# frame 1\r\n"
      "0.04,\t7,8,9");
  EXPECT_EQ(m.source, ReferenceMotion::Source::cloud);
  EXPECT_TRUE(m.is_cloud());
  ASSERT_EQ(m.frames.size(), 2u);
  EXPECT_EQ(m.frames[0].time, 0.0);
  EXPECT_TRUE(m.frames[0].nodes.empty());
  EXPECT_EQ(m.frames[0].positions,
            (std::vector<Vec3>{Vec3(0.5, 1, 0), Vec3(0.5, 1, 0), Vec3(-1, 2, 3e-3)}));
  EXPECT_EQ(m.frames[1].time, 0.04);
  EXPECT_EQ(m.frames[1].positions, std::vector<Vec3>{Vec3(7, 8, 9)});
  EXPECT_EQ(m.observations(), 4u);
}

// A cloud's points are not nodes: a thousand points for a scene of ten nodes.
TEST(CloudCsv, HoldsMorePointsThanTheSceneHasNodes) {
  std::string text = "time,x,y,z\n";
  for (int k = 0; k < 1000; ++k)
    text += "0.5," + std::to_string(k) + ",0,0\n";
  const ReferenceMotion m = parse(text);
  ASSERT_EQ(m.frames.size(), 1u);
  EXPECT_EQ(m.frames[0].positions.size(), 1000u);
  EXPECT_EQ(m.frames[0].positions[999], Vec3(999, 0, 0));
}

const std::string kCloudHeader = "time,x,y,z\n";

TEST(CloudCsvErrors, BadRowsAreNamedByLineAndField) {
  expect_reference_error(kCloudHeader + "0,1,2\n", kNodes, 2, "z", "found 3");
  expect_reference_error(kCloudHeader + "0,1,2,3,4\n", kNodes, 2, "after z", "time,x,y,z");
  expect_reference_error(kCloudHeader + "0,1,nan,3\n", kNodes, 2, "y", "NaN or infinite");
  expect_reference_error(kCloudHeader + "0,1,2,-1e7\n", kNodes, 2, "z", "1e6 m");
  expect_reference_error(kCloudHeader + "0,x,2,3\n", kNodes, 2, "x", "not a number");
  expect_reference_error(kCloudHeader + "0.2,1,2,3\n0.1,1,2,3\n", kNodes, 3, "time", "goes back");
  expect_reference_error(kCloudHeader + "# nothing\n", kNodes, 2, "", "no rows");
}

const std::string kHeader = "time,node,x,y,z\n";

TEST(MarkerCsvErrors, AnUnknownNodeIsNamed) {
  expect_reference_error(kHeader + "0,1,0,0,0\n0,10,0,0,0\n", kNodes, 3, "node", "unknown node");
  expect_reference_error(kHeader + "0,-1,0,0,0\n", kNodes, 2, "node", "negative");
  expect_reference_error(kHeader + "0,2.5,0,0,0\n", kNodes, 2, "node", "whole number");
  expect_reference_error(kHeader + "0,two,0,0,0\n", kNodes, 2, "node", "not a number");
  expect_reference_error(kHeader + "0,1e30,0,0,0\n", kNodes, 2, "node", "unknown node");
  expect_reference_error(kHeader + "0,,0,0,0\n", kNodes, 2, "node");
}

TEST(MarkerCsvErrors, NanOrInfinityIsNamed) {
  expect_reference_error(kHeader + "0,1,nan,0,0\n", kNodes, 2, "x", "NaN or infinite");
  expect_reference_error(kHeader + "0,1,0,inf,0\n", kNodes, 2, "y");
  expect_reference_error(kHeader + "0,1,0,0,1e999\n", kNodes, 2, "z");
  expect_reference_error(kHeader + "NaN,1,0,0,0\n", kNodes, 2, "time");
  expect_reference_error(kHeader + "0,1,0,0,1.5m\n", kNodes, 2, "z", "not a number");
  expect_reference_error(kHeader + "0,1,0,-2e6,0\n", kNodes, 2, "y", "1e6 m");
}

TEST(MarkerCsvErrors, TimeGoingBackIsNamed) {
  expect_reference_error(kHeader + "0.1,1,0,0,0\n0.2,1,0,0,0\n0.15,2,0,0,0\n", kNodes, 4, "time",
                         "goes back");
  // A frame's rows must stay together: returning to an earlier time is going back.
  expect_reference_error(kHeader + "0,1,0,0,0\n0.1,1,0,0,0\n0,2,0,0,0\n", kNodes, 4, "time");
  expect_reference_error(kHeader + "-0.1,1,0,0,0\n", kNodes, 2, "time", ">= 0");
}

TEST(MarkerCsvErrors, ADuplicateNodeInAFrameIsNamed) {
  expect_reference_error(kHeader + "0,1,0,0,0\n0,2,0,0,0\n0,1,1,1,1\n", kNodes, 4, "node", "twice");
  // The same node in the next frame is fine.
  EXPECT_EQ(parse(kHeader + "0,1,0,0,0\n0.1,1,0,0,0\n").frames.size(), 2u);
}

TEST(MarkerCsvErrors, NoRowsIsNamed) {
  expect_reference_error(kHeader, kNodes, 1, "", "no rows");
  expect_reference_error(kHeader + "\n# nothing\n", kNodes, 3, "", "no rows");
  expect_reference_error("", kNodes, 0, "header", "empty");
  expect_reference_error("# only a comment\n\n", kNodes, 2, "header", "empty");
}

TEST(MarkerCsvErrors, AWrongHeaderIsNamed) {
  expect_reference_error("t,node,x,y,z\n0,1,0,0,0\n", kNodes, 1, "header", "time,node,x,y,z");
  expect_reference_error("time,y,x,z\n0,1,0,0\n", kNodes, 1, "header", "'time,x,y,z'");
  expect_reference_error("# c\ntime,node,x,y\n0,1,0,0\n", kNodes, 2, "header");
  expect_reference_error("0,1,0,0,0\n", kNodes, 1, "header");
  expect_reference_error(std::string("\0\1\2binary", 9), kNodes, 1, "header");
}

TEST(MarkerCsvErrors, AWrongFieldCountIsNamed) {
  expect_reference_error(kHeader + "0,1,0,0\n", kNodes, 2, "z", "found 4");
  expect_reference_error(kHeader + "0,1,0,0,0\n0\n", kNodes, 3, "node", "found 1");
  expect_reference_error(kHeader + "0,1,0,0,0,0\n", kNodes, 2, "after z", "found 6");
}

// Each frame costs far more than its rows: 2^25 one-row frames would take 10
// GB. A reference holds at most 2^20 frames (distinct times).
TEST(MarkerCsvErrors, MoreFramesThanAReferenceMayHoldAreRefused) {
  std::string text = kHeader;
  for (std::size_t k = 1; k <= kMaxReferenceFrames + 1; ++k)
    text += std::to_string(k) + ",0,0,0,0\n";
  expect_reference_error(text, kNodes, static_cast<int>(kMaxReferenceFrames) + 2, "time",
                         "1048576 frames");
}

// More observations (markers) or points (a cloud) than a reference may hold
// are refused at the row of the first one too many. The limit is 2^25
// (reference_motion.h), held here to 4 through the reader's limits.
TEST(MarkerCsvErrors, MoreObservationsThanAReferenceMayHoldAreRefused) {
  EXPECT_EQ(ReferenceLimits().observations, kMaxReferenceObservations);
  EXPECT_EQ(ReferenceLimits().frames, kMaxReferenceFrames);
  ReferenceLimits four;
  four.observations = 4;
  const std::string markers = kHeader + "0,0,0,0,0\n0,1,0,0,0\n0.1,0,0,0,0\n0.1,1,0,0,0\n";
  EXPECT_EQ(parse_marker_csv(markers, "markers.csv", kNodes, four).observations(), 4u);
  expect_input_error(
      [&] { parse_marker_csv(markers + "0.2,0,0,0,0\n", "markers.csv", kNodes, four); },
      "markers.csv", 6, "", {"more than 4 observations"});
  const std::string cloud = "time,x,y,z\n0,1,2,3\n0,1,2,3\n0.1,1,2,3\n0.1,4,5,6\n";
  EXPECT_EQ(parse_marker_csv(cloud, "cloud.csv", kNodes, four).observations(), 4u);
  expect_input_error([&] { parse_marker_csv(cloud + "0.1,7,8,9\n", "cloud.csv", kNodes, four); },
                     "cloud.csv", 6, "", {"more than 4 points"});
}

// A binary file or a stray byte quoted in a message: a carriage return, a NUL
// or a terminal escape would break the one-line message (or the terminal), so
// they are shown as \xNN.
TEST(MarkerCsvErrors, ControlBytesInAMessageAreEscaped) {
  using namespace std::string_literals;
  const std::string cases[] = {"\x1b[2J\rtime\0,node,x,y,z\n0,1,0,0,0\n"s,
                               kHeader + "0,1\0,0,0,0\n"s};
  for (const std::string& text : cases) {
    try {
      parse_reference(text, "markers.csv", kNodes);
      ADD_FAILURE() << "accepted";
    } catch (const InputError& e) {
      const std::string what = e.what();
      for (const char c : what)
        EXPECT_FALSE(static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
            << "a control byte " << int(c) << " in the message";
      EXPECT_TRUE(what.find("\\x1b") != std::string::npos ||
                  what.find("\\x00") != std::string::npos)
          << what;
    }
  }
}

}  // namespace
}  // namespace neurocloth
