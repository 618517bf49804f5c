#pragma once
// A square grid and the same grid with its vertices in a shuffled order: what
// the tests of mesh renumbering write as OBJ files (a file that scatters
// neighbours is renumbered at load, and users must never see it).
#include <algorithm>
#include <cstdint>
#include <numeric>
#include <random>
#include <vector>

#include "core/scene/grid_builder.h"
#include "core/scene/mesh_node_order.h"

namespace neurocloth::test {

struct ShuffledGrid {
  ClothTopology grid;      // rows x rows nodes, row by row
  ClothTopology shuffled;  // shuffled vertex k is grid node order[k]
  std::vector<std::int32_t> order;
  std::vector<int> vertex_of;  // grid node -> its shuffled vertex
};

inline ShuffledGrid shuffled_grid(int rows, double spacing, unsigned seed = 12) {
  ShuffledGrid s;
  GridSpec g;
  g.rows = g.cols = rows;
  g.spacing = spacing;
  s.grid = build_grid(g);
  const int n = static_cast<int>(s.grid.rest_positions.size());
  s.order.resize(static_cast<std::size_t>(n));
  std::iota(s.order.begin(), s.order.end(), 0);
  std::shuffle(s.order.begin(), s.order.end(), std::mt19937(seed));
  s.vertex_of.resize(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k)
    s.vertex_of[static_cast<std::size_t>(s.order[static_cast<std::size_t>(k)])] = k;
  s.shuffled = renumbered(s.grid, s.order);
  return s;
}

}  // namespace neurocloth::test
