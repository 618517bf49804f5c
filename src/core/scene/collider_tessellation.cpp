#include "core/scene/collider_tessellation.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
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

void append_cylinder(const CylinderSpec& cylinder, SurfaceMesh& mesh) {
  const Vec3 axis = cylinder.axis.normalized();
  Vec3 u, v;
  orthonormal_basis(axis, u, v);
  const Vec3 half = 0.5 * cylinder.height * axis;
  auto across = [&](int j) -> Vec3 {
    const double azimuth = 2 * kPi * j / kSlices;
    return Vec3(std::cos(azimuth) * u + std::sin(azimuth) * v);
  };
  // The side: two rows of vertices, the top one (j) first; u x v = axis, so
  // (top j, bottom j, top j + 1) is counter-clockwise seen from outside.
  append_lattice(
      1, kSlices,
      [&](int i, int j) -> Vec3 {
        return Vec3(cylinder.center + (i == 0 ? half : Vec3(-half)) + cylinder.radius * across(j));
      },
      [&](int, int j) { return across(j); }, mesh);
  // Each end a fan around its centre, with its own vertices so that it stays flat.
  for (const double side : {1.0, -1.0}) {
    const Vec3 n = side * axis, centre = cylinder.center + side * half;
    const std::uint32_t middle = mesh.add_vertex(centre, n);
    for (int j = 0; j < kSlices; ++j)
      mesh.add_vertex(centre + cylinder.radius * across(j), n);
    for (int j = 0; j < kSlices; ++j) {
      const std::uint32_t a = middle + 1 + std::uint32_t(j),
                          b = middle + 1 + std::uint32_t((j + 1) % kSlices);
      if (side > 0)
        mesh.add_triangle(middle, a, b);
      else
        mesh.add_triangle(middle, b, a);
    }
  }
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

void append_obstacle(const ObstacleMesh& obstacle, SurfaceMesh& mesh, double crease_degrees) {
  const TriangleSurface& surface = obstacle.surface;
  const std::size_t nv = surface.vertices.size(), nt = surface.triangles.size();
  // Area-weighted face normals (the cross product's length is twice the area).
  std::vector<Vec3> face(nt);
  for (std::size_t f = 0; f < nt; ++f) {
    const auto& t = surface.triangles[f];
    const Vec3& a = surface.vertices[std::size_t(t[0])];
    face[f] =
        (surface.vertices[std::size_t(t[1])] - a).cross(surface.vertices[std::size_t(t[2])] - a);
  }
  // Each vertex's triangles (compressed rows).
  std::vector<std::size_t> first(nv + 1, 0), around(3 * nt);
  for (const auto& t : surface.triangles)
    for (const std::int32_t v : t)
      ++first[std::size_t(v) + 1];
  for (std::size_t v = 0; v < nv; ++v)
    first[v + 1] += first[v];
  std::vector<std::size_t> fill(first.begin(), first.end() - 1);
  for (std::size_t f = 0; f < nt; ++f)
    for (const std::int32_t v : surface.triangles[f])
      around[fill[std::size_t(v)]++] = f;

  // A corner's normal sums the triangles around its vertex that are within
  // the crease angle of its own triangle (all of them on a smooth surface; a
  // degenerate triangle takes all). Corners of a vertex whose sets are the
  // same share one vertex of the mesh.
  const double cos_crease = std::cos(crease_degrees * kPi / 180.0);
  std::vector<std::array<std::uint32_t, 3>> corner(nt);
  std::map<std::vector<std::size_t>, std::uint32_t> made;  // one vertex's groups, reused
  std::vector<std::size_t> group;
  for (std::size_t v = 0; v < nv; ++v) {
    made.clear();
    for (std::size_t i = first[v]; i < first[v + 1]; ++i) {
      const std::size_t f = around[i];
      const double len_f = face[f].norm();
      group.clear();
      Vec3 sum = Vec3::Zero();
      for (std::size_t j = first[v]; j < first[v + 1]; ++j) {
        const std::size_t g = around[j];
        const double len_g = face[g].norm();
        if (len_f > 0 && len_g > 0 && face[f].dot(face[g]) < cos_crease * len_f * len_g) continue;
        group.push_back(g);
        sum += face[g];
      }
      auto [it, fresh] = made.emplace(group, 0);
      if (fresh) {
        const double len = sum.norm();
        it->second =
            mesh.add_vertex(surface.vertices[v], len > 0 ? Vec3(sum / len) : Vec3(Vec3::UnitY()));
        mesh.source.push_back(std::int32_t(v));
      }
      const auto& t = surface.triangles[f];
      for (int k = 0; k < 3; ++k)
        if (std::size_t(t[std::size_t(k)]) == v) corner[f][std::size_t(k)] = it->second;
    }
  }
  for (const auto& c : corner)
    mesh.add_triangle(c[0], c[1], c[2]);
}

void append_collider(const ModuleSpec& collider, const Vec3& centre, double plane_half_size,
                     SurfaceMesh& mesh) {
  std::visit(
      [&](const auto& s) {
        using T = std::decay_t<decltype(s)>;
        if constexpr (std::is_same_v<T, PlaneSpec>)
          append_plane(s, centre, plane_half_size, mesh);
        else if constexpr (std::is_same_v<T, BoxSpec>)
          append_box(s, mesh);
        else if constexpr (std::is_same_v<T, SphereSpec>)
          append_sphere(s, mesh);
        else if constexpr (std::is_same_v<T, CapsuleSpec>)
          append_capsule(s, mesh);
        else if constexpr (std::is_same_v<T, CylinderSpec>)
          append_cylinder(s, mesh);
        else if constexpr (std::is_same_v<T, MeshSpec>) {
          if (s.mesh) append_obstacle(*s.mesh, mesh);
        }
      },
      collider);
}

void recompute_normals(SurfaceMesh& mesh) {
  std::fill(mesh.normal.begin(), mesh.normal.end(), 0.0f);
  for (std::size_t t = 0; t + 2 < mesh.index.size(); t += 3) {
    const std::uint32_t i[3] = {mesh.index[t], mesh.index[t + 1], mesh.index[t + 2]};
    const Vec3 a = mesh.vertex(i[0]);
    const Vec3 n = (mesh.vertex(i[1]) - a).cross(mesh.vertex(i[2]) - a);
    for (const std::uint32_t v : i)
      for (int d = 0; d < 3; ++d)
        mesh.normal[3 * v + std::size_t(d)] += float(n[d]);
  }
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    float* n = &mesh.normal[3 * v];
    const float len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int d = 0; d < 3; ++d)
      n[d] = len > 0 ? n[d] / len : (d == 1 ? 1.0f : 0.0f);
  }
}

}  // namespace neurocloth
