#include "obj_mesh_builder.h"

#include <tiny_obj_loader.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <utility>

#include "input_error.h"

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

}  // namespace

ClothTopology build_obj_mesh(const ObjMeshSpec& spec) {
  {
    std::ifstream probe(spec.path);
    if (!probe) throw InputError(spec.path, "", "cannot open OBJ file");
  }
  tinyobj::ObjReaderConfig config;
  config.triangulate = true;
  config.vertex_color = false;
  tinyobj::ObjReader reader;
  if (!reader.ParseFromFile(spec.path, config)) {
    const std::string err = first_line(reader.Error());
    throw InputError(spec.path, "", "broken OBJ: " + (err.empty() ? "parse failed" : err),
                     line_from_message(reader.Error()));
  }
  const auto& attrib = reader.GetAttrib();
  const int vertex_count = static_cast<int>(attrib.vertices.size() / 3);

  ClothTopology t;
  t.rest_positions.reserve(vertex_count);
  for (int i = 0; i < vertex_count; ++i) {
    const Vec3 v(attrib.vertices[3 * i], attrib.vertices[3 * i + 1], attrib.vertices[3 * i + 2]);
    if (!v.allFinite())
      throw InputError(spec.path, "v", "vertex " + std::to_string(i + 1) + " is not finite");
    t.rest_positions.push_back(spec.scale * v + spec.translate);
  }
  for (const auto& shape : reader.GetShapes()) {
    const auto& mesh = shape.mesh;
    size_t offset = 0;
    for (size_t f = 0; f < mesh.num_face_vertices.size(); ++f) {
      const int n = mesh.num_face_vertices[f];
      if (n != 3)
        throw InputError(spec.path, "f",
                         "face with " + std::to_string(n) + " vertices after triangulation");
      std::array<std::int32_t, 3> tri{};
      for (int k = 0; k < 3; ++k) {
        const int idx = mesh.indices[offset + k].vertex_index;
        if (idx < 0 || idx >= vertex_count)
          throw InputError(spec.path, "f",
                           "face refers to vertex " + std::to_string(idx + 1) +
                               " but the file has " + std::to_string(vertex_count));
        tri[k] = idx;
      }
      offset += 3;
      if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2])
        throw InputError(spec.path, "f",
                         "degenerate face repeats a vertex (" + std::to_string(tri[0] + 1) + ", " +
                             std::to_string(tri[1] + 1) + ", " + std::to_string(tri[2] + 1) + ")");
      t.triangles.push_back(tri);
    }
  }
  if (t.triangles.empty()) throw InputError(spec.path, "f", "the mesh has no faces");

  // Each undirected edge -> the vertices opposite it (one per adjacent triangle).
  std::map<std::pair<int, int>, std::vector<int>> edges;
  for (const auto& tri : t.triangles)
    for (int k = 0; k < 3; ++k) {
      const int a = tri[k], b = tri[(k + 1) % 3], opposite = tri[(k + 2) % 3];
      edges[{std::min(a, b), std::max(a, b)}].push_back(opposite);
    }
  // std::map iterates edges in (a, b) order: deterministic, and consecutive edges
  // of a regular mesh often form stencil runs.
  for (const auto& [edge, opposite] : edges)
    t.springs.push_back({edge.first, edge.second, SpringFamily::structural});
  if (spec.bend) {
    for (const auto& [edge, opposite] : edges) {
      if (opposite.size() != 2 || opposite[0] == opposite[1]) continue;  // boundary or non-manifold
      t.springs.push_back({std::min(opposite[0], opposite[1]), std::max(opposite[0], opposite[1]),
                           SpringFamily::bend});
    }
  }
  return t;
}

}  // namespace neurocloth
