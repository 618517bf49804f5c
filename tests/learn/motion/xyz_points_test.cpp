#include "learn/motion/xyz_points.h"

#include <gtest/gtest.h>

#include "learn/motion/reference_motion.h"
#include "support/input_error_check.h"

namespace neurocloth {
namespace {
using test::expect_input_error;

std::vector<Vec3> read_xyz(const std::string& text) {
  return parse_xyz_points(text, "scan.xyz");
}

// What scanners and CloudCompare write: spaces, tabs or commas, a normal and
// a colour after the point, comments, blank lines, CRLF, a byte order mark.
TEST(XyzPoints, ReadsPointsAndIgnoresExtraColumns) {
  const std::vector<Vec3> points = read_xyz(
      "\xEF\xBB\xBF# CloudCompare export\r\n"
      "0.5 1 -2\r\n"
      "\r\n"
      "  1e-3\t2.5\t3   0 0 1  255 128 0\r\n"
      "# a comment between points\r\n"
      "-1,2,3,0.1,0.2,0.3\r\n"
      "4, 5, 6");
  EXPECT_EQ(points, (std::vector<Vec3>{Vec3(0.5, 1, -2), Vec3(1e-3, 2.5, 3), Vec3(-1, 2, 3),
                                       Vec3(4, 5, 6)}));
}

// Points repeat and come in any order: nothing is made of either.
TEST(XyzPoints, KeepsRepeatedPoints) {
  EXPECT_EQ(read_xyz("1 1 1\n1 1 1\n").size(), 2u);
}

void expect_xyz_error(const std::string& text, int line, const std::string& field,
                      std::initializer_list<std::string> mentions = {}) {
  expect_input_error([&] { read_xyz(text); }, "scan.xyz", line, field, mentions);
}

TEST(XyzPointsErrors, BadLinesAreNamedByLineAndField) {
  expect_xyz_error("1 2 3\n4 5\n", 2, "z", {"expected 'x y z'", "'4 5'"});
  expect_xyz_error("1\n", 1, "y");
  expect_xyz_error("# c\n, ,\n", 2, "x");
  expect_xyz_error("1 2 3\n\n1 two 3\n", 3, "y", {"not a number: 'two'"});
  expect_xyz_error("nan 2 3\n", 1, "x", {"NaN or infinite"});
  expect_xyz_error("1 2 1e999\n", 1, "z", {"NaN or infinite"});
  expect_xyz_error("1 -2e6 3\n", 1, "y", {"beyond 1e6 m"});
  expect_xyz_error("X Y Z\n1 2 3\n", 1, "x", {"not a number: 'X'"});
}

// A file of more points than a reference may hold is refused at the line of
// the first point too many. The limit is 2^25 (reference_motion.h); the test
// holds the reader to 3, through the limits every reader takes, and checks
// that the readers' default is that constant.
TEST(XyzPointsErrors, MorePointsThanAReferenceMayHoldAreRefused) {
  EXPECT_EQ(ReferenceLimits().observations, kMaxReferenceObservations);
  ReferenceLimits three;
  three.observations = 3;
  const std::string text = "1 2 3\n# c\n4 5 6\n7 8 9\n";
  EXPECT_EQ(parse_xyz_points(text, "scan.xyz", three).size(), 3u);
  expect_input_error([&] { parse_xyz_points(text + "0 0 0\n", "scan.xyz", three); }, "scan.xyz", 5,
                     "", {"more than 3 points"});
}

TEST(XyzPointsErrors, NoPointsIsRefused) {
  expect_xyz_error("", 0, "", {"no points"});
  expect_xyz_error("# only\n\n", 2, "", {"no points"});
}

}  // namespace
}  // namespace neurocloth
