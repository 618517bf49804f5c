#include "core/modules/collider_motion.h"

#include <algorithm>
#include <type_traits>

namespace neurocloth {
namespace {

// The key interval holding t: keys a and a + 1 and how far along, s in [0, 1].
// Before the first key and after the last, one key held (a == b).
struct Between {
  std::size_t a, b;
  double s;
};
template <class Times>
Between between(const Times& time_of, std::size_t count, double t) {
  if (count == 0 || t <= time_of(0)) return {0, 0, 0.0};
  if (t >= time_of(count - 1)) return {count - 1, count - 1, 0.0};
  std::size_t lo = 0, hi = count - 1;  // time_of(lo) < t < time_of(hi)
  while (hi - lo > 1) {
    const std::size_t mid = (lo + hi) / 2;
    (time_of(mid) < t ? lo : hi) = mid;
  }
  return {lo, hi, (t - time_of(lo)) / (time_of(hi) - time_of(lo))};
}

}  // namespace

RigidPose motion_pose(const ColliderMotion& motion, const Vec3& pivot, double t) {
  if (!motion.moves()) return {};
  const auto& keys = motion.keys;
  const Between at = between([&](std::size_t k) { return keys[k].t; }, keys.size(), t);
  const MotionKey &a = keys[at.a], &b = keys[at.b];
  const Vec3 translate = (1 - at.s) * a.translate + at.s * b.translate;
  const Vec3 rotate = (1 - at.s) * a.rotate + at.s * b.rotate;
  RigidPose pose;
  pose.rotation = euler_xyz_degrees(rotate);
  pose.translation = pivot + translate - pose.rotation * pivot;
  return pose;
}

RigidPose collider_pose(const ModuleSpec& collider, double t) {
  return std::visit(
      [&](const auto& s) -> RigidPose {
        using T = std::decay_t<decltype(s)>;
        if constexpr (std::is_same_v<T, PlaneSpec>) {
          return motion_pose(s.motion, s.point, t);
        } else if constexpr (std::is_same_v<T, BoxSpec>) {
          RigidPose fixed;
          if (s.rotate != Vec3::Zero()) {
            fixed.rotation = euler_xyz_degrees(s.rotate);
            fixed.translation = s.center - fixed.rotation * s.center;
          }
          return s.motion.moves() ? motion_pose(s.motion, s.center, t).after(fixed) : fixed;
        } else if constexpr (std::is_same_v<T, SphereSpec>) {
          return motion_pose(s.motion, s.center, t);
        } else if constexpr (std::is_same_v<T, CapsuleSpec>) {
          return motion_pose(s.motion, 0.5 * (s.a + s.b), t);
        } else if constexpr (std::is_same_v<T, CylinderSpec>) {
          return motion_pose(s.motion, s.center, t);
        } else if constexpr (std::is_same_v<T, MeshSpec>) {
          return motion_pose(s.motion, s.translate, t);
        } else {
          return {};
        }
      },
      collider);
}

bool collider_posed(const ModuleSpec& collider) {
  const auto* box = std::get_if<BoxSpec>(&collider);
  const ColliderMotion* motion = collider_motion(collider);
  return (box && box->rotate != Vec3::Zero()) || (motion && motion->moves());
}

bool collider_moves(const ModuleSpec& collider) {
  const auto* mesh = std::get_if<MeshSpec>(&collider);
  const ColliderMotion* motion = collider_motion(collider);
  return (mesh && mesh->mesh && mesh->mesh->deforms()) || (motion && motion->moves());
}

const ColliderMotion* collider_motion(const ModuleSpec& collider) {
  return std::visit(
      [](const auto& s) -> const ColliderMotion* {
        using T = std::decay_t<decltype(s)>;
        if constexpr (std::is_same_v<T, PlaneSpec> || std::is_same_v<T, BoxSpec> ||
                      std::is_same_v<T, SphereSpec> || std::is_same_v<T, CapsuleSpec> ||
                      std::is_same_v<T, CylinderSpec> || std::is_same_v<T, MeshSpec>)
          return &s.motion;
        else
          return nullptr;
      },
      collider);
}

void obstacle_vertices_at(const ObstacleMesh& mesh, double t, std::vector<Vec3>& out) {
  if (!mesh.deforms()) {
    out = mesh.surface.vertices;
    return;
  }
  const Between at =
      between([&](std::size_t k) { return mesh.frame_times[k]; }, mesh.frame_times.size(), t);
  const std::vector<Vec3>&a = mesh.frames[at.a], &b = mesh.frames[at.b];
  out.resize(a.size());
  for (std::size_t i = 0; i < a.size(); ++i)
    out[i] = (1 - at.s) * a[i] + at.s * b[i];
}

}  // namespace neurocloth
