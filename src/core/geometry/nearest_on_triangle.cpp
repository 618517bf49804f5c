#include "core/geometry/nearest_on_triangle.h"

#include <algorithm>

namespace neurocloth {

namespace {

// The nearest point of segment (u, v) to y: its weight on v.
double along_segment(const Vec3& y, const Vec3& u, const Vec3& v) {
  const Vec3 e = v - u;
  const double len2 = e.squaredNorm();
  return len2 > 0 ? std::clamp((y - u).dot(e) / len2, 0.0, 1.0) : 0.0;
}

}  // namespace

std::array<double, 3> nearest_on_triangle(const Vec3& y, const Vec3& a, const Vec3& b,
                                          const Vec3& c) {
  // Voronoi regions of the corners, then the edges, then the face (Ericson,
  // Real-Time Collision Detection, 5.1.5), in barycentric weights: the
  // nearest point lies in exactly one.
  const Vec3 ab = b - a, ac = c - a, ay = y - a;
  const double d1 = ab.dot(ay), d2 = ac.dot(ay);
  if (d1 <= 0 && d2 <= 0) return {1, 0, 0};
  const Vec3 by = y - b;
  const double d3 = ab.dot(by), d4 = ac.dot(by);
  if (d3 >= 0 && d4 <= d3) return {0, 1, 0};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double v = d1 / (d1 - d3);
    return {1 - v, v, 0};
  }
  const Vec3 cy = y - c;
  const double d5 = ab.dot(cy), d6 = ac.dot(cy);
  if (d6 >= 0 && d5 <= d6) return {0, 0, 1};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double w = d2 / (d2 - d6);
    return {1 - w, 0, w};
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {0, 1 - w, w};
  }
  const double sum = va + vb + vc;
  if (!(sum > 0)) {
    // Degenerate: no corner or edge region claimed y, and the triangle has
    // no face. Its nearest point is on one of its edges.
    const double tab = along_segment(y, a, b), tbc = along_segment(y, b, c),
                 tca = along_segment(y, c, a);
    const double dab = (a + tab * ab - y).squaredNorm();
    const double dbc = (b + tbc * (c - b) - y).squaredNorm();
    const double dca = (c + tca * (a - c) - y).squaredNorm();
    if (dab <= dbc && dab <= dca) return {1 - tab, tab, 0};
    if (dbc <= dca) return {0, 1 - tbc, tbc};
    return {tca, 0, 1 - tca};
  }
  const double v = vb / sum, w = vc / sum;
  return {1 - v - w, v, w};
}

double point_triangle_distance(const Vec3& y, const Vec3& a, const Vec3& b, const Vec3& c) {
  const std::array<double, 3> w = nearest_on_triangle(y, a, b, c);
  return (w[0] * a + w[1] * b + w[2] * c - y).norm();
}

}  // namespace neurocloth
