#pragma once
// A PLY file's header (ply_points.h shows one): its format, and its elements
// with their counts and properties, in the order the body holds them. Read
// and checked before the body is touched: the keywords, the types, a vertex
// element with scalar x, y and z, and every count against the bytes that
// follow the header.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace neurocloth {

// The longest header accepted: a few hundred bytes in every real file.
inline constexpr std::size_t kMaxPlyHeaderBytes = 64 * 1024;

enum class PlyScalar { int8, uint8, int16, uint16, int32, uint32, float32, float64 };

struct PlyType {
  const char* name;
  PlyScalar scalar;
  std::size_t bytes;  // in a binary body
};

struct PlyProperty {
  std::string name;
  const PlyType* type = nullptr;   // a scalar's, or a list's items'
  const PlyType* count = nullptr;  // a list's count (an integer type); null for a scalar
  int axis = -1;                   // 0, 1, 2 for the vertex element's x, y, z
};

struct PlyElement {
  std::string name;
  std::uint64_t count = 0;
  std::vector<PlyProperty> properties;
  int line = 0;  // where the header declares it
};

enum class PlyFormat { ascii, little_endian, big_endian };

struct PlyHeader {
  PlyFormat format = PlyFormat::ascii;
  std::vector<PlyElement> elements;
  std::size_t vertex = 0;  // the vertex element's index in `elements`
  std::size_t body = 0;    // the offset of the body's first byte
  int lines = 0;           // the header's lines: an ascii body starts on the next
};

// The header of `bytes`, checked: a vertex element of 1 to
// kMaxReferenceObservations vertices with scalar x, y and z, and no element
// whose count the bytes after the header cannot hold at the least each record
// takes (a property's bytes, a list's count alone; a character per value in
// ascii). Throws InputError naming `path`, the line or byte offset and the
// field.
PlyHeader read_ply_header(const std::string& bytes, const std::string& path);

// The words of a header line or the values of an ascii body's line: split at
// spaces, tabs and carriage returns (CRLF files).
std::vector<std::string_view> ply_words(std::string_view line);

}  // namespace neurocloth
