// A disc as a hexagonal lattice bent round: ring k is the hexagon of side k
// of a triangular lattice, its 6k nodes moved onto the circle of radius
// R k / rings at equal angles. Between rings k - 1 and k each of the six
// sides holds k triangles pointing out and k - 1 pointing in, as in the flat
// lattice, so every triangle stays close to equilateral (the first ring's
// exactly) and the outline is the regular 6-rings-gon inscribed in the circle.
#include "core/scene/disc_builder.h"

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "core/base/portable_trig.h"
#include "core/scene/triangle_springs.h"

namespace neurocloth {
namespace {

// The first node of ring k (the centre is node 0, ring 0).
std::int32_t ring_start(int k) {
  return k == 0 ? 0 : 1 + 3 * (k - 1) * k;
}

// Node j (taken round, counter-clockwise from the first) of ring k.
std::int32_t ring_node(int k, int j) {
  if (k == 0) return 0;
  const int n = 6 * k;
  return ring_start(k) + ((j % n) + n) % n;
}

}  // namespace

ClothTopology build_disc(const DiscSpec& spec) {
  if (spec.rings < 1 || spec.rings > kMaxDiscRings)
    throw std::invalid_argument("a disc's rings must be in [1, " + std::to_string(kMaxDiscRings) +
                                "]");
  if (!(spec.radius > 0)) throw std::invalid_argument("a disc's radius must be > 0");
  if (!(spec.normal.norm() > 0)) throw std::invalid_argument("a disc's normal must not be zero");

  // u x v = normal: the triangles below wind counter-clockwise in (u, v), so
  // (b - a) x (c - a) points along the normal.
  const Vec3 n = spec.normal.normalized();
  const Vec3 helper = std::abs(n.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  const Vec3 u = helper.cross(n).normalized();
  const Vec3 v = n.cross(u);

  ClothTopology t;
  const int rings = spec.rings;
  t.rest_positions.reserve(static_cast<std::size_t>(ring_start(rings + 1)));
  t.rest_positions.push_back(spec.center);
  for (int k = 1; k <= rings; ++k) {
    const double r = spec.radius * k / rings;
    for (int j = 0; j < 6 * k; ++j) {
      // portable_*: the same rest positions, so the same run, on every CPU.
      const double angle = 2 * kPi * j / (6 * k);
      t.rest_positions.push_back(spec.center +
                                 r * (portable_cos(angle) * u + portable_sin(angle) * v));
    }
  }

  // Side s of ring k runs from outer node k s to k (s + 1), against inner
  // nodes (k - 1) s to (k - 1)(s + 1): the first ring's inner "side" is the centre.
  t.triangles.reserve(6 * static_cast<std::size_t>(rings) * rings);
  for (int k = 1; k <= rings; ++k)
    for (int s = 0; s < 6; ++s)
      for (int j = 0; j < k; ++j) {
        const std::int32_t inner = ring_node(k - 1, (k - 1) * s + j);
        t.triangles.push_back({inner, ring_node(k, k * s + j), ring_node(k, k * s + j + 1)});
        if (j + 1 < k)
          t.triangles.push_back(
              {inner, ring_node(k, k * s + j + 1), ring_node(k - 1, (k - 1) * s + j + 1)});
      }

  add_triangle_springs(t, spec.bend);
  return t;
}

}  // namespace neurocloth
