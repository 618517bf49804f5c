#pragma once
// The nearest point of a triangle to a point: what a point cloud's Chamfer
// loss (learn/fit/chamfer.h) and the distance between two cloths' surfaces
// (tradeoff/surface_distance.h) both measure against.
#include <array>

#include "core/base/vec3.h"

namespace neurocloth {

// The nearest point of triangle (a, b, c) to y, as barycentric weights (each
// in [0, 1], summing to 1). A degenerate triangle (zero area) gives the
// nearest point of its nearest edge.
std::array<double, 3> nearest_on_triangle(const Vec3& y, const Vec3& a, const Vec3& b,
                                          const Vec3& c);

// The distance from y to that point.
double point_triangle_distance(const Vec3& y, const Vec3& a, const Vec3& b, const Vec3& c);

}  // namespace neurocloth
