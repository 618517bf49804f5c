#pragma once
// Where a collider is at a moment: the pose taking the frame its shape is
// written in to the world, and a deforming mesh's vertices. Pure functions of
// the declaration and the time, so the collider (colliders.cpp), the renderer
// and the exporter all place an obstacle the same way.
#include <vector>

#include "core/geometry/rigid_pose.h"
#include "core/modules/module_specs.h"

namespace neurocloth {

// The motion's rigid move at time t, turning about `pivot` (ColliderMotion):
// x -> R(t) (x - pivot) + pivot + translate(t). Identity when it does not move.
RigidPose motion_pose(const ColliderMotion& motion, const Vec3& pivot, double t);

// The pose of a collider's shape frame at time t: its fixed placement (a box's
// rotation about its centre) then its motion. A mesh's placement is in its
// vertices already (obstacle_mesh.h). Identity for colliders neither rotated
// nor moving.
RigidPose collider_pose(const ModuleSpec& collider, double t);
// Whether the collider's pose differs from identity at any time (rotated or moving).
bool collider_posed(const ModuleSpec& collider);
// Whether it changes in time (moves, or deforms).
bool collider_moves(const ModuleSpec& collider);
// A collider's motion; null for a module that is not a collider.
const ColliderMotion* collider_motion(const ModuleSpec& collider);

// A deforming mesh's vertices at time t (before the motion): the cache's frames
// interpolated linearly, held before the first and after the last. The
// undeformed surface's vertices when it does not deform.
void obstacle_vertices_at(const ObstacleMesh& mesh, double t, std::vector<Vec3>& out);

}  // namespace neurocloth
