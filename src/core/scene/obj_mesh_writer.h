#pragma once
// A cloth's rest shape as a Wavefront OBJ: one vertex per node in node order
// (vertex k + 1 is node k) and one face per triangle. build_obj_mesh reads back
// the same triangles, so the same springs, and the same nodes to the reader's
// rounding: how the benchmarks and tests put a grid through the mesh path.
#include <string>

#include "core/network/cloth_topology.h"

namespace neurocloth {

// Throws std::runtime_error naming `path` when it cannot be written; written
// through a temporary file renamed into place, so never half a file.
void write_obj_mesh(const ClothTopology& topology, const std::string& path);

}  // namespace neurocloth
