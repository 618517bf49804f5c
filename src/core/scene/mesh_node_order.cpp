#include "core/scene/mesh_node_order.h"

#include <algorithm>
#include <numeric>
#include <utility>

#include "core/scene/stencil_order.h"

namespace neurocloth {
namespace {

// Each node's structural neighbours, packed: those of node i are
// neighbour[first[i]] .. neighbour[first[i + 1]].
struct Adjacency {
  std::vector<std::int32_t> first, neighbour;
  int degree(int i) const { return first[i + 1] - first[i]; }
};

Adjacency structural_adjacency(std::size_t node_count, const std::vector<SpringSpec>& springs) {
  Adjacency g;
  g.first.assign(node_count + 1, 0);
  for (const SpringSpec& s : springs)
    if (s.family == SpringFamily::structural) {
      ++g.first[s.a + 1];
      ++g.first[s.b + 1];
    }
  std::partial_sum(g.first.begin(), g.first.end(), g.first.begin());
  g.neighbour.resize(static_cast<std::size_t>(g.first.back()));
  std::vector<std::int32_t> next(g.first.begin(), g.first.end() - 1);
  for (const SpringSpec& s : springs)
    if (s.family == SpringFamily::structural) {
      g.neighbour[next[s.a]++] = s.b;
      g.neighbour[next[s.b]++] = s.a;
    }
  return g;
}

bool before(const Adjacency& g, int x, int y) {
  return std::make_pair(g.degree(x), x) < std::make_pair(g.degree(y), y);
}

// Where a breadth-first search's last level starts in its order, and how many
// levels below its root it reached.
struct Levels {
  std::size_t last = 0;
  int depth = 0;
};

// Breadth-first from `root` over the nodes not yet reached by search `id`
// (`reached` holds, per node, the last search that reached it), appending them
// to `order`, the children of one node by degree then index.
Levels breadth_first(const Adjacency& g, int root, int id, std::vector<std::int32_t>& reached,
                     std::vector<std::int32_t>& order) {
  Levels levels;
  levels.last = order.size();
  order.push_back(root);
  reached[root] = id;
  std::size_t level_end = order.size();
  std::vector<std::int32_t> children;
  for (std::size_t k = levels.last; k < order.size(); ++k) {
    if (k == level_end) {
      levels.last = k;
      ++levels.depth;
      level_end = order.size();
    }
    const int n = order[k];
    children.clear();
    for (int e = g.first[n]; e < g.first[n + 1]; ++e)
      if (reached[g.neighbour[e]] != id) {
        reached[g.neighbour[e]] = id;
        children.push_back(g.neighbour[e]);
      }
    std::sort(children.begin(), children.end(), [&g](int x, int y) { return before(g, x, y); });
    order.insert(order.end(), children.begin(), children.end());
  }
  return levels;
}

// George and Liu: from a vertex of least degree, move to a least-degree vertex
// of the farthest level while that makes the search deeper. Trial searches
// take fresh ids from `id`.
int pseudo_peripheral(const Adjacency& g, int root, int& id, std::vector<std::int32_t>& reached) {
  std::vector<std::int32_t> order;
  for (int depth = -1;;) {
    order.clear();
    const Levels levels = breadth_first(g, root, ++id, reached, order);
    if (levels.depth <= depth) return root;
    depth = levels.depth;
    root = *std::min_element(order.begin() + static_cast<std::ptrdiff_t>(levels.last), order.end(),
                             [&g](int x, int y) { return before(g, x, y); });
  }
}

}  // namespace

std::vector<std::int32_t> level_order(std::size_t node_count,
                                      const std::vector<SpringSpec>& springs) {
  const Adjacency g = structural_adjacency(node_count, springs);
  // A node is placed once the final search of its component reached it; every
  // search, trial or final, has its own id (0: none yet).
  std::vector<std::int32_t> reached(node_count, 0);
  std::vector<char> placed(node_count, 0);
  std::vector<std::int32_t> order;
  order.reserve(node_count);
  std::vector<std::int32_t> by_degree(node_count);
  std::iota(by_degree.begin(), by_degree.end(), 0);
  std::stable_sort(by_degree.begin(), by_degree.end(),
                   [&g](int x, int y) { return g.degree(x) < g.degree(y); });
  int id = 0;
  for (const int start : by_degree) {
    if (placed[start]) continue;
    const int root = pseudo_peripheral(g, start, id, reached);
    const std::size_t from = order.size();
    breadth_first(g, root, ++id, reached, order);
    for (std::size_t k = from; k < order.size(); ++k)
      placed[order[k]] = 1;
  }
  return order;
}

ClothTopology renumbered(const ClothTopology& t, const std::vector<std::int32_t>& order) {
  const std::size_t n = order.size();
  std::vector<std::int32_t> node_of(n), sources(n);
  ClothTopology r;
  r.rest_positions.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    node_of[order[i]] = static_cast<std::int32_t>(i);
    sources[i] = t.numbering.source(order[i]);
    r.rest_positions.push_back(t.rest_positions[order[i]]);
  }
  r.triangles.reserve(t.triangles.size());
  for (const auto& tri : t.triangles)
    r.triangles.push_back({node_of[tri[0]], node_of[tri[1]], node_of[tri[2]]});
  r.springs.reserve(t.springs.size());
  for (const SpringSpec& s : t.springs) {
    const std::int32_t a = node_of[s.a], b = node_of[s.b];
    r.springs.push_back({std::min(a, b), std::max(a, b), s.family});
  }
  sort_into_stencil_runs(r.springs);
  r.rows = t.rows;
  r.cols = t.cols;
  r.numbering = NodeNumbering(std::move(sources));
  return r;
}

void order_nodes_for_runs(ClothTopology& t) {
  ClothTopology candidate = renumbered(t, level_order(t.rest_positions.size(), t.springs));
  if (springs_in_stencil_runs(candidate.springs) > springs_in_stencil_runs(t.springs))
    t = std::move(candidate);
}

}  // namespace neurocloth
