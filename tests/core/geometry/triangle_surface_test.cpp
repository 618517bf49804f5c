// What finish_surface derives (triangle_surface.h), on meshes whose answers are
// known by hand: a cube (closed, 12 sharp edges, corner normals along the
// diagonals), the cube opened or with a face turned over (not closed), an
// icosphere (no sharp edge, radial normals), an open grid (only its border is
// sharp), degenerate and non-manifold triangles; and that finishing moved
// vertices again gives a fresh finish's bits without allocating.
#include "core/geometry/triangle_surface.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

#include "support/triangle_meshes.h"

namespace neurocloth {
namespace {

using test::cube_surface;
using test::icosphere;
using test::square_grid;

TEST(TriangleSurface, CubeIsClosedWithOutwardNormals) {
  const TriangleSurface s = cube_surface();
  EXPECT_TRUE(s.closed);
  EXPECT_EQ(s.edges.size(), 18u);  // 12 cube edges and 6 face diagonals
  for (std::size_t t = 0; t < s.triangles.size(); ++t) {
    const Vec3 centre = (s.vertices[static_cast<std::size_t>(s.triangles[t][0])] +
                         s.vertices[static_cast<std::size_t>(s.triangles[t][1])] +
                         s.vertices[static_cast<std::size_t>(s.triangles[t][2])]) /
                        3;
    // A face's normal is the axis its centre lies furthest along.
    Vec3 axis = Vec3::Zero();
    int k;
    centre.cwiseAbs().maxCoeff(&k);
    axis[k] = centre[k] > 0 ? 1 : -1;
    EXPECT_NEAR((s.face_normals[t] - axis).norm(), 0, 1e-15) << "triangle " << t;
  }
  // Angle weighting: each corner sees its three faces at 90 degrees however
  // they were split, so its normal is the diagonal.
  for (std::size_t v = 0; v < 8; ++v)
    EXPECT_NEAR((s.vertex_normals[v] - s.vertices[v] / std::sqrt(3.0)).norm(), 0, 1e-15);
  // A cube edge's normal halves its faces'; a diagonal's is its face's.
  for (std::size_t t = 0; t < s.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const Vec3 mid = (s.vertices[static_cast<std::size_t>(s.triangles[t][k])] +
                        s.vertices[static_cast<std::size_t>(s.triangles[t][(k + 1) % 3])]) /
                       2;
      const int zeros = (mid.array() == 0).count();
      const Vec3 expected = zeros == 2 ? s.face_normals[t] : Vec3(mid / mid.norm());
      EXPECT_NEAR((s.edge_normals[t][k] - expected).norm(), 0, 1e-15) << t << " " << k;
    }
}

TEST(TriangleSurface, CubeHasTwelveSharpEdgesEachOnce) {
  const TriangleSurface s = cube_surface();
  ASSERT_EQ(s.sharp_edges.size(), 12u);
  for (const TriangleSurface::SharpEdge& e : s.sharp_edges) {
    EXPECT_FALSE(e.border);
    EXPECT_NEAR(e.normal_a.dot(e.normal_b), 0, 1e-15);  // faces at right angles
    // Along one axis: the ends differ in one coordinate only.
    const Vec3 d =
        s.vertices[static_cast<std::size_t>(e.b)] - s.vertices[static_cast<std::size_t>(e.a)];
    EXPECT_EQ((d.array() != 0).count(), 1);
    // normal_a is the face that traverses a -> b.
    const auto& edge = s.edges[static_cast<std::size_t>(e.edge)];
    EXPECT_EQ(edge.a, e.a);
    EXPECT_EQ(edge.b, e.b);
  }
  // Nothing is sharp if the angle is wider than the cube's bends.
  TriangleSurface wide = cube_surface();
  finish_surface(wide, 95.0);
  EXPECT_TRUE(wide.sharp_edges.empty());
}

TEST(TriangleSurface, CubeMinusAFaceIsOpenAndItsRimIsBorder) {
  TriangleSurface s = cube_surface();
  s.triangles.erase(s.triangles.begin() + 2, s.triangles.begin() + 4);  // the +z face
  finish_surface(s);
  EXPECT_FALSE(s.closed);
  ASSERT_EQ(s.sharp_edges.size(), 12u);
  int border = 0;
  for (const TriangleSurface::SharpEdge& e : s.sharp_edges) {
    if (!e.border) continue;
    ++border;
    EXPECT_EQ(e.normal_a, e.normal_b);
    EXPECT_EQ(s.vertices[static_cast<std::size_t>(e.a)].z(), 1.0);
    EXPECT_EQ(s.vertices[static_cast<std::size_t>(e.b)].z(), 1.0);
  }
  EXPECT_EQ(border, 4);
}

TEST(TriangleSurface, AFaceTurnedOverIsNotClosed) {
  TriangleSurface s = cube_surface();
  std::swap(s.triangles[5][1], s.triangles[5][2]);
  finish_surface(s);
  EXPECT_FALSE(s.closed);
  EXPECT_EQ(s.edges.size(), 18u);  // still every edge twice, but not opposed
  EXPECT_TRUE(cube_surface().closed);
}

TEST(TriangleSurface, FineIcosphereHasNoSharpEdgeAndRadialNormals) {
  const TriangleSurface s = icosphere(4);
  EXPECT_TRUE(s.closed);
  EXPECT_EQ(s.triangles.size(), 5120u);
  EXPECT_TRUE(s.sharp_edges.empty());
  double worst = 0;
  for (std::size_t v = 0; v < s.vertices.size(); ++v)
    worst = std::max(worst, (s.vertex_normals[v] - s.vertices[v]).norm());
  // The 12 corners of the icosahedron are symmetric; elsewhere a vertex's
  // fan is slightly uneven. Measured 2.6e-3.
  EXPECT_LT(worst, 3e-3);
  for (const Vec3& n : s.face_normals)
    EXPECT_NEAR(n.norm(), 1, 1e-15);
  // The coarse icosahedron bends by 41.8 degrees at every edge.
  TriangleSurface coarse = icosphere(0);
  EXPECT_EQ(coarse.sharp_edges.size(), 30u);
  finish_surface(coarse, 42.0);
  EXPECT_TRUE(coarse.sharp_edges.empty());
}

TEST(TriangleSurface, OpenGridIsSharpOnlyAtItsBorder) {
  const int n = 5;
  const TriangleSurface s = square_grid(n);
  EXPECT_FALSE(s.closed);
  ASSERT_EQ(s.sharp_edges.size(), static_cast<std::size_t>(4 * n));
  for (const TriangleSurface::SharpEdge& e : s.sharp_edges) {
    EXPECT_TRUE(e.border);
    EXPECT_EQ(e.normal_a, Vec3(0, 0, 1));
    const Vec3 mid =
        (s.vertices[static_cast<std::size_t>(e.a)] + s.vertices[static_cast<std::size_t>(e.b)]) / 2;
    EXPECT_TRUE(mid.x() == 0 || mid.x() == 1 || mid.y() == 0 || mid.y() == 1) << mid.transpose();
  }
  // Every vertex of a flat sheet has the sheet's normal; so has every edge.
  for (const Vec3& v : s.vertex_normals)
    EXPECT_NEAR((v - Vec3(0, 0, 1)).norm(), 0, 1e-15);
  for (const auto& three : s.edge_normals)
    for (const Vec3& e : three)
      EXPECT_NEAR((e - Vec3(0, 0, 1)).norm(), 0, 1e-15);
}

TEST(TriangleSurface, DegenerateTrianglesAreIgnored) {
  TriangleSurface s = cube_surface();
  const TriangleSurface clean = cube_surface();
  // A sliver on three points of a line, and a triangle with a repeated corner.
  s.vertices.push_back(Vec3(3, 0, 0));
  s.vertices.push_back(Vec3(4, 0, 0));
  s.vertices.push_back(Vec3(5, 0, 0));
  s.triangles.push_back({8, 9, 10});
  s.triangles.push_back({1, 1, 3});
  finish_surface(s);
  EXPECT_EQ(s.face_normals[12], Vec3::Zero());
  EXPECT_EQ(s.face_normals[13], Vec3::Zero());
  for (std::size_t v = 0; v < 8; ++v)
    EXPECT_EQ(s.vertex_normals[v], clean.vertex_normals[v]);
  for (std::size_t v = 8; v < 11; ++v)
    EXPECT_EQ(s.vertex_normals[v], Vec3::Zero());
  for (std::size_t t = 0; t < 12; ++t)
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(s.edge_normals[t][k], clean.edge_normals[t][k]);
  EXPECT_EQ(s.sharp_edges.size(), 12u);  // none from the slivers' edges
  EXPECT_FALSE(s.closed);                // topology counts every triangle
}

TEST(TriangleSurface, AnEdgeOfThreeFacesIsSharpOnce) {
  TriangleSurface s;
  s.vertices = {{0, 0, 0}, {1, 0, 0}, {0.5, 1, 0}, {0.5, -1, 0}, {0.5, 0, 1}};
  s.triangles = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
  finish_surface(s);
  int on_01 = 0;
  for (const TriangleSurface::SharpEdge& e : s.sharp_edges) {
    if (std::minmax(e.a, e.b) != std::minmax(0, 1)) continue;
    ++on_01;
    EXPECT_FALSE(e.border);
    EXPECT_EQ(e.normal_a, s.face_normals[0]);
    EXPECT_EQ(e.normal_b, s.face_normals[1]);
  }
  EXPECT_EQ(on_01, 1);
  EXPECT_EQ(s.sharp_edges.size(), 7u);  // that one and the six borders
}

TEST(TriangleSurface, FinishingMovedVerticesEqualsAFreshFinishWithoutAllocating) {
  TriangleSurface moved = icosphere(3);
  moved.sharp_edges.reserve(moved.edges.size());  // what a deforming obstacle does
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-0.2, 0.2);
  for (int step = 0; step < 3; ++step) {
    const Vec3* normals = moved.face_normals.data();
    const TriangleSurface::SharpEdge* sharp = moved.sharp_edges.data();
    for (Vec3& v : moved.vertices)
      v += Vec3(u(rng), u(rng), u(rng));
    finish_moved_surface(moved);
    EXPECT_EQ(moved.face_normals.data(), normals);
    EXPECT_EQ(moved.sharp_edges.data(), sharp);
    TriangleSurface fresh;
    fresh.vertices = moved.vertices;
    fresh.triangles = moved.triangles;
    finish_surface(fresh);
    EXPECT_EQ(fresh.face_normals, moved.face_normals);
    EXPECT_EQ(fresh.vertex_normals, moved.vertex_normals);
    EXPECT_EQ(fresh.edge_normals, moved.edge_normals);
    ASSERT_EQ(fresh.sharp_edges.size(), moved.sharp_edges.size());
    EXPECT_GT(fresh.sharp_edges.size(), 0u);  // the noise folds it
    for (std::size_t i = 0; i < fresh.sharp_edges.size(); ++i) {
      EXPECT_EQ(fresh.sharp_edges[i].edge, moved.sharp_edges[i].edge);
      EXPECT_EQ(fresh.sharp_edges[i].normal_a, moved.sharp_edges[i].normal_a);
      EXPECT_EQ(fresh.sharp_edges[i].normal_b, moved.sharp_edges[i].normal_b);
    }
  }
}

TEST(TriangleSurface, MissingVerticesAndUnfinishedSurfacesAreRefused) {
  TriangleSurface s = cube_surface();
  s.triangles.push_back({0, 1, 8});
  EXPECT_THROW(finish_surface(s), std::out_of_range);
  s.triangles.back() = {0, -1, 2};
  EXPECT_THROW(finish_surface(s), std::out_of_range);
  TriangleSurface unfinished;
  unfinished.vertices = s.vertices;
  unfinished.triangles = {{0, 1, 2}};
  EXPECT_THROW(finish_moved_surface(unfinished), std::logic_error);
}

}  // namespace
}  // namespace neurocloth
