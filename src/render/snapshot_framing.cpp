#include "render/snapshot_framing.h"

#include <cmath>
#include <type_traits>

#include "core/modules/collider_motion.h"

namespace neurocloth {
namespace {

constexpr double kMinHalfSize = 0.05;  // m

}  // namespace

void Bounds::add(const Vec3& p) {
  if (!p.allFinite()) return;
  lo = lo.cwiseMin(p);
  hi = hi.cwiseMax(p);
}

RigidPose snapshot_collider_pose(const FrameSnapshot& s, std::size_t i) {
  if (i < s.colliders.size()) return s.colliders[i].pose;
  return collider_pose(s.geometry->colliders[i], s.time);
}

Bounds snapshot_bounds(const FrameSnapshot& s) {
  Bounds b;
  for (std::size_t i = 0; i < s.position.size() / 3; ++i)
    b.add(s.node(i));
  if (!s.geometry) return b;
  for (std::size_t i = 0; i < s.geometry->colliders.size(); ++i) {
    const ModuleSpec& spec = s.geometry->colliders[i];
    if (std::holds_alternative<PlaneSpec>(spec)) continue;
    const RigidPose pose = snapshot_collider_pose(s, i);
    auto add_ball = [&](const Vec3& centre, double r) {
      b.add(pose.apply(centre) - Vec3::Constant(r));
      b.add(pose.apply(centre) + Vec3::Constant(r));
    };
    std::visit(
        [&](const auto& c) {
          using T = std::decay_t<decltype(c)>;
          if constexpr (std::is_same_v<T, BoxSpec>) {
            for (int k = 0; k < 8; ++k)
              b.add(pose.apply(c.center + Vec3((k & 1) ? 1 : -1, (k & 2) ? 1 : -1, (k & 4) ? 1 : -1)
                                              .cwiseProduct(c.half_extents)));
          } else if constexpr (std::is_same_v<T, SphereSpec>) {
            add_ball(c.center, c.radius);
          } else if constexpr (std::is_same_v<T, CapsuleSpec>) {
            add_ball(c.a, c.radius);
            add_ball(c.b, c.radius);
          } else if constexpr (std::is_same_v<T, CylinderSpec>) {
            // Its two end discs lie within these balls.
            const Vec3 half = 0.5 * c.height * c.axis.normalized();
            add_ball(c.center + half, c.radius);
            add_ball(c.center - half, c.radius);
          } else if constexpr (std::is_same_v<T, MeshSpec>) {
            if (!c.mesh) return;
            const std::vector<float>& deformed =
                i < s.colliders.size() ? s.colliders[i].vertices : std::vector<float>();
            if (!deformed.empty()) {
              for (std::size_t v = 0; v + 2 < deformed.size(); v += 3)
                b.add(pose.apply(Vec3(deformed[v], deformed[v + 1], deformed[v + 2])));
            } else {
              for (const Vec3& p : c.mesh->surface.vertices)
                b.add(pose.apply(p));
            }
          }
        },
        spec);
  }
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
