#pragma once
// How far apart two cloths' surfaces are: from every node of one to the nearest
// point of the other's triangles, both ways. Unlike the distance between the
// same node in two runs, it does not see a fold that slid along itself, only a
// surface that is somewhere else (docs/tradeoff.md, "Errors people see").
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/base/vec3.h"

namespace neurocloth {

using Triangles = std::vector<std::array<std::int32_t, 3>>;

// Node i of positions laid out x0 y0 z0 x1 ...
inline Vec3 node_at(const double* x, std::size_t i) {
  return Vec3(x[3 * i], x[3 * i + 1], x[3 * i + 2]);
}

struct SurfaceDistance {
  double mean = 0;  // m: over the nodes of both cloths
  double max = 0;   // m
};

// `a` and `b` are x0 y0 z0 x1 ... of `nodes` nodes; `triangles` index both.
// Without triangles (a chain of nodes) the surface is its nodes. Non-finite
// coordinates give NaN (nothing to measure).
SurfaceDistance surface_distance(const double* a, const double* b, std::size_t nodes,
                                 const Triangles& triangles);

}  // namespace neurocloth
