#pragma once
// Which mass point a click means: the nearest triangle of the cloth hit by the
// cursor ray, then the nearest of its three nodes to the hit point. A ray that
// misses the cloth picks the node nearest the ray within `tolerance`. Pure
// math on a snapshot: testable without a window.
#include "core/scene/frame_snapshot.h"
#include "render/orbit_camera.h"

namespace neurocloth {

struct Pick {
  int node = -1;               // -1: nothing picked
  Vec3 point = Vec3(0, 0, 0);  // where the ray met the cloth (or the node)
  double ray_t = 0;            // distance along the ray
};

Pick pick_node(const Ray& ray, const FrameSnapshot& snapshot, double tolerance);

// The point on the plane through `anchor` facing the camera that the ray hits:
// where a dragged node is pulled towards.
Vec3 drag_point(const Ray& ray, const Vec3& anchor, const OrbitCamera& camera);

}  // namespace neurocloth
