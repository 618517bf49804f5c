#include "core/io/obj_triangles.h"

#include <tiny_obj_loader.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <utility>

#include "core/io/input_error.h"
#include "core/io/text_file.h"

namespace neurocloth {
namespace {

// tinyobjloader reports some problems as "... line N ..." inside its message.
int line_from_message(const std::string& msg) {
  return number_after(msg, "line ");
}

std::string first_line(std::string s) {
  while (!s.empty() && (s.back() == '\n' || s.back() == '\r'))
    s.pop_back();
  const auto nl = s.find('\n');
  return nl == std::string::npos ? s : s.substr(0, nl);
}

// "4 million" for 4'000'000, else the digits.
std::string count_name(std::size_t n) {
  return n >= 1'000'000 && n % 1'000'000 == 0 ? std::to_string(n / 1'000'000) + " million"
                                              : std::to_string(n);
}

bool space_or_tab(char c) {
  return c == ' ' || c == '\t';
}

// A decimal number as OBJ writes one ("-1.5", "2e-3"); tinyobjloader reads
// anything else ("nan", "inf", "0x1p3") as 0 without a word.
bool decimal(const std::string& s) {
  std::size_t i = s[0] == '+' || s[0] == '-' ? 1 : 0, digits = 0;
  for (; i < s.size() && std::isdigit(static_cast<unsigned char>(s[i])); ++i)
    ++digits;
  if (i < s.size() && s[i] == '.')
    for (++i; i < s.size() && std::isdigit(static_cast<unsigned char>(s[i])); ++i)
      ++digits;
  if (digits == 0) return false;
  if (i < s.size() && (s[i] == 'e' || s[i] == 'E')) {
    i += i + 1 < s.size() && (s[i + 1] == '+' || s[i + 1] == '-') ? 2 : 1;
    const std::size_t from = i;
    while (i < s.size() && std::isdigit(static_cast<unsigned char>(s[i])))
      ++i;
    if (i == from) return false;
  }
  return i == s.size();
}

// A vertex's x, y and z: decimal and finite (a w or a colour may follow).
void check_vertex(const std::string& text, std::size_t from, std::size_t end, std::size_t vertex,
                  int line, const std::string& path) {
  std::size_t k = from;
  for (int axis = 0; axis < 3; ++axis) {
    while (k < end && space_or_tab(text[k]))
      ++k;
    const std::size_t start = k;
    while (k < end && !space_or_tab(text[k]))
      ++k;
    const std::string token = text.substr(start, k - start);
    const std::string which = "vertex " + std::to_string(vertex) + " (" + "xyz"[axis] + ")";
    if (token.empty()) throw InputError(path, "v", which + " is missing", line);
    const double value = decimal(token) ? std::strtod(token.c_str(), nullptr) : NAN;
    if (!std::isfinite(value))
      throw InputError(path, "v", which + ": '" + token + "' is not a finite number", line);
    // Before any scale: the scene checks what it places.
    if (std::abs(value) > kMaxObjCoordinate)
      throw InputError(path, "v", which + ": " + token + " is beyond +-1e10 in any unit", line);
  }
}

// The statements a mesh is built from, and those tinyobjloader must see for
// the face indices to mean what the file says (texture coordinates, normals).
// Groups, objects and smoothing groups are harmless.
bool needed(const std::string& text, std::size_t from, std::size_t end) {
  std::size_t k = from;
  while (k < end && !space_or_tab(text[k]))
    ++k;
  const std::string keyword = text.substr(from, k - from);
  for (const char* kept : {"v", "vt", "vn", "f", "o", "g", "s"})
    if (keyword == kept) return true;
  return false;
}

// One pass over the text before tinyobjloader sees it (obj_triangles.h): every
// refusal it can make with the line, every unused statement blanked (line ends
// kept), and the line of every face returned. Lines end as tinyobjloader ends
// them (\n, \r\n or \r).
std::vector<int> screen(std::string& text, const std::string& path, const ObjLimits& limits) {
  std::vector<int> lines;
  std::size_t vertices = 0, triangles = 0;
  int line = 1;
  for (std::size_t i = 0; i < text.size(); ++line) {
    std::size_t end = i;
    while (end < text.size() && text[end] != '\n' && text[end] != '\r')
      ++end;
    std::size_t p = i;
    while (p < end && space_or_tab(text[p]))
      ++p;
    if (p < end && text[p] != '#' && !needed(text, p, end))
      std::fill(text.begin() + static_cast<std::ptrdiff_t>(p),
                text.begin() + static_cast<std::ptrdiff_t>(end), ' ');
    const bool face = p + 1 < end && text[p] == 'f' && space_or_tab(text[p + 1]);
    const bool vertex = p + 1 < end && text[p] == 'v' && space_or_tab(text[p + 1]);
    if (vertex) {
      if (++vertices > limits.vertices)
        throw InputError(path, "v", "more than " + count_name(limits.vertices) + " vertices", line);
      check_vertex(text, p + 1, end, vertices, line, path);
    }
    if (face) {
      std::size_t corners = 0;
      for (std::size_t k = p + 1; k < end;) {
        while (k < end && space_or_tab(text[k]))
          ++k;
        if (k == end) break;
        ++corners;
        while (k < end && !space_or_tab(text[k]))
          ++k;
        if (corners > kMaxObjFaceCorners)
          throw InputError(
              path, "f", "a face with more than " + std::to_string(kMaxObjFaceCorners) + " corners",
              line);
      }
      if (corners < 3)
        throw InputError(path, "f",
                         "a face needs at least 3 corners (got " + std::to_string(corners) + ")",
                         line);
      triangles += corners - 2;
      if (triangles > limits.triangles)
        throw InputError(path, "f", "more than " + count_name(limits.triangles) + " triangles",
                         line);
      lines.push_back(line);
    }
    i = end;
    if (i < text.size() && text[i] == '\r') ++i;  // \r, or the first half of \r\n
    if (i < text.size() && text[i] == '\n') ++i;
  }
  return lines;
}

// A polygon as triangles (obj_triangles.h), its diagonals measured at `at`.
void triangulate(const std::vector<int>& corners, const std::vector<Vec3>& at, int line,
                 ObjTriangles& out) {
  const std::size_t n = corners.size();
  if (n == 4) {
    const double d02 = (at[corners[2]] - at[corners[0]]).squaredNorm();
    const double d13 = (at[corners[3]] - at[corners[1]]).squaredNorm();
    if (d02 < d13) {
      out.triangles.push_back({corners[0], corners[1], corners[2]});
      out.triangles.push_back({corners[0], corners[2], corners[3]});
    } else {
      out.triangles.push_back({corners[0], corners[1], corners[3]});
      out.triangles.push_back({corners[1], corners[2], corners[3]});
    }
  } else {
    for (std::size_t k = 1; k + 1 < n; ++k)
      out.triangles.push_back({corners[0], corners[k], corners[k + 1]});
  }
  out.lines.resize(out.triangles.size(), line);
}

}  // namespace

ObjTriangles parse_obj_triangles(std::string text, const std::string& path, const ObjLimits& limits,
                                 const ObjPlacement& place) {
  const std::vector<int> lines = screen(text, path, limits);
  tinyobj::ObjReaderConfig config;
  config.triangulate = false;  // ours is linear in the corners and knows each face's line
  config.vertex_color = false;
  tinyobj::ObjReader reader;
  if (!reader.ParseFromString(text, "", config)) {
    const std::string err = first_line(reader.Error());
    throw InputError(path, "", "broken OBJ: " + (err.empty() ? "parse failed" : err),
                     line_from_message(reader.Error()));
  }
  const auto& attrib = reader.GetAttrib();
  const int vertex_count = static_cast<int>(attrib.vertices.size() / 3);

  ObjTriangles out;
  out.vertices.reserve(vertex_count);
  for (int i = 0; i < vertex_count; ++i) {
    const Vec3 v(attrib.vertices[3 * i], attrib.vertices[3 * i + 1], attrib.vertices[3 * i + 2]);
    if (!v.allFinite())
      throw InputError(path, "v", "vertex " + std::to_string(i + 1) + " is not finite");
    out.vertices.push_back(v);
  }
  std::vector<Vec3> placed;
  if (place) {
    placed.reserve(out.vertices.size());
    for (const Vec3& v : out.vertices)
      placed.push_back(place(v));
  }
  const std::vector<Vec3>& at = place ? placed : out.vertices;

  std::size_t face = 0;  // across shapes, in file order: the index into `lines`
  std::vector<int> corners;
  for (const auto& shape : reader.GetShapes()) {
    const auto& mesh = shape.mesh;
    std::size_t offset = 0;
    for (std::size_t f = 0; f < mesh.num_face_vertices.size(); ++f, ++face) {
      const int line = face < lines.size() ? lines[face] : 0;
      const std::size_t n = mesh.num_face_vertices[f];
      corners.clear();
      for (std::size_t k = 0; k < n; ++k) {
        const int idx = mesh.indices[offset + k].vertex_index;
        if (idx < 0 || idx >= vertex_count)
          throw InputError(path, "f",
                           "face refers to vertex " + std::to_string(idx + 1) +
                               " but the file has " + std::to_string(vertex_count),
                           line);
        if (std::find(corners.begin(), corners.end(), idx) != corners.end())
          throw InputError(path, "f", "degenerate face repeats vertex " + std::to_string(idx + 1),
                           line);
        corners.push_back(idx);
      }
      offset += n;
      triangulate(corners, at, line, out);
    }
  }
  if (out.triangles.empty()) throw InputError(path, "f", "the mesh has no faces");
  return out;
}

ObjTriangles read_obj_triangles(const std::string& path, const ObjLimits& limits,
                                const ObjPlacement& place) {
  return parse_obj_triangles(read_text_file(path, "OBJ file", limits.bytes), path, limits, place);
}

}  // namespace neurocloth
