#include "learn/motion/ply_header.h"

#include <string_view>

#include "core/io/csv_fields.h"
#include "core/io/input_error.h"
#include "learn/motion/reference_motion.h"

namespace neurocloth {
namespace {

// PLY 1.0's names, and the sized names later writers use (VTK, Open3D).
constexpr PlyType kTypes[] = {
    {"char", PlyScalar::int8, 1},      {"int8", PlyScalar::int8, 1},
    {"uchar", PlyScalar::uint8, 1},    {"uint8", PlyScalar::uint8, 1},
    {"short", PlyScalar::int16, 2},    {"int16", PlyScalar::int16, 2},
    {"ushort", PlyScalar::uint16, 2},  {"uint16", PlyScalar::uint16, 2},
    {"int", PlyScalar::int32, 4},      {"int32", PlyScalar::int32, 4},
    {"uint", PlyScalar::uint32, 4},    {"uint32", PlyScalar::uint32, 4},
    {"float", PlyScalar::float32, 4},  {"float32", PlyScalar::float32, 4},
    {"double", PlyScalar::float64, 8}, {"float64", PlyScalar::float64, 8}};

const PlyType* type_named(std::string_view name) {
  for (const PlyType& t : kTypes)
    if (name == t.name) return &t;
  return nullptr;
}

// A header count: decimal digits only, at most 18 of them (far above any
// file's, far below overflow).
bool whole_count(std::string_view s, std::uint64_t& out) {
  if (s.empty() || s.size() > 18) return false;
  out = 0;
  for (const char c : s) {
    if (c < '0' || c > '9') return false;
    out = out * 10 + static_cast<std::uint64_t>(c - '0');
  }
  return true;
}

std::string plural(std::uint64_t n, const std::string& name) {
  return std::to_string(n) + " " + name + (n == 1 ? "" : "s");
}

// The header: line by line up to end_header, every keyword checked.
class HeaderReader {
 public:
  HeaderReader(const std::string& bytes, const std::string& path) : bytes_(bytes), path_(path) {}

  PlyHeader read() {
    for (std::size_t at = 0;;) {
      if (at >= bytes_.size())
        throw InputError(path_, "end_header", "the file ends inside its header", line_);
      const std::size_t eol = bytes_.find('\n', at);
      const std::size_t end = eol == std::string::npos ? bytes_.size() : eol;
      if (end >= kMaxPlyHeaderBytes)
        throw InputError(path_, "end_header",
                         "no end_header in the first " + std::to_string(kMaxPlyHeaderBytes >> 10) +
                             " KiB: a header longer than any real PLY's",
                         line_ + 1);
      ++line_;
      const std::string_view line(bytes_.data() + at, end - at);
      at = end + 1;
      if (line_ == 1) {
        if (ply_words(line).size() != 1 || ply_words(line)[0] != "ply")
          throw InputError(path_, "ply",
                           "not a PLY file: the first line must be 'ply', found " + shown(line), 1);
        continue;
      }
      if (keyword(line)) {
        header_.body = std::min(at, bytes_.size());
        header_.lines = line_;
        return checked();
      }
    }
  }

 private:
  // One header line; true at end_header.
  bool keyword(std::string_view line) {
    const auto w = ply_words(line);
    if (w.empty()) return false;
    if (w[0] == "comment" || w[0] == "obj_info") return false;
    if (w[0] == "format") {
      format(w);
    } else if (w[0] == "element") {
      element(w);
    } else if (w[0] == "property") {
      property(w);
    } else if (w[0] == "end_header") {
      if (w.size() != 1) fail("end_header", "expected 'end_header' alone, found " + shown(line));
      if (!have_format_) fail("format", "no format line before end_header");
      return true;
    } else {
      fail("header", "unknown keyword " + shown(w[0]) +
                         " (a PLY header has format, element, property, comment, obj_info and "
                         "end_header lines)");
    }
    return false;
  }

  void format(const std::vector<std::string_view>& w) {
    if (have_format_) fail("format", "a second format line");
    if (w.size() != 3)
      fail("format", "expected 'format ascii|binary_little_endian|binary_big_endian 1.0'");
    if (w[1] == "ascii")
      header_.format = PlyFormat::ascii;
    else if (w[1] == "binary_little_endian")
      header_.format = PlyFormat::little_endian;
    else if (w[1] == "binary_big_endian")
      header_.format = PlyFormat::big_endian;
    else
      fail("format", "unknown format " + shown(w[1]) +
                         " (expected ascii, binary_little_endian or binary_big_endian)");
    if (w[2] != "1.0" && w[2] != "1")
      fail("format", "version " + shown(w[2]) + ": this reader reads PLY 1.0");
    have_format_ = true;
  }

  void element(const std::vector<std::string_view>& w) {
    if (!have_format_) fail("format", "an element before the format line");
    if (w.size() != 3) fail("element", "expected 'element NAME COUNT'");
    PlyElement e;
    e.name = std::string(w[1]);
    e.line = line_;
    if (!whole_count(w[2], e.count))
      fail("element " + e.name, "count " + shown(w[2]) + " is not a whole number below 1e18");
    for (const PlyElement& other : header_.elements)
      if (other.name == e.name) fail("element " + e.name, "declared twice");
    header_.elements.push_back(std::move(e));
  }

  void property(const std::vector<std::string_view>& w) {
    if (header_.elements.empty()) fail("property", "a property before any element");
    PlyElement& e = header_.elements.back();
    PlyProperty p;
    if (w.size() >= 2 && w[1] == "list") {
      if (w.size() != 5) fail("property", "expected 'property list COUNT_TYPE ITEM_TYPE NAME'");
      p.count = type(w[2]);
      if (p.count->scalar == PlyScalar::float32 || p.count->scalar == PlyScalar::float64)
        fail("property " + std::string(w[4]),
             "a list's count type must be an integer type, not " + shown(w[2]));
      p.type = type(w[3]);
      p.name = std::string(w[4]);
    } else {
      if (w.size() != 3) fail("property", "expected 'property TYPE NAME'");
      p.type = type(w[1]);
      p.name = std::string(w[2]);
    }
    for (const PlyProperty& other : e.properties)
      if (other.name == p.name) fail("property " + p.name, "declared twice in " + e.name);
    e.properties.push_back(std::move(p));
  }

  const PlyType* type(std::string_view name) const {
    const PlyType* t = type_named(name);
    if (!t)
      fail("property", "unknown type " + shown(name) +
                           " (char uchar short ushort int uint float double, or int8 uint8 int16 "
                           "uint16 int32 uint32 float32 float64)");
    return t;
  }

  // What the body's reading relies on: a vertex element with scalar x, y, z.
  PlyHeader checked() {
    std::size_t v = 0;
    while (v < header_.elements.size() && header_.elements[v].name != "vertex")
      ++v;
    if (v == header_.elements.size())
      throw InputError(path_, "element vertex",
                       "no vertex element: a point cloud's points are its vertices");
    header_.vertex = v;
    PlyElement& e = header_.elements[v];
    for (int axis = 0; axis < 3; ++axis) {
      const char name[2] = {"xyz"[axis], 0};
      PlyProperty* found = nullptr;
      for (PlyProperty& p : e.properties)
        if (p.name == name) found = &p;
      if (!found || found->count)
        throw InputError(path_, name,
                         std::string("the vertex element has no ") + (found ? "scalar " : "") +
                             "property " + name,
                         e.line);
      found->axis = axis;
    }
    if (e.count == 0) throw InputError(path_, "element vertex", "no points: 0 vertices", e.line);
    if (e.count > kMaxReferenceObservations)
      throw InputError(path_, "element vertex",
                       std::to_string(e.count) + " vertices: more than the " +
                           std::to_string(kMaxReferenceObservations) +
                           " points a reference may hold",
                       e.line);
    return std::move(header_);
  }

  [[noreturn]] void fail(const std::string& field, const std::string& message) const {
    throw InputError(path_, field, message, line_);
  }

  const std::string& bytes_;
  const std::string& path_;
  PlyHeader header_;
  bool have_format_ = false;
  int line_ = 0;
};

// The least a record of `e` takes: each property's bytes (a list's count
// alone) in a binary body; a character per value in a text one.
std::uint64_t least_record_bytes(const PlyElement& e, PlyFormat format) {
  if (format == PlyFormat::ascii) return e.properties.size();
  std::uint64_t n = 0;
  for (const PlyProperty& p : e.properties)
    n += p.count ? p.count->bytes : p.type->bytes;
  return n;
}

bool fixed_size(const PlyElement& e) {
  for (const PlyProperty& p : e.properties)
    if (p.count) return false;
  return true;
}

// Every element's count against the bytes after the header, before anything
// is allocated or walked: a count that lies is refused here when the file
// cannot hold even the least its records take.
void check_counts(const PlyHeader& h, std::size_t size, const std::string& path) {
  std::uint64_t at = h.body;
  bool exact = h.format != PlyFormat::ascii;  // each element starts where `at` says
  for (const PlyElement& e : h.elements) {
    const std::uint64_t least = least_record_bytes(e, h.format);
    if (least == 0) continue;  // no properties: its records take no bytes
    const std::uint64_t room = size - at;
    if (e.count > room / least) {
      if (exact && fixed_size(e))
        throw InputError(path, "element " + e.name,
                         "the file ends at byte " + std::to_string(size) + " in " + e.name + " " +
                             std::to_string(room / least) + " of " + std::to_string(e.count) +
                             " (the header states more than the file holds)");
      throw InputError(path, "element " + e.name,
                       "the header states " + std::to_string(e.count) + " " + e.name +
                           " records of at least " + plural(least, "byte") + " from byte " +
                           std::to_string(at) + "; the file has " + plural(room, "byte") +
                           " there (the count is more than the file holds)",
                       e.line);
    }
    at += e.count * least;
    exact = exact && fixed_size(e);
  }
}

}  // namespace

std::vector<std::string_view> ply_words(std::string_view line) {
  std::vector<std::string_view> out;
  const auto space = [](char c) { return c == ' ' || c == '\t' || c == '\r'; };
  for (std::size_t i = 0; i < line.size();) {
    while (i < line.size() && space(line[i]))
      ++i;
    const std::size_t from = i;
    while (i < line.size() && !space(line[i]))
      ++i;
    if (i > from) out.push_back(line.substr(from, i - from));
  }
  return out;
}

PlyHeader read_ply_header(const std::string& bytes, const std::string& path) {
  PlyHeader header = HeaderReader(bytes, path).read();
  check_counts(header, bytes.size(), path);
  return header;
}

}  // namespace neurocloth
