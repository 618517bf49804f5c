#include "render/collider_meshes.h"

#include <cmath>
#include <type_traits>

#include "core/base/vec3.h"

namespace neurocloth {
namespace {

constexpr int kSlices = 48;  // around a sphere or capsule
constexpr int kStacks = 24;  // pole to pole

// Two unit vectors completing `axis` (unit) to a right-handed frame.
void orthonormal_basis(const Vec3& axis, Vec3& u, Vec3& v) {
  const Vec3 helper = std::abs(axis.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  u = axis.cross(helper).normalized();
  v = axis.cross(u);
}

// A grid of (stacks + 1) x (slices + 1) vertices joined into quads; vertex
// (i, j) comes from point(i, j) and normal(i, j). Used for spheres and capsules.
template <class Point, class Normal>
void append_lattice(int stacks, int slices, Point point, Normal normal, SurfaceMesh& mesh) {
  const std::uint32_t first = std::uint32_t(mesh.vertex_count());
  for (int i = 0; i <= stacks; ++i)
    for (int j = 0; j <= slices; ++j)
      mesh.add_vertex(point(i, j), normal(i, j));
  const std::uint32_t row = std::uint32_t(slices + 1);
  for (int i = 0; i < stacks; ++i)
    for (int j = 0; j < slices; ++j) {
      const std::uint32_t a = first + std::uint32_t(i) * row + std::uint32_t(j);
      const std::uint32_t b = a + row;  // the next stack, further from the top pole
      mesh.add_triangle(a, b, a + 1);
      mesh.add_triangle(a + 1, b, b + 1);
    }
}

}  // namespace

std::uint32_t SurfaceMesh::add_vertex(const Vec3& p, const Vec3& n) {
  for (int d = 0; d < 3; ++d) {
    position.push_back(float(p[d]));
    normal.push_back(float(n[d]));
  }
  return std::uint32_t(vertex_count() - 1);
}

void SurfaceMesh::add_triangle(std::uint32_t a, std::uint32_t b, std::uint32_t c) {
  index.insert(index.end(), {a, b, c});
}

void append_box(const BoxSpec& box, SurfaceMesh& mesh) {
  // Each face has its own four vertices so that its normal stays flat.
  for (int axis = 0; axis < 3; ++axis)
    for (const double side : {-1.0, 1.0}) {
      Vec3 n = Vec3::Zero();
      n[axis] = side;
      Vec3 u = Vec3::Zero(), v = Vec3::Zero();
      u[(axis + 1) % 3] = 1;
      v[(axis + 2) % 3] = 1;
      if (side < 0) std::swap(u, v);  // keeps u x v = n: counter-clockwise from outside
      const Vec3 h = box.half_extents;
      const Vec3 c = box.center + side * h[axis] * Vec3::Unit(axis);
      const Vec3 du = u.cwiseProduct(h), dv = v.cwiseProduct(h);
      const std::uint32_t a = mesh.add_vertex(c - du - dv, n);
      const std::uint32_t b = mesh.add_vertex(c + du - dv, n);
      const std::uint32_t d = mesh.add_vertex(c + du + dv, n);
      const std::uint32_t e = mesh.add_vertex(c - du + dv, n);
      mesh.add_triangle(a, b, d);
      mesh.add_triangle(a, d, e);
    }
}

void append_sphere(const SphereSpec& sphere, SurfaceMesh& mesh) {
  auto direction = [](int i, int j) -> Vec3 {
    const double polar = kPi * i / kStacks, azimuth = 2 * kPi * j / kSlices;
    return Vec3(std::sin(polar) * std::cos(azimuth), std::cos(polar),
                -std::sin(polar) * std::sin(azimuth));
  };
  append_lattice(
      kStacks, kSlices,
      [&](int i, int j) -> Vec3 { return sphere.center + sphere.radius * direction(i, j); },
      direction, mesh);
}

void append_capsule(const CapsuleSpec& capsule, SurfaceMesh& mesh) {
  Vec3 axis = capsule.b - capsule.a;
  const double length = axis.norm();
  axis = length > 0 ? Vec3(axis / length) : Vec3(Vec3::UnitY());
  Vec3 u, v;
  orthonormal_basis(axis, u, v);
  // A sphere split at its equator, the top half around b and the bottom half
  // around a; the two middle stacks join them with the cylinder.
  const int half = kStacks / 2;
  auto direction = [&](int i, int j) -> Vec3 {
    const int stack = i <= half ? i : i - 1;  // stacks half and half + 1 share a latitude
    const double polar = kPi * stack / kStacks, azimuth = 2 * kPi * j / kSlices;
    return Vec3(std::cos(polar) * axis +
                std::sin(polar) * (std::cos(azimuth) * u + std::sin(azimuth) * v));
  };
  auto point = [&](int i, int j) -> Vec3 {
    const Vec3& end = i <= half ? capsule.b : capsule.a;
    return Vec3(end + capsule.radius * direction(i, j));
  };
  append_lattice(kStacks + 1, kSlices, point, direction, mesh);
}

void append_plane(const PlaneSpec& plane, const Vec3& centre, double half_size, SurfaceMesh& mesh) {
  const Vec3 n = plane.normal.normalized();
  Vec3 u, v;
  orthonormal_basis(n, u, v);
  const Vec3 c = centre - (centre - plane.point).dot(n) * n;
  const std::uint32_t a = mesh.add_vertex(c + half_size * (-u - v), n);
  const std::uint32_t b = mesh.add_vertex(c + half_size * (u - v), n);
  const std::uint32_t d = mesh.add_vertex(c + half_size * (u + v), n);
  const std::uint32_t e = mesh.add_vertex(c + half_size * (-u + v), n);
  mesh.add_triangle(a, b, d);
  mesh.add_triangle(a, d, e);
}

SurfaceMesh collider_mesh(const std::vector<ModuleSpec>& colliders, const Vec3& centre,
                          double plane_half_size) {
  SurfaceMesh mesh;
  for (const ModuleSpec& spec : colliders)
    std::visit(
        [&](const auto& s) {
          using T = std::decay_t<decltype(s)>;
          if constexpr (std::is_same_v<T, PlaneSpec>)
            append_plane(s, centre, plane_half_size, mesh);
          if constexpr (std::is_same_v<T, BoxSpec>) append_box(s, mesh);
          if constexpr (std::is_same_v<T, SphereSpec>) append_sphere(s, mesh);
          if constexpr (std::is_same_v<T, CapsuleSpec>) append_capsule(s, mesh);
        },
        spec);
  return mesh;
}

}  // namespace neurocloth
