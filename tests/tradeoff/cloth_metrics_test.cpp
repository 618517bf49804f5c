// The errors people see (cloth_metrics.h): distances between surfaces, the
// drape coefficient and fold count, checked on shapes whose answers are known
// by hand and against a brute-force search.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/geometry/nearest_on_triangle.h"
#include "support/test_support.h"
#include "tradeoff/cloth_metrics.h"

namespace neurocloth {
namespace {

// An n x n sheet of side `side` centred on the origin in the x-z plane at
// height y: positions and triangles.
struct Sheet {
  std::vector<double> x;
  Triangles triangles;
  std::size_t nodes() const { return x.size() / 3; }
};

Sheet sheet(int n, double side, double y = 0) {
  Sheet s;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      s.x.insert(s.x.end(), {-side / 2 + side * j / (n - 1), y, -side / 2 + side * i / (n - 1)});
  for (int i = 0; i + 1 < n; ++i)
    for (int j = 0; j + 1 < n; ++j) {
      const int a = i * n + j, b = a + 1, c = a + n, d = c + 1;
      s.triangles.push_back({a, b, d});
      s.triangles.push_back({a, d, c});
    }
  return s;
}

double brute_nearest(const Vec3& p, const std::vector<double>& x, const Triangles& triangles) {
  double best = INFINITY;
  auto at = [&](int i) { return Vec3(x[3 * i], x[3 * i + 1], x[3 * i + 2]); };
  for (const auto& t : triangles)
    best = std::min(best, point_triangle_distance(p, at(t[0]), at(t[1]), at(t[2])));
  return best;
}

// A sheet slid along itself by less than its spacing is the same surface: the
// node distance sees the slide, the surface distance does not.
TEST(SurfaceDistance, ASlideAlongTheSurfaceIsNoDistanceAMoveAcrossItIs) {
  const Sheet a = sheet(17, 1.0);
  Sheet slid = a, lifted = a;
  for (std::size_t i = 0; i < a.nodes(); ++i) {
    slid.x[3 * i] += 0.01;  // spacing 1/16
    lifted.x[3 * i + 1] += 0.002;
  }
  const SurfaceDistance s = surface_distance(a.x.data(), slid.x.data(), a.nodes(), a.triangles);
  // Only the edges that slid past each other's border are off (by up to the slide).
  EXPECT_LT(s.mean, 0.01 * 2 * 17 / 289.0 + 1e-12);
  EXPECT_NEAR(s.max, 0.01, 1e-12);
  const SurfaceDistance l = surface_distance(a.x.data(), lifted.x.data(), a.nodes(), a.triangles);
  EXPECT_NEAR(l.mean, 0.002, 1e-15);
  EXPECT_NEAR(l.max, 0.002, 1e-15);
  EXPECT_EQ(surface_distance(a.x.data(), a.x.data(), a.nodes(), a.triangles).max, 0);
}

// The grid's search against every triangle, on crumpled random cloths.
TEST(SurfaceDistance, TheGridFindsWhatABruteForceSearchFinds) {
  std::mt19937_64 rng(41);
  std::normal_distribution<double> noise(0, 0.05);
  for (int round = 0; round < 4; ++round) {
    Sheet a = sheet(12, 1.0), b = sheet(12, 1.0);
    for (double& v : a.x)
      v += noise(rng) * (round + 1);
    for (double& v : b.x)
      v += noise(rng) * (round + 1) + (round == 3 ? 3.0 : 0.0);  // the last far apart
    double sum = 0, max = 0;
    for (int pass = 0; pass < 2; ++pass) {
      const Sheet& from = pass ? b : a;
      const Sheet& to = pass ? a : b;
      for (std::size_t i = 0; i < from.nodes(); ++i) {
        const double d = brute_nearest(Vec3(from.x[3 * i], from.x[3 * i + 1], from.x[3 * i + 2]),
                                       to.x, to.triangles);
        sum += d;
        max = std::max(max, d);
      }
    }
    const SurfaceDistance s = surface_distance(a.x.data(), b.x.data(), a.nodes(), a.triangles);
    EXPECT_NEAR(s.mean, sum / (2 * a.nodes()), 1e-12) << round;
    EXPECT_DOUBLE_EQ(s.max, max) << round;
  }
}

// Coordinates near the double's range (a hostile or blown-up result): an
// answer, not a hang.
TEST(SurfaceDistance, CloudsAtTheEdgeOfTheDoublesRangeStillFinish) {
  Sheet a = sheet(6, 1.0), b = a;
  a.x[0] = -1e308;
  b.x[3] = 1e308;
  const SurfaceDistance s = surface_distance(a.x.data(), b.x.data(), a.nodes(), a.triangles);
  EXPECT_FALSE(std::isnan(s.max));
  EXPECT_GT(s.max, 1e307);
}

TEST(SurfaceDistance, NonFiniteIsNotMeasured) {
  Sheet a = sheet(4, 1.0), b = a;
  b.x[4] = NAN;
  EXPECT_TRUE(std::isnan(surface_distance(a.x.data(), b.x.data(), a.nodes(), a.triangles).mean));
}

DrapeSupport table(double half) {
  DrapeSupport s;
  s.shape = DrapeSupport::Shape::box;
  s.center = Vec3(0, -0.5, 0);
  s.half_extents = Vec3(half, 0.5, half);
  return s;
}

// The cloth outside a square table's edge folded down at `angle` from the
// horizontal, each axis on its own: its shadow is a square of half-width
// table + overhang * cos(angle).
Sheet draped(const Sheet& flat, double table_half, double angle) {
  Sheet s = flat;
  for (std::size_t i = 0; i < s.nodes(); ++i) {
    double drop = 0;
    for (int d : {0, 2}) {
      double& v = s.x[3 * i + d];
      const double over = std::abs(v) - table_half;
      if (over <= 0) continue;
      v = std::copysign(table_half + over * std::cos(angle), v);
      drop = std::max(drop, over * std::sin(angle));
    }
    s.x[3 * i + 1] -= drop;
  }
  return s;
}

// A 1.2 m cloth on a 0.8 m table, its overhang at 0, 60 and 90 degrees:
// the coefficient is ((0.8 + 0.4 cos)^2 - 0.64) / (1.44 - 0.64).
TEST(DrapeShape, TheCoefficientOfAFoldedSquareIsItsShadowsShare) {
  const Sheet flat = sheet(121, 1.2);
  const DrapeMeter meter(table(0.4), flat.x.data(), flat.nodes(), flat.triangles,
                         1.2 * std::sqrt(2));
  EXPECT_NEAR(meter.flat_outside_area(), 0.8, 0.004);
  for (double degrees : {0.0, 60.0, 90.0}) {
    const double angle = degrees * kPi / 180;
    const Sheet d = draped(flat, 0.4, angle);
    const double side = 0.8 + 0.4 * std::cos(angle);
    const double expected = (side * side - 0.64) / 0.8;
    EXPECT_NEAR(meter.measure(d.x.data()).coefficient, expected, 0.004) << degrees;
  }
}

// A flat square's outline has four corners: four peaks around its centre.
TEST(DrapeShape, AFlatSquareHasFourCorners) {
  const Sheet flat = sheet(41, 1.2);
  const DrapeMeter meter(table(0.4), flat.x.data(), flat.nodes(), flat.triangles, 1.7);
  EXPECT_EQ(meter.measure(flat.x.data()).folds, 4);
}

// A disc whose rim waves k times (r = R (1 + 0.12 cos k theta)), as a drape
// tester's specimen with k nodes: k folds.
TEST(DrapeShape, TheFoldCountIsTheNodesOfAWavingRim) {
  for (int k : {5, 6, 7, 9}) {
    const int rings = 20, sectors = 360;
    Sheet s;
    s.x = {0, 0, 0};
    for (int r = 1; r <= rings; ++r)
      for (int q = 0; q < sectors; ++q) {
        const double theta = 2 * kPi * q / sectors;
        const double radius = 0.5 * r / rings * (1 + 0.12 * std::cos(k * theta));
        s.x.insert(s.x.end(), {radius * std::cos(theta), 0, radius * std::sin(theta)});
      }
    auto node = [&](int r, int q) { return r == 0 ? 0 : 1 + (r - 1) * sectors + q % sectors; };
    for (int r = 0; r < rings; ++r)
      for (int q = 0; q < sectors; ++q) {
        s.triangles.push_back({node(r, q), node(r + 1, q), node(r + 1, q + 1)});
        if (r > 0) s.triangles.push_back({node(r, q), node(r + 1, q + 1), node(r, q + 1)});
      }
    DrapeSupport disc;
    disc.shape = DrapeSupport::Shape::sphere;
    disc.center = Vec3(0, -0.2, 0);
    disc.radius = 0.15;
    const DrapeMeter meter(disc, s.x.data(), s.nodes(), s.triangles, 1.0);
    const DrapeShape d = meter.measure(s.x.data());
    EXPECT_EQ(d.folds, k);
    EXPECT_NEAR(d.coefficient, 1, 1e-12);
  }
}

TEST(DrapeShape, AClothWithinItsSupportsFootprintHasNoCoefficient) {
  const Sheet small = sheet(9, 0.5);
  EXPECT_THROW(DrapeMeter(table(0.4), small.x.data(), small.nodes(), small.triangles, 0.7),
               std::invalid_argument);
}

TEST(DrapeShape, TheSupportIsTheScenesFirstBoxOrSphereSeenAlongGravity) {
  const std::optional<DrapeSupport> s = drape_support(test::asset_scene("table_drape"));
  ASSERT_TRUE(s);
  EXPECT_EQ(s->shape, DrapeSupport::Shape::box);
  EXPECT_TRUE(s->covers(Vec3(0.39, 5, -0.39)));
  EXPECT_FALSE(s->covers(Vec3(0.41, 5, 0)));
  EXPECT_FALSE(drape_support(test::asset_scene("hanging")));
  DrapeSupport ball;
  ball.shape = DrapeSupport::Shape::sphere;
  ball.radius = 1;
  EXPECT_TRUE(ball.covers(Vec3(0.99, -7, 0)));
  EXPECT_FALSE(ball.covers(Vec3(0.8, 3, 0.8)));
}

// On the scene: its flat start drapes at 1, every metric of a state against
// itself is 0, and a scene without a support has no drape to compare.
TEST(ClothMetrics, AStateAgainstItselfIsNothingOnEveryMetric) {
  const Scene scene = test::asset_scene("table_drape");
  const MetricContext c = metric_context(scene);
  ASSERT_TRUE(c.drape);
  EXPECT_NEAR(c.size, std::sqrt(2.0) * 31 * 0.0387, 1e-9);
  std::vector<double> x;
  for (const Vec3& p : scene.topology.rest_positions)
    x.insert(x.end(), {p.x(), p.y(), p.z()});
  const FrameShape f = frame_shape(x.data(), c);
  EXPECT_DOUBLE_EQ(f.drape, 1);
  EXPECT_EQ(f.folds, 4);
  EXPECT_NEAR(f.strain_max, 0, 1e-12);
  const MetricValues v = compare_frames(x.data(), f, 3, x.data(), f, 3, c);
  for (Metric m : kAllMetrics)
    EXPECT_EQ(v[slot(m)], 0) << to_string(m);
  const MetricContext hanging = metric_context(test::asset_scene("hanging"));
  EXPECT_FALSE(hanging.drape);
  std::vector<double> y(3 * hanging.nodes, 0.5);
  const FrameShape g = frame_shape(y.data(), hanging);
  EXPECT_TRUE(std::isnan(g.drape));
  EXPECT_EQ(g.folds, -1);
  EXPECT_TRUE(
      std::isnan(compare_frames(y.data(), g, 0, y.data(), g, 0, hanging)[slot(Metric::drape)]));
}

// Over a run: the worst sample time, the RMS over all of them.
TEST(ClothMetrics, ARunsErrorIsItsWorstTimeAndItsRmsOverAll) {
  const Scene scene = test::asset_scene("hanging");
  const MetricContext c = metric_context(scene);
  Trajectory a, b;
  for (int j = 0; j < 2; ++j) {
    std::vector<double> x;
    for (const Vec3& p : scene.topology.rest_positions)
      x.insert(x.end(), {p.x(), p.y(), p.z()});
    std::vector<double> y = x;
    for (std::size_t i = 0; i < c.nodes; ++i)
      y[3 * i + 2] += (j + 1) * 0.01 * c.size;  // 1%, then 2% across the sheet
    a.positions.push_back(x);
    b.positions.push_back(y);
    a.energy.push_back(1);
    b.energy.push_back(1 + j * c.energy_scale * 0.5);
    a.shapes.push_back(frame_shape(x.data(), c));
    b.shapes.push_back(frame_shape(y.data(), c));
  }
  const MetricComparison m = compare_trajectories(a, b, c);
  EXPECT_NEAR(m.run[slot(Metric::node_max)], 0.02, 1e-12);
  EXPECT_NEAR(m.run[slot(Metric::node_rms)], std::sqrt((0.01 * 0.01 + 0.02 * 0.02) / 2), 1e-12);
  EXPECT_NEAR(m.by_sample[0][slot(Metric::node_max)], 0.01, 1e-12);
  EXPECT_NEAR(m.run[slot(Metric::energy)], 0.5, 1e-12);
  b.positions.pop_back();
  EXPECT_THROW(compare_trajectories(a, b, c), std::invalid_argument);
}

TEST(ClothMetrics, NamesReadBackAndUnknownOnesDoNot) {
  for (Metric m : kAllMetrics)
    EXPECT_EQ(parse_metric(to_string(m)), m);
  EXPECT_FALSE(parse_metric("surface"));
  EXPECT_NE(metric_names().find("surface_mean"), std::string::npos);
}

}  // namespace
}  // namespace neurocloth
