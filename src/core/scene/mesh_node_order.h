#pragma once
// A node order for a mesh whose file scatters neighbours. The spring layer
// vectorises runs of springs whose two ends both advance by one node
// (spring_layer.h); a mesh's springs can only form such runs if its nodes are
// numbered along the cloth, as a grid's rows number them.
#include <cstdint>
#include <vector>

#include "core/network/cloth_topology.h"

namespace neurocloth {

// The level structure of a breadth-first search over the structural springs,
// each component from a pseudo-peripheral vertex (George and Liu's search from
// a vertex of least degree), children taken in order of degree: Cuthill-McKee
// without the reversal, which changes nothing for runs. On a grid-like mesh the
// levels are straight lines across the cloth, each ordered along itself, so the
// springs between two levels form a run a level long. order[i] is the node
// that becomes node i.
std::vector<std::int32_t> level_order(std::size_t node_count,
                                      const std::vector<SpringSpec>& springs);

// `t` with node i being node order[i] of `t`: positions, triangles (winding
// kept), springs (a < b, put in stencil order) and the numbering all follow.
ClothTopology renumbered(const ClothTopology& t, const std::vector<std::int32_t>& order);

// Renumbers `t` by level_order when more of its springs then stand in stencil
// runs than in its present order; keeps it otherwise (a mesh written row by row
// already has its runs, and its nodes stay in the file's order). Its springs
// must be in stencil order.
void order_nodes_for_runs(ClothTopology& t);

}  // namespace neurocloth
