#include "learn/motion/ply_header.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "learn/motion/reference_motion.h"
#include "support/input_error_check.h"

namespace neurocloth {
namespace {
using test::expect_input_error;

const std::string kXyzProperties = "property float x\nproperty float y\nproperty float z\n";

void expect_header_error(const std::string& bytes, int line, const std::string& field,
                         std::initializer_list<std::string> mentions = {}) {
  expect_input_error([&] { read_ply_header(bytes, "scan.ply"); }, "scan.ply", line, field,
                     mentions);
}

TEST(PlyHeader, ReadsElementsPropertiesAndWhereTheBodyStarts) {
  const std::string head =
      "ply\r\nformat binary_big_endian 1.0\r\ncomment made by hand\r\nobj_info scanner 7\r\n"
      "element face 2\r\nproperty list uint8 int32 vertex_indices\r\n"
      "element vertex 3\r\nproperty uchar red\r\nproperty float z\r\nproperty float64 x\r\n"
      "property int16 y\r\nend_header\r\n";
  const PlyHeader h = read_ply_header(head + std::string(2 + 3 * 15, '\0'), "scan.ply");
  EXPECT_EQ(h.format, PlyFormat::big_endian);
  EXPECT_EQ(h.body, head.size());
  EXPECT_EQ(h.lines, 12);
  ASSERT_EQ(h.elements.size(), 2u);
  EXPECT_EQ(h.vertex, 1u);
  const PlyElement& face = h.elements[0];
  EXPECT_EQ(face.count, 2u);
  ASSERT_EQ(face.properties.size(), 1u);
  ASSERT_NE(face.properties[0].count, nullptr);
  EXPECT_EQ(face.properties[0].count->scalar, PlyScalar::uint8);
  EXPECT_EQ(face.properties[0].type->scalar, PlyScalar::int32);
  const PlyElement& vertex = h.elements[1];
  ASSERT_EQ(vertex.properties.size(), 4u);
  EXPECT_EQ(vertex.properties[0].axis, -1);
  EXPECT_EQ(vertex.properties[1].axis, 2);
  EXPECT_EQ(vertex.properties[2].axis, 0);
  EXPECT_EQ(vertex.properties[2].type->bytes, 8u);
  EXPECT_EQ(vertex.properties[3].axis, 1);
}

TEST(PlyHeaderErrors, NotAPlyOrAnUnknownFormatIsNamed) {
  expect_header_error("solid cube\n", 1, "ply", {"not a PLY file", "'solid cube'"});
  expect_header_error("ply\nformat binary_middle_endian 1.0\n", 2, "format",
                      {"unknown format 'binary_middle_endian'"});
  expect_header_error("ply\nformat ascii 2.0\n", 2, "format", {"version '2.0'"});
  expect_header_error("ply\nformat ascii\n", 2, "format");
  expect_header_error("ply\nformat ascii 1.0\nformat ascii 1.0\n", 3, "format", {"second"});
  expect_header_error("ply\nelement vertex 1\n", 2, "format", {"before the format line"});
  expect_header_error("ply\nend_header\n", 2, "format", {"no format line"});
}

TEST(PlyHeaderErrors, AMissingVertexElementOrCoordinateIsNamed) {
  const std::string f = "ply\nformat ascii 1.0\n";
  expect_header_error(f + "element face 1\nproperty list uchar int idx\nend_header\n3 0 1 2\n", 0,
                      "element vertex", {"no vertex element"});
  expect_header_error(f + "element vertex 1\nproperty float x\nproperty float y\nend_header\n", 3,
                      "z", {"no property z"});
  expect_header_error(
      f + "element vertex 1\nproperty list uchar float x\nproperty float y\nproperty float z\n"
          "end_header\n",
      3, "x", {"no scalar property x"});
  expect_header_error(f + "element vertex 0\n" + kXyzProperties + "end_header\n", 3,
                      "element vertex", {"no points"});
}

TEST(PlyHeaderErrors, BadPropertiesAreNamed) {
  const std::string f = "ply\nformat ascii 1.0\n";
  expect_header_error(f + "element face 1\nproperty list float int idx\n", 4, "property idx",
                      {"integer type, not 'float'"});
  expect_header_error(f + "element face 1\nproperty list double int idx\n", 4, "property idx");
  expect_header_error(f + "element vertex 1\nproperty real x\n", 4, "property",
                      {"unknown type 'real'"});
  expect_header_error(f + "property float x\n", 3, "property", {"before any element"});
  expect_header_error(f + "element vertex 1\nproperty float x\nproperty double x\n", 5,
                      "property x", {"twice"});
  expect_header_error(f + "element vertex 1\nproperty list uchar int\n", 4, "property");
  expect_header_error(f + "element vertex 1\nelement vertex 2\n", 4, "element vertex",
                      {"declared twice"});
  expect_header_error(f + "element vertex -1\n", 3, "element vertex", {"'-1'"});
  expect_header_error(f + "element vertex\n", 3, "element");
  expect_header_error(f + "texture vertex 1\n", 3, "header", {"unknown keyword 'texture'"});
  expect_header_error(f + "element vertex 1\n" + kXyzProperties + "end_header now\n", 7,
                      "end_header");
}

TEST(PlyHeaderErrors, AHeaderWithoutAnEndIsRefused) {
  expect_header_error("ply\nformat ascii 1.0\nelement vertex 1\n" + kXyzProperties, 6, "end_header",
                      {"ends inside its header"});
  expect_header_error("", 0, "end_header");
  std::string comments = "ply\nformat ascii 1.0\n";
  while (comments.size() <= kMaxPlyHeaderBytes)
    comments += "comment a header longer than any real one\n";
  const int lines = static_cast<int>(std::count(comments.begin(), comments.end(), '\n'));
  expect_header_error(comments + "end_header\n", lines, "end_header", {"64 KiB"});
  // One line as long: no newline for 64 KiB.
  expect_header_error("ply\ncomment " + std::string(kMaxPlyHeaderBytes, 'x'), 2, "end_header",
                      {"64 KiB"});
}

}  // namespace
}  // namespace neurocloth
