#include "render/snapshot_framing.h"

#include <cmath>
#include <type_traits>

namespace neurocloth {
namespace {

constexpr double kMinHalfSize = 0.05;  // m

}  // namespace

void Bounds::add(const Vec3& p) {
  if (!p.allFinite()) return;
  lo = lo.cwiseMin(p);
  hi = hi.cwiseMax(p);
}

Bounds snapshot_bounds(const FrameSnapshot& s) {
  Bounds b;
  for (std::size_t i = 0; i < s.position.size() / 3; ++i)
    b.add(s.node(i));
  if (!s.geometry) return b;
  for (const ModuleSpec& spec : s.geometry->colliders)
    std::visit(
        [&](const auto& c) {
          using T = std::decay_t<decltype(c)>;
          if constexpr (std::is_same_v<T, BoxSpec>) {
            b.add(c.center - c.half_extents);
            b.add(c.center + c.half_extents);
          } else if constexpr (std::is_same_v<T, SphereSpec>) {
            b.add(c.center - Vec3::Constant(c.radius));
            b.add(c.center + Vec3::Constant(c.radius));
          } else if constexpr (std::is_same_v<T, CapsuleSpec>) {
            for (const Vec3& end : {c.a, c.b}) {
              b.add(end - Vec3::Constant(c.radius));
              b.add(end + Vec3::Constant(c.radius));
            }
          }
        },
        spec);
  return b;
}

OrbitCamera framing_camera(const FrameSnapshot& snapshot, double aspect) {
  OrbitCamera camera;
  const Bounds b = snapshot_bounds(snapshot);
  if (b.empty()) return camera;
  // A single node or a short chain still gets a view of some size around it.
  const Vec3 centre = 0.5 * (b.lo + b.hi);
  const Vec3 half = (0.5 * (b.hi - b.lo)).cwiseMax(Vec3::Constant(kMinHalfSize));
  camera.frame(centre - half, centre + half, aspect);
  return camera;
}

}  // namespace neurocloth
