#pragma once
// A rows x cols sheet of nodes; node (row, col) has index row * cols + col.
#include "core/network/cloth_topology.h"

namespace neurocloth {

struct GridSpec {
  int rows = 2;
  int cols = 2;
  double spacing = 0.05;
  Vec3 origin = Vec3::Zero();
  Vec3 row_direction = Vec3::UnitZ();  // moving to the next row moves along this
  Vec3 col_direction = Vec3::UnitX();  // moving to the next column moves along this
  SpringFamilies families;
};

// Throws std::invalid_argument on rows/cols < 1, spacing <= 0 or zero directions.
ClothTopology build_grid(const GridSpec& spec);

}  // namespace neurocloth
