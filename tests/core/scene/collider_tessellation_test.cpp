// Collider meshes: every vertex on the solid's surface, normals pointing out,
// and triangles wound counter-clockwise seen from outside (so that the
// renderer's front side is the outside); a mesh obstacle's normals smooth
// where it is smooth and split at its creases.
#include "core/scene/collider_tessellation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "support/triangle_meshes.h"

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

TEST(ColliderTessellation, ABoxHasSixFlatFacesOnItsSurface) {
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

TEST(ColliderTessellation, ASphereLiesAtItsRadiusWithRadialNormals) {
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

TEST(ColliderTessellation, ACapsuleLiesAtItsRadiusFromItsSegment) {
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

// Side vertices at the radius with normals across the axis; end vertices on
// their end's plane with its normal; the area the solid's within the slices'
// chords (48 of them: 0.3% short).
TEST(ColliderTessellation, ACylindersSideIsAtItsRadiusAndItsEndsAreFlat) {
  CylinderSpec cylinder;
  cylinder.center = Vec3(0.1, 0.5, -0.2);
  cylinder.axis = Vec3(0.3, 1, 0.2).normalized();
  cylinder.radius = 0.09;
  cylinder.height = 0.2;
  SurfaceMesh m;
  append_collider(cylinder, Vec3::Zero(), 5, m);
  const double area = check_winding(m), r = cylinder.radius, h = cylinder.height;
  const double exact = 2 * M_PI * r * h + 2 * M_PI * r * r;
  EXPECT_NEAR(area, exact, 0.005 * exact);
  EXPECT_LT(area, exact);
  const Vec3 a = cylinder.axis;
  for (std::size_t i = 0; i < m.vertex_count(); ++i) {
    const Vec3 d = vertex(m, i) - cylinder.center, n = normal(m, i);
    const double along = d.dot(a), across = (d - along * a).norm();
    if (std::abs(n.dot(a)) > 0.5) {  // an end's
      EXPECT_NEAR(std::abs(n.dot(a)), 1, 1e-6) << i;
      EXPECT_NEAR(along, 0.5 * h * n.dot(a), 1e-6) << i;
      EXPECT_LE(across, r + 1e-6) << i;
    } else {
      EXPECT_NEAR(n.dot(a), 0, 1e-6) << i;
      EXPECT_NEAR(std::abs(along), 0.5 * h, 1e-6) << i;
      EXPECT_NEAR(across, r, 1e-6) << i;
      EXPECT_GT((d - along * a).normalized().dot(n), 1 - 1e-5) << i;
    }
  }
}

TEST(ColliderTessellation, APlaneIsASquareAroundTheSceneOnThePlane) {
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

TEST(ColliderTessellation, OnlyCollidersBecomeMeshes) {
  SurfaceMesh m;
  for (const ModuleSpec& spec : {ModuleSpec(AirDragSpec{}), ModuleSpec(BoxSpec{}),
                                 ModuleSpec(WindSpec{}), ModuleSpec(SphereSpec{})})
    append_collider(spec, Vec3::Zero(), 5, m);
  SurfaceMesh expected;
  append_box(BoxSpec{}, expected);
  append_sphere(SphereSpec{}, expected);
  EXPECT_EQ(m.index, expected.index);
  EXPECT_EQ(m.position, expected.position);
  EXPECT_TRUE(m.source.empty());
}

// A box's shape frame is the box as declared: its rotation is its pose's
// (collider_pose), not its mesh's.
TEST(ColliderTessellation, ARotatedBoxIsTessellatedAxisAligned) {
  BoxSpec box;
  box.rotate = Vec3(0, 30, 0);
  SurfaceMesh rotated, plain;
  append_collider(box, Vec3::Zero(), 5, rotated);
  append_box(BoxSpec{}, plain);
  EXPECT_EQ(rotated.position, plain.position);
}

std::shared_ptr<ObstacleMesh> obstacle(TriangleSurface surface) {
  auto mesh = std::make_shared<ObstacleMesh>();
  mesh->surface = std::move(surface);
  return mesh;
}

// A cube of 12 triangles: every edge is a 90 degree crease, so each corner is
// split into its three faces' vertices and every face is flat.
TEST(ColliderTessellation, AMeshBoxShowsFlatFaces) {
  const auto cube = obstacle(test::cube_surface(0.5));
  SurfaceMesh m;
  append_obstacle(*cube, m);
  EXPECT_EQ(m.index.size(), 36u);
  EXPECT_EQ(m.vertex_count(), 24u);
  ASSERT_EQ(m.source.size(), 24u);
  EXPECT_NEAR(check_winding(m), 6.0, 1e-9);
  for (std::size_t i = 0; i < m.vertex_count(); ++i) {
    EXPECT_EQ(vertex(m, i), cube->surface.vertices[std::size_t(m.source[i])]);
    // An axis: the normal of one face, not a corner's average.
    EXPECT_NEAR(normal(m, i).cwiseAbs().maxCoeff(), 1, 1e-6) << i;
  }
}

// An icosphere is smooth everywhere: one vertex each, normals nearly radial.
TEST(ColliderTessellation, AMeshSphereIsSmoothShaded) {
  const auto ball = obstacle(test::icosphere(3, 0.4));
  SurfaceMesh m;
  MeshSpec spec;
  spec.mesh = ball;
  append_collider(spec, Vec3::Zero(), 5, m);
  EXPECT_EQ(m.vertex_count(), ball->surface.vertices.size());
  EXPECT_EQ(m.index.size(), 3 * ball->surface.triangles.size());
  check_winding(m);
  for (std::size_t i = 0; i < m.vertex_count(); ++i)
    EXPECT_GT(vertex(m, i).normalized().dot(normal(m, i)), 0.999) << i;
}

// After the vertices move (a deforming obstacle), the normals follow them and
// a crease's split vertices keep their own sides.
TEST(ColliderTessellation, NormalsAreRecomputedFromMovedVertices) {
  const auto cube = obstacle(test::cube_surface(0.5));
  SurfaceMesh m;
  append_obstacle(*cube, m);
  const std::vector<float> before = m.normal;
  // Turned a quarter about z: x -> y, y -> -x.
  for (std::size_t i = 0; i < m.vertex_count(); ++i) {
    const Vec3 p = vertex(m, i);
    m.position[3 * i] = float(-p.y());
    m.position[3 * i + 1] = float(p.x());
  }
  recompute_normals(m);
  for (std::size_t i = 0; i < m.vertex_count(); ++i) {
    const Vec3 n0(before[3 * i], before[3 * i + 1], before[3 * i + 2]);
    EXPECT_LT((normal(m, i) - Vec3(-n0.y(), n0.x(), n0.z())).norm(), 1e-6) << i;
  }
}

}  // namespace
}  // namespace neurocloth
