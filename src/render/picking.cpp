#include "render/picking.h"

#include <cmath>
#include <limits>

namespace neurocloth {
namespace {

// Möller–Trumbore: the distance along the ray to triangle abc, either side,
// or a negative number when the ray misses it.
double ray_triangle(const Ray& ray, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 e1 = b - a, e2 = c - a;
  const Vec3 p = ray.direction.cross(e2);
  const double det = e1.dot(p);
  // A triangle seen exactly edge-on (or degenerate) cannot be hit.
  if (std::abs(det) < 1e-14 * e1.squaredNorm() * e2.norm() + 1e-300) return -1;
  const double inv = 1.0 / det;
  const Vec3 s = ray.origin - a;
  const double u = s.dot(p) * inv;
  if (u < 0 || u > 1) return -1;
  const Vec3 q = s.cross(e1);
  const double v = ray.direction.dot(q) * inv;
  if (v < 0 || u + v > 1) return -1;
  return e2.dot(q) * inv;
}

}  // namespace

Pick pick_node(const Ray& ray, const FrameSnapshot& snapshot, double tolerance) {
  Pick pick;
  const std::size_t n = snapshot.position.size() / 3;
  // The nearest triangle in front of the eye, then its corner nearest the hit.
  if (snapshot.geometry) {
    double best = std::numeric_limits<double>::infinity();
    for (const auto& t : snapshot.geometry->triangles) {
      if (std::size_t(t[0]) >= n || std::size_t(t[1]) >= n || std::size_t(t[2]) >= n) continue;
      const double d =
          ray_triangle(ray, snapshot.node(t[0]), snapshot.node(t[1]), snapshot.node(t[2]));
      if (d > 0 && d < best) {
        best = d;
        const Vec3 hit = ray.origin + d * ray.direction;
        int nearest = t[0];
        for (int k = 1; k < 3; ++k)
          if ((snapshot.node(t[k]) - hit).squaredNorm() <
              (snapshot.node(nearest) - hit).squaredNorm())
            nearest = t[k];
        pick = {nearest, hit, d};
      }
    }
    if (pick.node >= 0) return pick;
  }
  // A miss (or a cloth without triangles, such as a chain): the node nearest
  // the ray, if within tolerance; of equally near ones, the closer to the eye.
  double best_distance = tolerance, best_t = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 p = snapshot.node(i);
    const double t = (p - ray.origin).dot(ray.direction);
    if (t <= 0) continue;
    const double off = (p - ray.origin - t * ray.direction).norm();
    if (off < best_distance || (off == best_distance && t < best_t && pick.node >= 0)) {
      best_distance = off;
      best_t = t;
      pick = {int(i), p, t};
    }
  }
  return pick;
}

Vec3 drag_point(const Ray& ray, const Vec3& anchor, const OrbitCamera& camera) {
  const Vec3 normal = camera.forward();
  const double along = ray.direction.dot(normal);
  // A ray parallel to the plane (impossible for a ray through the image) or
  // meeting it behind the eye leaves the point where it is.
  if (std::abs(along) < 1e-12) return anchor;
  const double t = (anchor - ray.origin).dot(normal) / along;
  if (!(t > 0)) return anchor;
  return ray.origin + t * ray.direction;
}

}  // namespace neurocloth
