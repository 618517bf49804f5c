#pragma once
// What a snapshot occupies in space, and the camera that shows all of it: the
// default view of the headless snapshots (and of the window's "frame" action).
#include "core/scene/frame_snapshot.h"
#include "render/orbit_camera.h"

namespace neurocloth {

struct Bounds {
  Vec3 lo = Vec3::Constant(1e300);
  Vec3 hi = Vec3::Constant(-1e300);
  bool empty() const { return !(lo.x() <= hi.x()); }
  void add(const Vec3& p);
};

// The cloth's nodes and the finite colliders (boxes, spheres, capsules, mesh
// obstacles) where the snapshot has them (rotated, moved, deformed); planes
// are unbounded and left out. Non-finite positions are skipped.
Bounds snapshot_bounds(const FrameSnapshot& snapshot);

// Collider `i` of the snapshot's geometry: its pose at the snapshot's time,
// from the snapshot's placements (computed from the declaration when the
// snapshot has none).
RigidPose snapshot_collider_pose(const FrameSnapshot& snapshot, std::size_t i);

// The default camera (yaw and pitch) moved to frame snapshot_bounds for an
// image of the given aspect (width / height); the default camera when empty.
OrbitCamera framing_camera(const FrameSnapshot& snapshot, double aspect);

}  // namespace neurocloth
