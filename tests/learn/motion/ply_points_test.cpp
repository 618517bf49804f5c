#include "learn/motion/ply_points.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>

#include "core/io/text_file.h"
#include "learn/motion/reference_motion.h"
#include "learn/motion/xyz_points.h"
#include "support/input_error_check.h"

namespace neurocloth {
namespace {
using test::expect_input_error;

enum class Order { ascii, little, big };

const char* format_name(Order o) {
  return o == Order::ascii    ? "ascii"
         : o == Order::little ? "binary_little_endian"
                              : "binary_big_endian";
}

std::size_t type_bytes(const std::string& type) {
  if (type == "char" || type == "uchar" || type == "int8" || type == "uint8") return 1;
  if (type == "short" || type == "ushort" || type == "int16" || type == "uint16") return 2;
  if (type == "double" || type == "float64") return 8;
  return 4;
}

// One value as a PLY body of `order` holds it: text, or the type's bytes in
// the file's byte order (built from the value's bits, whatever the machine's).
void put(std::string& out, const std::string& type, double v, Order order) {
  if (order == Order::ascii) {
    char s[40];
    std::snprintf(s, sizeof s, "%.17g ", v);
    out += s;
    return;
  }
  const std::size_t n = type_bytes(type);
  std::uint64_t bits;
  if (type == "float" || type == "float32") {
    const float f = static_cast<float>(v);
    std::uint32_t b32;
    std::memcpy(&b32, &f, 4);
    bits = b32;
  } else if (type == "double" || type == "float64") {
    std::memcpy(&bits, &v, 8);
  } else {
    bits = static_cast<std::uint64_t>(static_cast<std::int64_t>(v));
  }
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t shift = 8 * (order == Order::big ? n - 1 - k : k);
    out += static_cast<char>((bits >> shift) & 0xff);
  }
}

// The end of a record: a text body's line end.
void end_record(std::string& out, Order order) {
  if (order == Order::ascii) out.back() = '\n';
}

std::string ply(Order order, const std::string& declarations) {
  return std::string("ply\nformat ") + format_name(order) + " 1.0\n" + declarations +
         "end_header\n";
}

const std::vector<Vec3> kPoints = {Vec3(0.5, 0.1, 3), Vec3(-100.25, 1.0 / 3.0, -7),
                                   Vec3(0, -2e-3, 1000)};

// A scanner's file: colours and a list beside the vertices' x, y, z (each of
// another type), then faces.
std::string scanner_file(Order o) {
  std::string b = ply(o,
                      "comment written by a test as a scanner would\n"
                      "obj_info num_cols 3\n"
                      "element vertex 3\n"
                      "property uchar red\n"
                      "property float x\n"
                      "property double y\n"
                      "property short z\n"
                      "property list uchar int neighbours\n"
                      "element face 2\n"
                      "property uchar flags\n"
                      "property list uchar int vertex_indices\n");
  for (std::size_t i = 0; i < kPoints.size(); ++i) {
    put(b, "uchar", 200, o);
    put(b, "float", kPoints[i].x(), o);
    put(b, "double", kPoints[i].y(), o);
    put(b, "short", kPoints[i].z(), o);
    put(b, "uchar", 2, o);
    put(b, "int", double(i), o);
    put(b, "int", double(i + 1), o);
    end_record(b, o);
  }
  for (int corners : {3, 4}) {
    put(b, "uchar", 1, o);
    put(b, "uchar", corners, o);
    for (int c = 0; c < corners; ++c)
      put(b, "int", c % 3, o);
    end_record(b, o);
  }
  return b;
}

TEST(PlyPoints, AsciiLittleAndBigEndianGiveTheSamePoints) {
  for (Order o : {Order::ascii, Order::little, Order::big}) {
    SCOPED_TRACE(format_name(o));
    const std::vector<Vec3> points = parse_ply_points(scanner_file(o), "scan.ply");
    ASSERT_EQ(points.size(), 3u);
    for (std::size_t i = 0; i < 3; ++i) {
      EXPECT_EQ(points[i].x(), double(float(kPoints[i].x())));  // a float32 property
      EXPECT_EQ(points[i].y(), kPoints[i].y());                 // float64: every bit
      EXPECT_EQ(points[i].z(), kPoints[i].z());
    }
  }
}

// Bytes written out by hand, not by the test's own encoder: 1, 2, -3 as
// float32 in each byte order.
TEST(PlyPoints, ReadsBigEndianByteSwapped) {
  const std::string head =
      "element vertex 1\nproperty float x\nproperty float y\n"
      "property float z\n";
  const std::string big =
      ply(Order::big, head) + std::string("\x3f\x80\x00\x00\x40\x00\x00\x00\xc0\x40\x00\x00", 12);
  const std::string little = ply(Order::little, head) +
                             std::string("\x00\x00\x80\x3f\x00\x00\x00\x40\x00\x00\x40\xc0", 12);
  EXPECT_EQ(parse_ply_points(big, "be.ply"), std::vector<Vec3>{Vec3(1, 2, -3)});
  EXPECT_EQ(parse_ply_points(little, "le.ply"), std::vector<Vec3>{Vec3(1, 2, -3)});
}

// Every scalar type PLY names, old and sized, as x in every format.
TEST(PlyPoints, ReadsEveryScalarType) {
  const char* types[] = {"char",   "int8",    "uchar",  "uint8",  "short", "int16",
                         "ushort", "uint16",  "int",    "int32",  "uint",  "uint32",
                         "float",  "float32", "double", "float64"};
  for (const char* type : types)
    for (Order o : {Order::ascii, Order::little, Order::big}) {
      SCOPED_TRACE(std::string(type) + " " + format_name(o));
      const bool unsigned_type = type[0] == 'u';
      const double x = unsigned_type ? 200 : -7;
      std::string b = ply(o, std::string("element vertex 2\nproperty ") + type +
                                 " x\nproperty float y\nproperty float z\n");
      for (int i = 0; i < 2; ++i) {
        put(b, type, x + i, o);
        put(b, "float", 1, o);
        put(b, "float", 2, o);
        end_record(b, o);
      }
      const std::vector<Vec3> points = parse_ply_points(b, "types.ply");
      ASSERT_EQ(points.size(), 2u);
      EXPECT_EQ(points[0], Vec3(x, 1, 2));
      EXPECT_EQ(points[1], Vec3(x + 1, 1, 2));
    }
}

// Faces (lists) declared before the vertices: read past, in every format.
TEST(PlyPoints, SkipsFacesBeforeTheVertices) {
  for (Order o : {Order::ascii, Order::little, Order::big}) {
    SCOPED_TRACE(format_name(o));
    std::string b = ply(o,
                        "element face 2\nproperty list ushort float corners\n"
                        "element vertex 2\nproperty double x\nproperty double y\n"
                        "property double z\nproperty uint8 alpha\n");
    for (int corners : {5, 0}) {
      put(b, "ushort", corners, o);
      for (int c = 0; c < corners; ++c)
        put(b, "float", 1e6 * c, o);  // the faces' values are not coordinates
      end_record(b, o);
    }
    for (int i = 0; i < 2; ++i) {
      put(b, "double", i, o);
      put(b, "double", 0.25, o);
      put(b, "double", -i, o);
      put(b, "uint8", 255, o);
      end_record(b, o);
    }
    EXPECT_EQ(parse_ply_points(b, "faces_first.ply"),
              (std::vector<Vec3>{Vec3(0, 0.25, 0), Vec3(1, 0.25, -1)}));
  }
}

// A header with CRLF line ends (a Windows tool's), blank lines in an ascii
// body, no final newline.
TEST(PlyPoints, ReadsCrlfHeadersAndBlankLines) {
  const std::string binary = std::string(
                                 "ply\r\nformat binary_little_endian 1.0\r\ncomment crlf\r\n"
                                 "element vertex 1\r\nproperty float x\r\nproperty float y\r\n"
                                 "property float z\r\nend_header\r\n") +
                             std::string("\x00\x00\x80\x3f\x00\x00\x00\x40\x00\x00\x40\xc0", 12);
  EXPECT_EQ(parse_ply_points(binary, "crlf.ply"), std::vector<Vec3>{Vec3(1, 2, -3)});
  const std::string ascii =
      "ply\r\nformat ascii 1.0\r\nelement vertex 2\r\nproperty float x\r\nproperty float y\r\n"
      "property float z\r\nend_header\r\n1 2 3\r\n\r\n  4\t5 6";
  EXPECT_EQ(parse_ply_points(ascii, "crlf.ply"), (std::vector<Vec3>{Vec3(1, 2, 3), Vec3(4, 5, 6)}));
}

// The fuzzer's seeds (tests/fuzz/corpus/ply) are files this reader accepts:
// the fuzzer starts from what real tools write.
TEST(PlyPoints, ReadsTheFuzzSeeds) {
  const std::filesystem::path seeds =
      std::filesystem::path(NEUROCLOTH_TEST_DATA) / ".." / "fuzz" / "corpus" / "ply";
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(seeds)) {
    const std::string path = entry.path().string();
    const std::string bytes = read_text_file(path, "seed", 1 << 20);
    const std::vector<Vec3> points = entry.path().extension() == ".ply"
                                         ? parse_ply_points(bytes, path)
                                         : parse_xyz_points(bytes, path);
    EXPECT_GE(points.size(), 3u) << path;
    ++files;
  }
  EXPECT_EQ(files, 5);
}

const std::string kThousandVertices =
    "element vertex 1000\nproperty float x\nproperty float y\n"
    "property float z\n";

std::string floats(int count, float v = 0.5f) {
  std::string b;
  for (int i = 0; i < count; ++i)
    put(b, "float", v, Order::little);
  return b;
}

// A header that states more vertices than the file holds is refused where the
// file ends, before anything is allocated for the stated count.
TEST(PlyPointsErrors, ACountThatLiesIsNamedWithTheByteWhereTheFileEnds) {
  const std::string head = ply(Order::little, kThousandVertices);
  const std::string b = head + floats(12 * 3 + 1);  // 12 whole vertices and a bit
  expect_input_error([&] { parse_ply_points(b, "scan.ply"); }, "scan.ply", 0, "element vertex",
                     {"ends at byte " + std::to_string(b.size()), "in vertex 12 of 1000"});
  // A huge count is refused the same way, not allocated.
  const std::string huge = ply(Order::big,
                               "element vertex 33554432\nproperty double x\n"
                               "property double y\nproperty double z\n") +
                           floats(6);
  expect_input_error([&] { parse_ply_points(huge, "huge.ply"); }, "huge.ply", 0, "element vertex",
                     {"in vertex 1 of 33554432"});
}

TEST(PlyPointsErrors, AFileEndingInsideALaterElementIsNamed) {
  std::string b = ply(Order::little,
                      "element vertex 1\nproperty float x\nproperty float y\n"
                      "property float z\nelement face 3\n"
                      "property list uchar int vertex_indices\n") +
                  floats(3);
  put(b, "uchar", 3, Order::little);
  for (int c = 0; c < 3; ++c)
    put(b, "int", c, Order::little);
  put(b, "uchar", 3, Order::little);
  put(b, "int", 0, Order::little);  // face 1 holds one of its three corners
  expect_input_error([&] { parse_ply_points(b, "faces.ply"); }, "faces.ply", 0, "element face",
                     {"ends at byte " + std::to_string(b.size()), "in face 1 of 3"});
  // A list's count that would run past the end.
  std::string c = ply(Order::little,
                      "element vertex 1\nproperty float x\nproperty float y\n"
                      "property float z\nelement face 1\n"
                      "property list uint int vertex_indices\n") +
                  floats(3);
  put(c, "uint", 4e9, Order::little);
  expect_input_error([&] { parse_ply_points(c, "faces.ply"); }, "faces.ply", 0, "element face",
                     {"in face 0 of 1"});
}

TEST(PlyPointsErrors, AbsurdCountsAreRefusedBeforeReading) {
  // Beyond what a reference may hold, whatever the file's size.
  expect_input_error(
      [&] {
        parse_ply_points(ply(Order::little,
                             "element vertex 999999999999\nproperty float x\n"
                             "property float y\nproperty float z\n"),
                         "big.ply");
      },
      "big.ply", 3, "element vertex", {"999999999999 vertices", "33554432"});
  // A list element before the vertices whose count the file cannot hold even
  // at one count byte a record.
  const std::string b = ply(Order::little,
                            "element face 100000000000000\n"
                            "property list uchar int vertex_indices\n"
                            "element vertex 1\nproperty float x\n"
                            "property float y\nproperty float z\n") +
                        floats(3);
  expect_input_error([&] { parse_ply_points(b, "big.ply"); }, "big.ply", 3, "element face",
                     {"100000000000000", "more than the file holds"});
  expect_input_error(
      [&] {
        parse_ply_points(ply(Order::ascii, "element vertex 12345678901234567890\n"), "n.ply");
      },
      "n.ply", 3, "element vertex", {"not a whole number"});
  // Ascii: a value takes a character at least.
  expect_input_error(
      [&] { parse_ply_points(ply(Order::ascii, kThousandVertices) + "1 2 3\n", "a.ply"); }, "a.ply",
      3, "element vertex", {"more than the file holds"});
}

TEST(PlyPointsErrors, TrailingDataIsNamed) {
  const std::string b = ply(Order::little,
                            "element vertex 1\nproperty float x\n"
                            "property float y\nproperty float z\n") +
                        floats(3) + "\n\n";
  expect_input_error(
      [&] { parse_ply_points(b, "tail.ply"); }, "tail.ply", 0, "element vertex",
      {"2 bytes after the last element", "from byte " + std::to_string(b.size() - 2)});
  const std::string a = ply(Order::ascii,
                            "element vertex 1\nproperty float x\n"
                            "property float y\nproperty float z\n") +
                        "1 2 3\n\n4 5 6\n";
  expect_input_error([&] { parse_ply_points(a, "tail.ply"); }, "tail.ply", 10, "element vertex",
                     {"data after the last element"});
}

TEST(PlyPointsErrors, AnAsciiBodyThatEndsEarlyOrMiscountsIsNamedByLine) {
  const std::string head = ply(Order::ascii,
                               "element vertex 5\nproperty float x\n"
                               "property float y\nproperty float z\n");
  // Values long enough for the count check before reading (a character each) to pass.
  expect_input_error([&] { parse_ply_points(head + "1.00 2.00 3.00\n4.00 5.00 6.00\n", "a.ply"); },
                     "a.ply", 9, "element vertex", {"ends at line 9 in vertex 2 of 5"});
  expect_input_error([&] { parse_ply_points(head + "1.00 2.00 3.00\n4.00 5.00\n", "a.ply"); },
                     "a.ply", 9, "z", {"vertex 1 has 2 values"});
  expect_input_error(
      [&] { parse_ply_points(head + "1 2 3\n4 5 6 7\n1 1 1\n1 1 1\n1 1 1\n", "a.ply"); }, "a.ply",
      9, "element vertex", {"vertex 1 has 4 values"});
  const std::string lists = ply(Order::ascii,
                                "element vertex 1\nproperty float x\n"
                                "property float y\nproperty float z\n"
                                "element face 1\nproperty list uchar int idx\n") +
                            "1 2 3\n";
  expect_input_error([&] { parse_ply_points(lists + "4 0 1 2\n", "a.ply"); }, "a.ply", 11, "idx",
                     {"face 0: a list of '4' items", "3 values after it"});
  expect_input_error([&] { parse_ply_points(lists + "1.5 0 1 2\n", "a.ply"); }, "a.ply", 11, "idx",
                     {"whole number"});
}

TEST(PlyPointsErrors, NanInfiniteOrHugeCoordinatesAreNamedWithTheirByte) {
  const std::string head = ply(Order::little,
                               "element vertex 2\nproperty float x\n"
                               "property float y\nproperty float z\n");
  const std::string nan = head + floats(4) + floats(1, NAN) + floats(1);
  expect_input_error([&] { parse_ply_points(nan, "nan.ply"); }, "nan.ply", 0, "y",
                     {"vertex 1 at byte " + std::to_string(head.size() + 16), "NaN or infinite"});
  const std::string inf = head + floats(5) + floats(1, INFINITY);
  expect_input_error([&] { parse_ply_points(inf, "inf.ply"); }, "inf.ply", 0, "z",
                     {"vertex 1 at byte " + std::to_string(head.size() + 20)});
  std::string big = ply(Order::big,
                        "element vertex 1\nproperty double x\nproperty double y\n"
                        "property double z\n");
  put(big, "double", -2e6, Order::big);
  put(big, "double", 0, Order::big);
  put(big, "double", 0, Order::big);
  expect_input_error([&] { parse_ply_points(big, "big.ply"); }, "big.ply", 0, "x",
                     {"vertex 0 at byte", "beyond 1e6 m"});
  // A uint32 coordinate beyond 1e6 is refused as a float's would be.
  std::string u = ply(Order::little,
                      "element vertex 1\nproperty uint x\nproperty uint y\n"
                      "property uint z\n");
  for (double v : {1.0, 4e9, 1.0})
    put(u, "uint", v, Order::little);
  expect_input_error([&] { parse_ply_points(u, "u.ply"); }, "u.ply", 0, "y", {"beyond 1e6 m"});
  const std::string a = ply(Order::ascii,
                            "element vertex 2\nproperty float x\n"
                            "property float y\nproperty float z\n") +
                        "1 2 3\n1 2 nan\n";
  expect_input_error([&] { parse_ply_points(a, "a.ply"); }, "a.ply", 9, "z",
                     {"vertex 1", "NaN or infinite"});
  const std::string huge = ply(Order::ascii,
                               "element vertex 1\nproperty float x\n"
                               "property float y\nproperty float z\n") +
                           "1 2 1e7\n";
  expect_input_error([&] { parse_ply_points(huge, "a.ply"); }, "a.ply", 8, "z",
                     {"vertex 0", "beyond 1e6 m"});
}

TEST(PlyPointsErrors, ANegativeBinaryListCountIsNamed) {
  std::string b = ply(Order::little,
                      "element face 1\nproperty list char int idx\n"
                      "element vertex 1\nproperty float x\nproperty float y\n"
                      "property float z\n");
  const std::size_t at = b.size();
  put(b, "char", -1, Order::little);
  b += floats(3);
  expect_input_error([&] { parse_ply_points(b, "neg.ply"); }, "neg.ply", 0, "idx",
                     {"face 0 at byte " + std::to_string(at), "a list of -1 items"});
}

}  // namespace
}  // namespace neurocloth
