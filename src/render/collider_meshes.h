#pragma once
// Triangle meshes of the colliders a scene declares (plain C++, no OpenGL):
// a plane as a large square around the scene, boxes, spheres and capsules.
#include <cstdint>
#include <vector>

#include "core/modules/module_specs.h"

namespace neurocloth {

struct SurfaceMesh {
  std::vector<float> position;       // x, y, z per vertex, m
  std::vector<float> normal;         // x, y, z per vertex, unit, pointing out of the solid
  std::vector<std::uint32_t> index;  // three per triangle, counter-clockwise seen from outside

  std::uint32_t add_vertex(const Vec3& p, const Vec3& n);
  void add_triangle(std::uint32_t a, std::uint32_t b, std::uint32_t c);
  std::size_t vertex_count() const { return position.size() / 3; }
};

void append_box(const BoxSpec& box, SurfaceMesh& mesh);
void append_sphere(const SphereSpec& sphere, SurfaceMesh& mesh);
void append_capsule(const CapsuleSpec& capsule, SurfaceMesh& mesh);
// A square of half side `half_size` on the plane, centred where `centre` projects onto it.
void append_plane(const PlaneSpec& plane, const Vec3& centre, double half_size, SurfaceMesh& mesh);

// Every plane, box, sphere and capsule in `colliders` (other modules are ignored).
SurfaceMesh collider_mesh(const std::vector<ModuleSpec>& colliders, const Vec3& centre,
                          double plane_half_size);

}  // namespace neurocloth
