#pragma once
// What a cloth builder produces: rest geometry and the spring graph, before any
// material is applied. Builders emit springs in "stencil order" where they can
// (consecutive springs whose two ends both advance by one node), which the spring
// layer turns into runs that vectorise.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/base/vec3.h"
#include "core/network/node_numbering.h"

namespace neurocloth {

enum class SpringFamily : std::uint8_t { structural = 0, shear = 1, bend = 2 };
inline constexpr int kSpringFamilyCount = 3;
const char* to_string(SpringFamily f);

struct SpringSpec {
  std::int32_t a;  // n_i1 in the paper
  std::int32_t b;  // n_i2
  SpringFamily family;
};

struct ClothTopology {
  std::vector<Vec3> rest_positions;
  std::vector<SpringSpec> springs;
  std::vector<std::array<std::int32_t, 3>> triangles;  // for rendering and wind
  int rows = 0;                                        // grid shape; 0 for meshes
  int cols = 0;
  // Which file vertex each node is, when a mesh's nodes were renumbered.
  NodeNumbering numbering;
};

// Which spring families a builder creates.
struct SpringFamilies {
  bool structural = true;
  bool shear = true;
  bool bend = true;
};

// The cloth area each node stands for: a third of every triangle it belongs to
// (lumped). 0 for a node in no triangle (e.g. a one-column chain).
std::vector<double> lumped_node_areas(const ClothTopology& topology);

}  // namespace neurocloth
