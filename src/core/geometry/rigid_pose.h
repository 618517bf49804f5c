#pragma once
// A rigid placement: x_world = rotation * x_local + translation. What places an
// oriented box or a mesh obstacle, and what an obstacle's keyframed motion
// gives at each moment (core/modules/collider_motion.h).
#include <cmath>

#include "core/base/vec3.h"

namespace neurocloth {

struct RigidPose {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Vec3 translation = Vec3::Zero();

  Vec3 apply(const Vec3& x) const { return rotation * x + translation; }
  Vec3 apply_inverse(const Vec3& x) const { return rotation.transpose() * (x - translation); }
  // This pose after `inner`: x -> this(inner(x)).
  RigidPose after(const RigidPose& inner) const {
    return {rotation * inner.rotation, rotation * inner.translation + translation};
  }
  bool identity() const {
    return rotation == Eigen::Matrix3d::Identity() && translation == Vec3::Zero();
  }
};

// The rotation of Euler angles in degrees, applied X first, then Y, then Z
// (Blender's default "XYZ" order): R = Rz * Ry * Rx.
inline Eigen::Matrix3d euler_xyz_degrees(const Vec3& degrees) {
  const Vec3 r = degrees * (kPi / 180.0);
  return (Eigen::AngleAxisd(r.z(), Vec3::UnitZ()) * Eigen::AngleAxisd(r.y(), Vec3::UnitY()) *
          Eigen::AngleAxisd(r.x(), Vec3::UnitX()))
      .toRotationMatrix();
}

}  // namespace neurocloth
