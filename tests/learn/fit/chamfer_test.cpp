// The Chamfer distance of a point cloud to the cloth (chamfer.h): the nearest
// triangle against all of them, and the gradient against central differences for
// every option.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/geometry/nearest_on_triangle.h"
#include "learn/fit/chamfer.h"

namespace neurocloth {
namespace {

// A 6 x 6 grid bent into a wave, and a cloud near (and partly beyond) it.
struct Patch {
  std::vector<Vec3> nodes;
  std::shared_ptr<const ClothSurface> surface;
  std::vector<Vec3> cloud;
};

Patch wavy_patch(unsigned seed) {
  Patch p;
  const int n = 6;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> jitter(-0.004, 0.004);
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < n; ++c)
      p.nodes.emplace_back(0.02 * c + jitter(rng), 0.01 * std::sin(0.9 * r + 0.4 * c) + jitter(rng),
                           0.02 * r + jitter(rng));
  std::vector<std::array<std::int32_t, 3>> tris;
  for (int r = 0; r + 1 < n; ++r)
    for (int c = 0; c + 1 < n; ++c) {
      const int i = r * n + c;
      tris.push_back({i, i + 1, i + n});
      tris.push_back({i + 1, i + n + 1, i + n});
    }
  p.surface = std::make_shared<const ClothSurface>(tris, p.nodes.size());
  std::uniform_real_distribution<double> in(-0.02, 0.12), off(-0.015, 0.015);
  for (int k = 0; k < 150; ++k)
    p.cloud.emplace_back(in(rng), off(rng), in(rng));
  p.cloud.emplace_back(0.05, 0.3, 0.05);  // an outlier
  return p;
}

// The squared distance from y to the patch's surface, trying every triangle.
double brute_surface_distance2(const Patch& p, const Vec3& y) {
  double best = HUGE_VAL;
  for (const auto& t : p.surface->triangles) {
    const Vec3 &a = p.nodes[t[0]], &b = p.nodes[t[1]], &c = p.nodes[t[2]];
    const auto w = nearest_on_triangle(y, a, b, c);
    best = std::min(best, (w[0] * a + w[1] * b + w[2] * c - y).squaredNorm());
  }
  return best;
}

TEST(Chamfer, TheNearestTriangleIsTheNearestOfAll) {
  const Patch p = wavy_patch(2);
  ChamferSettings s;
  s.one_sided = true;
  ChamferTarget target(p.cloud, p.surface, s);
  std::vector<Vec3> g;
  const double E = target.loss(p.nodes, g);
  double brute = 0;
  for (const Vec3& y : p.cloud)
    brute += 0.5 * brute_surface_distance2(p, y);
  EXPECT_NEAR(E, brute, 1e-15 * brute);
}

// The two-sided loss as chamfer.h writes it, every nearest found by trying
// them all: each observed point to its nearest point of every triangle, plus
// M / S times each sample (every node, every triangle's centroid) to its
// nearest observed point, each squared distance through rho.
double brute_force_two_sided(const Patch& p, const ChamferSettings& s) {
  double to_surface = 0;
  for (const Vec3& y : p.cloud)
    to_surface += 0.5 * robust_loss(s, brute_surface_distance2(p, y)).value;
  std::vector<Vec3> samples = p.nodes;
  for (const auto& t : p.surface->triangles)
    samples.push_back((p.nodes[t[0]] + p.nodes[t[1]] + p.nodes[t[2]]) / 3);
  double to_cloud = 0;
  for (const Vec3& q : samples) {
    double best = HUGE_VAL;
    for (const Vec3& y : p.cloud)
      best = std::min(best, (q - y).squaredNorm());
    to_cloud += robust_loss(s, best).value;
  }
  const double weight = double(p.cloud.size()) / double(samples.size());
  return to_surface + 0.5 * weight * to_cloud;
}

// Both terms against the brute force, plain and robust: the k-d trees find
// every nearest, and the cloth's samples are weighed by M / S.
TEST(Chamfer, TheTwoSidedLossIsTheBruteForceOne) {
  const Patch p = wavy_patch(4);
  for (RobustLoss l : {RobustLoss::none, RobustLoss::huber, RobustLoss::cauchy}) {
    ChamferSettings s;
    s.robust = l;
    s.scale = 0.005;
    ChamferTarget two_sided(p.cloud, p.surface, s);
    s.one_sided = true;
    ChamferTarget one_sided(p.cloud, p.surface, s);
    std::vector<Vec3> g;
    const double E = two_sided.loss(p.nodes, g);
    const double brute = brute_force_two_sided(p, s);
    const double cloth_term = E - one_sided.loss(p.nodes, g);
    std::printf("  %s: %.17g against %.17g, %.2g apart; the cloth's term %.2g of it\n",
                to_string(l), E, brute, std::abs(E - brute) / brute, cloth_term / E);
    // The cloth's term is no rounding of the whole, so the test sees it:
    // measured 0.12 (plain; the outlier's pull is most of the rest), 0.36
    // (Huber), 0.44 (Cauchy) of the loss.
    EXPECT_GT(cloth_term, 0.1 * E) << to_string(l);
    // Measured: the same bits, all three (the same sums in the same order);
    // bound a few ulp, as the one-sided test's.
    EXPECT_NEAR(E, brute, 1e-15 * brute) << to_string(l);
  }
}

void expect_gradient_is_differences(const ChamferSettings& s) {
  const Patch p = wavy_patch(3);
  ChamferTarget target(p.cloud, p.surface, s);
  std::vector<Vec3> g, unused;
  target.loss(p.nodes, g);
  const double eps = 1e-7;
  double largest = 0;
  for (const Vec3& v : g)
    largest = std::max(largest, v.cwiseAbs().maxCoeff());
  ASSERT_GT(largest, 0.0);
  double worst = 0;
  for (std::size_t i = 0; i < p.nodes.size(); ++i)
    for (int d = 0; d < 3; ++d) {
      std::vector<Vec3> up = p.nodes, down = p.nodes;
      up[i][d] += eps;
      down[i][d] -= eps;
      const double fd = (target.loss(up, unused) - target.loss(down, unused)) / (2 * eps);
      worst = std::max(worst, std::abs(fd - g[i][d]) / largest);
    }
  std::printf("  %s, %s: worst difference %.2g of the largest component\n",
              s.one_sided ? "one-sided" : "two-sided", to_string(s.robust), worst);
  // Measured: at most 1.0e-9 (Cauchy; the differences' own truncation and
  // rounding at eps 1e-7).
  EXPECT_LT(worst, 2e-9);
}

TEST(Chamfer, GradientEqualsDifferencesTwoSided) {
  expect_gradient_is_differences({});
}
TEST(Chamfer, GradientEqualsDifferencesOneSided) {
  ChamferSettings s;
  s.one_sided = true;
  expect_gradient_is_differences(s);
}
TEST(Chamfer, GradientEqualsDifferencesWithRobustLosses) {
  for (RobustLoss l : {RobustLoss::huber, RobustLoss::cauchy}) {
    ChamferSettings s;
    s.robust = l;
    s.scale = 0.005;
    expect_gradient_is_differences(s);
  }
}

TEST(Chamfer, ARobustLossPullsAnOutlierLess) {
  ChamferSettings plain, huber, cauchy;
  huber.robust = RobustLoss::huber;
  cauchy.robust = RobustLoss::cauchy;
  huber.scale = cauchy.scale = 0.01;
  // Below the scale the same square; far beyond it a pull (d rho / d d =
  // 2 d rho') of 2 scale (Huber) and falling (Cauchy).
  EXPECT_DOUBLE_EQ(robust_loss(huber, 1e-6).value, 1e-6);
  EXPECT_NEAR(robust_loss(cauchy, 1e-8).value, 1e-8, 1e-11);
  const double d = 1.0;
  EXPECT_DOUBLE_EQ(2 * d * robust_loss(plain, d * d).slope, 2.0);
  EXPECT_DOUBLE_EQ(2 * d * robust_loss(huber, d * d).slope, 0.02);
  EXPECT_LT(2 * d * robust_loss(cauchy, d * d).slope, 2.1e-4);
  RobustLoss parsed{};
  EXPECT_TRUE(parse_robust_loss("cauchy", parsed));
  EXPECT_EQ(parsed, RobustLoss::cauchy);
  EXPECT_FALSE(parse_robust_loss("tukey", parsed));
}

TEST(Chamfer, RefusesAnEmptyCloudOrAClothWithoutTriangles) {
  const Patch p = wavy_patch(1);
  EXPECT_THROW(ChamferTarget({}, p.surface, {}), std::invalid_argument);
  EXPECT_THROW(
      ChamferTarget(
          p.cloud,
          std::make_shared<const ClothSurface>(std::vector<std::array<std::int32_t, 3>>{}, 4), {}),
      std::invalid_argument);
}

}  // namespace
}  // namespace neurocloth
