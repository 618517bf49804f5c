#include "core/scene/obj_mesh_builder.h"

#include <algorithm>
#include <limits>
#include <map>
#include <utility>

#include "core/io/obj_triangles.h"
#include "core/io/text_file.h"
#include "core/scene/mesh_node_order.h"
#include "core/scene/stencil_order.h"

namespace neurocloth {
namespace {

// As many nodes as the largest grid a scene may declare.
constexpr std::size_t kMaxVertices = 4'000'000;

}  // namespace

ClothTopology build_obj_mesh(const ObjMeshSpec& spec) {
  // A cloth has no limit of its own on triangles: its bytes bound them.
  const ObjLimits limits{kMaxMeshBytes, kMaxVertices, std::numeric_limits<std::size_t>::max()};
  ObjTriangles obj = read_obj_triangles(
      spec.path, limits, [&](const Vec3& v) -> Vec3 { return spec.scale * v + spec.translate; });
  ClothTopology t;
  t.rest_positions.reserve(obj.vertices.size());
  for (const Vec3& v : obj.vertices)
    t.rest_positions.push_back(spec.scale * v + spec.translate);
  t.triangles = std::move(obj.triangles);

  // Each undirected edge -> the vertices opposite it (one per adjacent triangle).
  std::map<std::pair<int, int>, std::vector<int>> edges;
  for (const auto& tri : t.triangles)
    for (int k = 0; k < 3; ++k) {
      const int a = tri[k], b = tri[(k + 1) % 3], opposite = tri[(k + 2) % 3];
      edges[{std::min(a, b), std::max(a, b)}].push_back(opposite);
    }
  for (const auto& [edge, opposite] : edges)
    t.springs.push_back({edge.first, edge.second, SpringFamily::structural});
  if (spec.bend) {
    for (const auto& [edge, opposite] : edges) {
      if (opposite.size() != 2 || opposite[0] == opposite[1]) continue;  // boundary or non-manifold
      t.springs.push_back({std::min(opposite[0], opposite[1]), std::max(opposite[0], opposite[1]),
                           SpringFamily::bend});
    }
  }
  // Springs into runs where the mesh is regular; nodes into an order that gives
  // runs if the file's does not. Users still count nodes as the file counts
  // its vertices (t.numbering).
  sort_into_stencil_runs(t.springs);
  order_nodes_for_runs(t);
  return t;
}

}  // namespace neurocloth
