// Collider meshes: every vertex on the solid's surface, normals pointing out,
// and triangles wound counter-clockwise seen from outside (so that the
// renderer's front side is the outside).
#include "render/collider_meshes.h"

#include <gtest/gtest.h>

#include <cmath>

namespace neurocloth {
namespace {

Vec3 vertex(const SurfaceMesh& m, std::size_t i) {
  return Vec3(m.position[3 * i], m.position[3 * i + 1], m.position[3 * i + 2]);
}
Vec3 normal(const SurfaceMesh& m, std::size_t i) {
  return Vec3(m.normal[3 * i], m.normal[3 * i + 1], m.normal[3 * i + 2]);
}

// Each triangle's geometric normal agrees with its vertices' normals, and every
// index is in range; returns the total area.
double check_winding(const SurfaceMesh& m) {
  EXPECT_EQ(m.index.size() % 3, 0u);
  double area = 0;
  for (std::size_t t = 0; t + 2 < m.index.size(); t += 3) {
    for (int k = 0; k < 3; ++k)
      EXPECT_LT(m.index[t + k], m.vertex_count());
    const Vec3 a = vertex(m, m.index[t]), b = vertex(m, m.index[t + 1]),
               c = vertex(m, m.index[t + 2]);
    const Vec3 n = (b - a).cross(c - a);
    area += 0.5 * n.norm();
    if (n.norm() < 1e-12) continue;  // a pole's sliver
    const Vec3 avg = normal(m, m.index[t]) + normal(m, m.index[t + 1]) + normal(m, m.index[t + 2]);
    EXPECT_GT(n.normalized().dot(avg.normalized()), 0.9) << "triangle " << t / 3;
  }
  for (std::size_t i = 0; i < m.vertex_count(); ++i)
    EXPECT_NEAR(normal(m, i).norm(), 1, 1e-6);
  return area;
}

TEST(ColliderMeshes, ABoxHasSixFlatFacesOnItsSurface) {
  BoxSpec box;
  box.center = Vec3(0, 0.375, 0);
  box.half_extents = Vec3(0.4, 0.375, 0.4);
  SurfaceMesh m;
  append_box(box, m);
  EXPECT_EQ(m.vertex_count(), 24u);
  EXPECT_EQ(m.index.size(), 36u);
  const double area = check_winding(m);
  const Vec3 h = box.half_extents;
  EXPECT_NEAR(area, 8 * (h.x() * h.y() + h.y() * h.z() + h.z() * h.x()), 1e-5);
  for (std::size_t i = 0; i < m.vertex_count(); ++i) {
    const Vec3 local = vertex(m, i) - box.center;
    // On the face its normal points out of.
    const Vec3 n = normal(m, i);
    EXPECT_NEAR(local.dot(n), h.cwiseProduct(n.cwiseAbs()).sum(), 1e-6);
    EXPECT_NEAR(local.cwiseAbs().cwiseQuotient(h).maxCoeff(), 1, 1e-6);
  }
}

TEST(ColliderMeshes, ASphereLiesAtItsRadiusWithRadialNormals) {
  SphereSpec sphere;
  sphere.center = Vec3(1, 2, 3);
  sphere.radius = 0.3;
  SurfaceMesh m;
  append_sphere(sphere, m);
  const double area = check_winding(m);
  EXPECT_NEAR(area, 4 * M_PI * 0.09, 0.01 * 4 * M_PI * 0.09);
  for (std::size_t i = 0; i < m.vertex_count(); ++i) {
    const Vec3 r = vertex(m, i) - sphere.center;
    EXPECT_NEAR(r.norm(), 0.3, 1e-6);
    EXPECT_GT(r.normalized().dot(normal(m, i)), 1 - 1e-6);
  }
}

TEST(ColliderMeshes, ACapsuleLiesAtItsRadiusFromItsSegment) {
  CapsuleSpec capsule;
  capsule.a = Vec3(-0.5, 0.2, 0.1);
  capsule.b = Vec3(0.5, 0.4, -0.3);
  capsule.radius = 0.15;
  SurfaceMesh m;
  append_capsule(capsule, m);
  const double area = check_winding(m);
  const double length = (capsule.b - capsule.a).norm(), r = capsule.radius;
  const double exact = 2 * M_PI * r * length + 4 * M_PI * r * r;
  EXPECT_NEAR(area, exact, 0.01 * exact);
  const Vec3 axis = (capsule.b - capsule.a) / length;
  for (std::size_t i = 0; i < m.vertex_count(); ++i) {
    const Vec3 p = vertex(m, i);
    const double t = std::clamp((p - capsule.a).dot(axis), 0.0, length);
    const Vec3 nearest = capsule.a + t * axis;
    EXPECT_NEAR((p - nearest).norm(), r, 1e-6);
    EXPECT_GT((p - nearest).normalized().dot(normal(m, i)), 1 - 1e-5);
  }
}

TEST(ColliderMeshes, APlaneIsASquareAroundTheSceneOnThePlane) {
  PlaneSpec plane;
  plane.point = Vec3(0, -0.2, 0);
  plane.normal = Vec3(0, 1, 0);
  SurfaceMesh m;
  append_plane(plane, Vec3(3, 5, -1), 10, m);
  EXPECT_NEAR(check_winding(m), 400, 1e-3);
  Vec3 centre = Vec3::Zero();
  for (std::size_t i = 0; i < m.vertex_count(); ++i) {
    EXPECT_NEAR(vertex(m, i).y(), -0.2, 1e-6);
    EXPECT_EQ(normal(m, i), Vec3(0, 1, 0));
    centre += vertex(m, i) / 4;
  }
  EXPECT_LT((centre - Vec3(3, -0.2, -1)).norm(), 1e-5);
}

TEST(ColliderMeshes, OnlyCollidersBecomeMeshes) {
  const std::vector<ModuleSpec> specs = {AirDragSpec{}, BoxSpec{}, WindSpec{}, SphereSpec{}};
  const SurfaceMesh m = collider_mesh(specs, Vec3::Zero(), 5);
  SurfaceMesh expected;
  append_box(BoxSpec{}, expected);
  append_sphere(SphereSpec{}, expected);
  EXPECT_EQ(m.index, expected.index);
  EXPECT_EQ(m.position, expected.position);
  EXPECT_TRUE(collider_mesh({}, Vec3::Zero(), 5).index.empty());
}

}  // namespace
}  // namespace neurocloth
