// The drape meter over a cylinder, a drape tester's support (ISO 9073-9):
// what the cylinder covers seen along gravity, the support a scene gives, and
// the coefficient of a disc specimen whose overhang is folded down by hand
// against its formula, at three resolutions. (The box and sphere supports' checks are in
// cloth_metrics_test.cpp, beside the metrics they feed.)
#include "tradeoff/drape_shape.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

#include "core/scene/disc_builder.h"
#include "support/scene_builder.h"
#include "support/test_support.h"

namespace neurocloth::drape_shape_test {

DrapeSupport cylinder(const Vec3& center, const Vec3& axis, double radius, double height) {
  DrapeSupport s;
  s.shape = DrapeSupport::Shape::cylinder;
  s.center = center;
  s.axis = axis.normalized();
  s.radius = radius;
  s.height = height;
  return s;
}

// Whether the vertical line through p meets the solid, by walking down it.
bool walked_cover(const DrapeSupport& s, const Vec3& p) {
  for (double t = -1; t <= 1; t += 2.5e-4) {
    const Vec3 d = p + t * s.up - s.center;
    const double along = d.dot(s.axis);
    if (std::abs(along) <= 0.5 * s.height && (d - along * s.axis).norm() <= s.radius) return true;
  }
  return false;
}

// Upright, it covers its disc at any height; lying or tilted, what a walk
// down the vertical line finds (a point within a millimetre of the outline is
// left out: the walk's own steps blur it).
TEST(DrapeShapeCylinder, CoversItsFootprintSeenAlongGravity) {
  const DrapeSupport post = cylinder(Vec3(0.1, 0.5, -0.2), Vec3(0, 1, 0), 0.09, 0.2);
  EXPECT_TRUE(post.covers(Vec3(0.1 + 0.089, 7, -0.2)));
  EXPECT_TRUE(post.covers(Vec3(0.1 + 0.06, -3, -0.2 + 0.06)));
  EXPECT_FALSE(post.covers(Vec3(0.1 + 0.091, 0.5, -0.2)));
  EXPECT_FALSE(post.covers(Vec3(0.1 + 0.07, 0.5, -0.2 + 0.07)));

  std::mt19937_64 rng(5058);
  std::uniform_real_distribution<double> u(-0.3, 0.3);
  for (const Vec3& axis : {Vec3(1, 0, 0), Vec3(0.3, 1, -0.2), Vec3(1, 0.4, 0.5)}) {
    const DrapeSupport s = cylinder(Vec3(0, 0.3, 0), axis, 0.1, 0.4);
    int covered = 0, checked = 0;
    for (int n = 0; n < 150; ++n) {
      const Vec3 p(u(rng), u(rng), u(rng));
      const bool walked = walked_cover(s, p);
      // Near the outline: moving 1 mm changes the walk's answer.
      const bool near_outline = walked != walked_cover(s, p + Vec3(1e-3, 0, 0)) ||
                                walked != walked_cover(s, p - Vec3(1e-3, 0, 0)) ||
                                walked != walked_cover(s, p + Vec3(0, 0, 1e-3)) ||
                                walked != walked_cover(s, p - Vec3(0, 0, 1e-3));
      if (near_outline) continue;
      ++checked;
      covered += walked;
      EXPECT_EQ(s.covers(p), walked) << axis.transpose() << " at " << p.transpose();
    }
    EXPECT_GT(covered, 10) << axis.transpose();
    EXPECT_GT(checked - covered, 10) << axis.transpose();
  }
}

TEST(DrapeShapeCylinder, TheScenesFirstSupportMayBeACylinder) {
  test::SceneBuilder b(2, 2, 0.1);
  b.disc(0.15, 6, Vec3(0, 0.205, 0))
      .module({{"type", "plane"}, {"point", {0, -1, 0}}})
      .module({{"type", "cylinder"},
               {"center", {0, 0.1, 0}},
               {"axis", {0, 1, 0}},
               {"radius", 0.09},
               {"height", 0.2}})
      .module({{"type", "sphere"}, {"center", {0, -0.5, 0}}, {"radius", 0.3}});
  const std::optional<DrapeSupport> s = drape_support(b.parse());
  ASSERT_TRUE(s);
  EXPECT_EQ(s->shape, DrapeSupport::Shape::cylinder);
  EXPECT_STREQ(to_string(s->shape), "cylinder");
  EXPECT_EQ(s->center, Vec3(0, 0.1, 0));
  EXPECT_EQ(s->radius, 0.09);
  EXPECT_EQ(s->height, 0.2);
  // Without gravity there is no "seen from above".
  EXPECT_FALSE(drape_support(b.gravity(Vec3::Zero()).parse()));
}

// A 30 cm disc on an 18 cm support, its overhang folded down at an angle a
// into a cone: the shadow outside the support is the ring out to
// r + (R - r) cos a, so the coefficient is ((r + (R - r) cos a)^2 - r^2) /
// (R^2 - r^2), at every resolution of the disc within the raster's and the
// outline's error (a 72-gon is 0.13% short of the circle's area, the overhang
// ring 0.2%); the flat disc's outline is round: no nodes.
TEST(DrapeShapeCylinder, TheCoefficientOfAFoldedDiscIsItsShadowsShareAtAnyResolution) {
  const double R = 0.15, r = 0.09;
  const DrapeSupport support = cylinder(Vec3(0, 0.1, 0), Vec3(0, 1, 0), r, 0.2);
  for (const int rings : {12, 18, 24}) {
    DiscSpec spec;
    spec.radius = R;
    spec.rings = rings;
    spec.center = Vec3(0, 0.205, 0);
    const ClothTopology t = build_disc(spec);
    std::vector<double> flat;
    for (const Vec3& p : t.rest_positions)
      flat.insert(flat.end(), {p.x(), p.y(), p.z()});
    const std::size_t nodes = t.rest_positions.size();
    const DrapeMeter meter(support, flat.data(), nodes, t.triangles, 2 * R);
    const double ring = kPi * (R * R - r * r);
    EXPECT_NEAR(meter.flat_outside_area(), ring, 0.004 * ring) << rings;
    const DrapeShape still = meter.measure(flat.data());
    EXPECT_NEAR(still.coefficient, 1, 1e-12) << rings;
    EXPECT_EQ(still.folds, 0) << rings;
    for (double degrees : {30.0, 60.0, 80.0}) {
      const double a = degrees * kPi / 180;
      std::vector<double> folded = flat;
      for (std::size_t i = 0; i < nodes; ++i) {
        const double x = flat[3 * i], z = flat[3 * i + 2], rho = std::hypot(x, z);
        if (rho <= r) continue;
        const double over = rho - r, out = r + over * std::cos(a);
        folded[3 * i] = x * out / rho;
        folded[3 * i + 1] -= over * std::sin(a);
        folded[3 * i + 2] = z * out / rho;
      }
      const double out = r + (R - r) * std::cos(a);
      const double expected = (out * out - r * r) / (R * R - r * r);
      EXPECT_NEAR(meter.measure(folded.data()).coefficient, expected, 0.005)
          << rings << " rings, " << degrees << " degrees";
    }
  }
}

// The scene's meter: its flat start is the reference, a ClothState measures
// as its positions do, and its line says what it found.
TEST(DrapeShapeCylinder, TheScenesMeterMeasuresItsStartAsFlat) {
  test::SceneBuilder b(2, 2, 0.1);
  b.disc(0.15, 12, Vec3(0, 0.205, 0))
      .module({{"type", "cylinder"}, {"center", {0, 0.1, 0}}, {"radius", 0.09}, {"height", 0.2}});
  const Scene scene = b.parse();
  const std::shared_ptr<const DrapeMeter> meter = scene_drape_meter(scene);
  ASSERT_TRUE(meter);
  EXPECT_EQ(meter->node_count(), scene.topology.rest_positions.size());
  const ClothState start = scene.initial_state();
  const DrapeShape d = meter->measure(start);
  EXPECT_NEAR(d.coefficient, 1, 1e-12);
  EXPECT_EQ(d.folds, 0);
  EXPECT_EQ(describe(d, meter->support()), "drape coefficient 1.000, 0 nodes over the cylinder");
  EXPECT_THROW(meter->measure(ClothState(3)), std::invalid_argument);
  DrapeShape seven;
  seven.coefficient = 0.6249;
  seven.folds = 7;
  EXPECT_EQ(describe(seven, meter->support()),
            "drape coefficient 0.625, 7 nodes over the cylinder");

  // No support, or a support wider than the cloth: no meter.
  EXPECT_FALSE(scene_drape_meter(test::asset_scene("hanging")));
  test::SceneBuilder wide(2, 2, 0.1);
  wide.disc(0.15, 6, Vec3(0, 0.205, 0))
      .module({{"type", "cylinder"}, {"center", {0, 0.1, 0}}, {"radius", 0.2}, {"height", 0.2}});
  EXPECT_FALSE(scene_drape_meter(wide.parse()));
}

}  // namespace neurocloth::drape_shape_test
