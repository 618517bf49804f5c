#pragma once
// The nearest points of two segments: where a cloth's edge comes closest to an
// obstacle's edge (mesh_collider.cpp).
#include <algorithm>

#include "core/base/vec3.h"

namespace neurocloth {

// Parameters s (on p0-p1) and u (on q0-q1), each in [0, 1], of the nearest
// points p0 + s (p1 - p0) and q0 + u (q1 - q0). Parallel segments: the pair
// with s nearest 0 that is as near as any. A segment of zero length is its point.
inline void nearest_of_segments(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1,
                                double& s, double& u) {
  const Vec3 d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  if (!(a > 0.0) && !(e > 0.0)) {
    s = u = 0.0;
    return;
  }
  if (!(a > 0.0)) {
    s = 0.0;
    u = std::clamp(f / e, 0.0, 1.0);
    return;
  }
  const double c = d1.dot(r);
  if (!(e > 0.0)) {
    u = 0.0;
    s = std::clamp(-c / a, 0.0, 1.0);
    return;
  }
  const double b = d1.dot(d2), denom = a * e - b * b;  // >= 0
  s = denom > 1e-14 * a * e ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
  u = (b * s + f) / e;
  if (u < 0.0) {
    u = 0.0;
    s = std::clamp(-c / a, 0.0, 1.0);
  } else if (u > 1.0) {
    u = 1.0;
    s = std::clamp((b - c) / a, 0.0, 1.0);
  }
}

}  // namespace neurocloth
