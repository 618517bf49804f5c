#pragma once
// The springs of a cloth made of triangles (an OBJ's, a disc's): what a
// triangle mesh says about which nodes pull on which, known once for every
// builder that makes one.
#include "core/network/cloth_topology.h"

namespace neurocloth {

// Adds to `t` (its rest positions and triangles set, no springs yet) a
// structural spring per unique edge and, with `bend`, a bend spring across
// every edge two triangles share (between the two vertices opposite it; a
// boundary or non-manifold edge has none). Then puts the springs in stencil
// order and renumbers the nodes where that makes more of them stand in runs
// (stencil_order.h, mesh_node_order.h), which sets t.numbering.
void add_triangle_springs(ClothTopology& t, bool bend);

}  // namespace neurocloth
