#pragma once
// Puts a builder's springs in stencil order. The spring layer turns
// consecutive springs whose two ends both advance by one node into runs that
// vectorise (spring_layer.h); a grid builder emits that order by construction,
// but a mesh names its edges in whatever order its faces come.
#include <cstddef>
#include <vector>

#include "core/network/cloth_topology.h"

namespace neurocloth {

// Reorders `springs` without changing the set: every stretch of springs of one
// family with the same offset b - a and consecutive a (a grid row's worth in a
// mesh written row by row) stands together, longer stretches first by family,
// offset and a; springs in no long stretch follow in (a, b) order, which keeps
// their node reads near each other. Deterministic for a given set.
void sort_into_stencil_runs(std::vector<SpringSpec>& springs);

// How many of `springs`, as sort_into_stencil_runs left them, stand in a
// stretch long enough to be kept together: how well a node order suits runs.
std::size_t springs_in_stencil_runs(const std::vector<SpringSpec>& springs);

}  // namespace neurocloth
