// The nearest point of a triangle (nearest_on_triangle.h): against a fine
// lattice of the triangle's points, and distances worked out by hand in each
// Voronoi region and for degenerate triangles.
#include "core/geometry/nearest_on_triangle.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace neurocloth {
namespace {

// The nearest of a fine lattice of the triangle's points: what the exact
// answer may not be farther than.
double lattice_nearest2(const Vec3& y, const Vec3& a, const Vec3& b, const Vec3& c) {
  double best = HUGE_VAL;
  const int m = 400;
  for (int i = 0; i <= m; ++i)
    for (int j = 0; i + j <= m; ++j) {
      const double u = double(i) / m, v = double(j) / m;
      best = std::min(best, ((1 - u - v) * a + u * b + v * c - y).squaredNorm());
    }
  return best;
}

TEST(NearestOnTriangle, AgainstALatticeInEveryRegion) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.5, 1.5);
  const Vec3 a(0, 0, 0), b(1, 0.1, 0), c(0.2, 0.9, 0.1);
  for (int k = 0; k < 300; ++k) {
    const Vec3 y(u(rng), u(rng), u(rng));
    const auto w = nearest_on_triangle(y, a, b, c);
    EXPECT_NEAR(w[0] + w[1] + w[2], 1.0, 1e-14);
    for (double x : w) {
      EXPECT_GE(x, -1e-14);
      EXPECT_LE(x, 1 + 1e-14);
    }
    const double d2 = (w[0] * a + w[1] * b + w[2] * c - y).squaredNorm();
    const double lattice = lattice_nearest2(y, a, b, c);
    // Never farther than the lattice's best, and the lattice (spacing 1/400
    // of the sides) is at most a hair farther than the exact point.
    EXPECT_LE(d2, lattice + 1e-15) << "point " << y.transpose();
    EXPECT_GE(d2, lattice - 6e-3 * std::sqrt(lattice) - 1e-5) << "point " << y.transpose();
  }
  // A degenerate triangle (three points on a line) gives a point of the line.
  const auto w = nearest_on_triangle(Vec3(0.5, 1, 0), a, Vec3(1, 0, 0), Vec3(2, 0, 0));
  EXPECT_NEAR((w[0] * a + w[1] * Vec3(1, 0, 0) + w[2] * Vec3(2, 0, 0) - Vec3(0.5, 0, 0)).norm(),
              0.0, 1e-14);
}

TEST(NearestOnTriangle, DistancesByHandInEveryRegion) {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  EXPECT_DOUBLE_EQ(point_triangle_distance(Vec3(0.2, 0.2, 0.5), a, b, c), 0.5);         // the face
  EXPECT_DOUBLE_EQ(point_triangle_distance(Vec3(-1, -1, 0), a, b, c), std::sqrt(2.0));  // a
  EXPECT_DOUBLE_EQ(point_triangle_distance(Vec3(2, 0, 0), a, b, c), 1.0);               // b
  EXPECT_DOUBLE_EQ(point_triangle_distance(Vec3(0.5, -2, 0), a, b, c), 2.0);            // edge ab
  EXPECT_NEAR(point_triangle_distance(Vec3(1, 1, 0), a, b, c), std::sqrt(0.5), 1e-15);  // bc
  // A degenerate triangle is its longest edge.
  EXPECT_DOUBLE_EQ(point_triangle_distance(Vec3(0.5, 1, 0), a, b, Vec3(0.5, 0, 0)), 1.0);
  EXPECT_DOUBLE_EQ(point_triangle_distance(Vec3(0, 3, 4), a, a, a), 5.0);
}

}  // namespace
}  // namespace neurocloth
