#include "core/scene/triangle_springs.h"

#include <algorithm>
#include <map>
#include <utility>
#include <vector>

#include "core/scene/mesh_node_order.h"
#include "core/scene/stencil_order.h"

namespace neurocloth {

void add_triangle_springs(ClothTopology& t, bool bend) {
  // Each undirected edge -> the vertices opposite it (one per adjacent triangle).
  std::map<std::pair<int, int>, std::vector<int>> edges;
  for (const auto& tri : t.triangles)
    for (int k = 0; k < 3; ++k) {
      const int a = tri[k], b = tri[(k + 1) % 3], opposite = tri[(k + 2) % 3];
      edges[{std::min(a, b), std::max(a, b)}].push_back(opposite);
    }
  for (const auto& [edge, opposite] : edges)
    t.springs.push_back({edge.first, edge.second, SpringFamily::structural});
  if (bend) {
    for (const auto& [edge, opposite] : edges) {
      if (opposite.size() != 2 || opposite[0] == opposite[1]) continue;  // boundary or non-manifold
      t.springs.push_back({std::min(opposite[0], opposite[1]), std::max(opposite[0], opposite[1]),
                           SpringFamily::bend});
    }
  }
  // Springs into runs where the mesh is regular; nodes into an order that gives
  // runs if the builder's does not. Users still count nodes in the builder's
  // order (t.numbering).
  sort_into_stencil_runs(t.springs);
  order_nodes_for_runs(t);
}

}  // namespace neurocloth
