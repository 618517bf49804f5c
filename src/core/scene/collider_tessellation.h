#pragma once
// Triangle meshes of the colliders a scene declares, in each collider's shape
// frame: the spec's own coordinates, which collider_pose (collider_motion.h)
// takes to the world at a moment. A plane is a large square around the scene,
// boxes (axis-aligned as declared: a box's rotation is its pose's), spheres,
// capsules and cylinders are tessellated, a mesh obstacle is its own triangles. What the
// renderer draws and `simulate --export-pc2` writes, so both show one shape.
// Plain C++, no OpenGL.
#include <cstdint>
#include <vector>

#include "core/modules/module_specs.h"

namespace neurocloth {

// Where a mesh obstacle's shading keeps an edge sharp: its two faces' normals
// differ by more than this.
inline constexpr double kCreaseDegrees = 40.0;

struct SurfaceMesh {
  std::vector<float> position;       // x, y, z per vertex, m
  std::vector<float> normal;         // x, y, z per vertex, unit, pointing out of the solid
  std::vector<std::uint32_t> index;  // three per triangle, counter-clockwise seen from outside
  // A mesh obstacle's vertices: the obstacle vertex each one shows. A vertex on
  // a crease is split, one per side, so each side keeps its faces' normal; a
  // deforming obstacle's positions are copied through this. Empty when the
  // mesh holds no obstacle.
  std::vector<std::int32_t> source;

  std::uint32_t add_vertex(const Vec3& p, const Vec3& n);
  void add_triangle(std::uint32_t a, std::uint32_t b, std::uint32_t c);
  std::size_t vertex_count() const { return position.size() / 3; }
  Vec3 vertex(std::size_t i) const {
    return {position[3 * i], position[3 * i + 1], position[3 * i + 2]};
  }
};

void append_box(const BoxSpec& box, SurfaceMesh& mesh);
void append_sphere(const SphereSpec& sphere, SurfaceMesh& mesh);
void append_capsule(const CapsuleSpec& capsule, SurfaceMesh& mesh);
// Its side smooth (normals across the axis), its two ends flat discs.
void append_cylinder(const CylinderSpec& cylinder, SurfaceMesh& mesh);
// A square of half side `half_size` on the plane, centred where `centre` projects onto it.
void append_plane(const PlaneSpec& plane, const Vec3& centre, double half_size, SurfaceMesh& mesh);
// A mesh obstacle's triangles at its surface's vertices, normals smooth across
// edges flatter than `crease_degrees` and split at sharper ones (a box of 12
// triangles shows flat faces, a sphere a smooth one). Degenerate triangles are
// kept (they draw nothing). Appends to `mesh`'s `source` as well.
void append_obstacle(const ObstacleMesh& obstacle, SurfaceMesh& mesh,
                     double crease_degrees = kCreaseDegrees);

// Any collider's mesh in its shape frame (a plane's square as above); a module
// that is not a collider appends nothing.
void append_collider(const ModuleSpec& collider, const Vec3& centre, double plane_half_size,
                     SurfaceMesh& mesh);

// The normals again from the positions (a deforming obstacle's, after they
// moved): each vertex's the area-weighted sum of its triangles' normals, unit.
// A crease's split vertices keep only their side's triangles, so creases stay.
void recompute_normals(SurfaceMesh& mesh);

}  // namespace neurocloth
