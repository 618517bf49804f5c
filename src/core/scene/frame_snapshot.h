#pragma once
// What the renderer draws: a plain copy of the cloth at one moment. The
// simulation thread fills one and publishes it; the render thread reads it
// without any lock and never touches the live simulation. What never changes
// during a run (triangles, springs, the colliders' shapes) is shared between
// snapshots, not copied each frame; where each collider is at the moment (a
// moving obstacle's pose, a deforming one's vertices) is copied.
#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/base/vec3.h"
#include "core/geometry/rigid_pose.h"
#include "core/modules/module_specs.h"
#include "core/network/cloth_topology.h"

namespace neurocloth {

class Scene;
class Simulation;

inline constexpr int kCoarseGridFrom = 160;

struct SceneGeometry {
  std::string scene_name;
  std::vector<std::array<std::int32_t, 3>> triangles;
  // A grid cloth of more than kCoarseGridFrom rows or columns on every other
  // row and column (the last always kept): what a window drawing on the CPU
  // draws instead of `triangles` when they would cost its frame rate
  // (RenderOptions::max_cloth_triangles). Empty for meshes and smaller grids.
  std::vector<std::array<std::int32_t, 3>> coarse_triangles;
  std::vector<std::int32_t> spring_a, spring_b;
  std::vector<SpringFamily> spring_family;
  std::vector<float> rest_length;     // m, per spring (for the strain colour map)
  std::vector<ModuleSpec> colliders;  // colliders only (is_collider)
  std::size_t node_count = 0;
  NodeNumbering numbering;  // the file's vertex of each node: what the user is shown
};

struct FrameSnapshot {
  std::shared_ptr<const SceneGeometry> geometry;
  std::vector<float> position;       // x, y, z per node, m
  std::vector<std::uint8_t> pinned;  // 1 for a pinned node
  // Forces the user applies (the drag), for drawing as lines.
  struct AppliedForce {
    std::int32_t node;
    Vec3 force;   // N
    Vec3 anchor;  // the point it pulls towards (the cursor on its drag plane)
  };
  std::vector<AppliedForce> forces;
  // Each of geometry->colliders where it is at `time` (collider_motion.h).
  struct ColliderPlacement {
    RigidPose pose;  // its shape frame to the world (identity for a collider neither
                     // rotated nor moving)
    // A deforming mesh's vertices at `time` in its shape frame (before `pose`),
    // x, y, z per vertex in the OBJ's order; empty for every other collider.
    std::vector<float> vertices;
  };
  std::vector<ColliderPlacement> colliders;
  double time = 0;  // simulated s
  long serial = 0;  // increases with every published snapshot

  Vec3 node(std::size_t i) const {
    return {position[3 * i], position[3 * i + 1], position[3 * i + 2]};
  }
};

std::shared_ptr<const SceneGeometry> make_geometry(const Scene& scene);
// Copies the simulation's positions and pins into `out`, and places
// out.geometry's colliders at the simulation's time (set the geometry first;
// none without one). No allocation once sized; a collider that does not move
// costs nothing.
void capture(const Simulation& sim, FrameSnapshot& out);
// The colliders' placements alone: `geometry`'s colliders at time t.
void place_colliders(const SceneGeometry* geometry, double t,
                     std::vector<FrameSnapshot::ColliderPlacement>& out);

}  // namespace neurocloth
