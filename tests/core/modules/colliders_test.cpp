// Colliders (plane, box, sphere, capsule): nodes stay outside, friction sticks
// and slides where Coulomb says, fast nodes do not tunnel, pins are left alone.
// Scenes come from the test scene builder and are read by parse_scene, as a
// user's scene file would be; distances are measured with this file's own geometry.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <random>
#include <string>
#include <variant>
#include <vector>

#include "core/modules/collider_shapes.h"
#include "core/modules/module_factories.h"
#include "core/scene/scene.h"
#include "support/scene_builder.h"
#include "support/test_support.h"

namespace neurocloth {
namespace {

constexpr double kG = 9.81;
constexpr double kDefaultThickness = 0.005;  // the default
constexpr double kSlack = 1e-9;              // "outside" allows this much round-off

using test::SceneBuilder;
using Json = SceneBuilder::Json;

Json xyz(const Vec3& v) {
  return {v.x(), v.y(), v.z()};
}

// An n x n sheet of cotton, `width` wide, level at `height`, centred over the origin.
SceneBuilder sheet(int n, double width, double height) {
  return SceneBuilder(n, n, width / (n - 1))
      .name("sheet")
      .origin(Vec3(-width / 2, height, -width / 2))
      .material(100.0, 0.01, 0.1)
      .friction(0.3);
}

// One free node with no springs: what the friction law acts on undisturbed.
SceneBuilder free_node(const Vec3& p, double friction, const std::string& integrator = "network",
                       double dt = 0.01) {
  return SceneBuilder(1, 1, 0.1)
      .name("node")
      .origin(p)
      .springs({})
      .material(0.0, 0.1, 0.0)
      .friction(friction)
      .solver(integrator, dt);
}

Simulation simulate(const SceneBuilder& scene) {
  return scene.parse().make_simulation();
}

// Signed distances, written independently of the module.
double box_distance(const Vec3& p, const Vec3& center, const Vec3& size) {
  const Vec3 q = (p - center).cwiseAbs() - 0.5 * size;
  return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);
}
double segment_distance(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (p - a - t * ab).norm();
}

using Distance = std::function<double(const Vec3&)>;

// Runs `seconds` in slices; after each, no free node is closer than the
// thickness to the solid.
void run_outside(Simulation& sim, double seconds, double slice, const Distance& distance) {
  for (double t = 0; t < seconds - 1e-9; t += slice) {
    EXPECT_EQ(sim.advance(slice), RunStatus::ok) << sim.divergence_reason();
    const ClothState& s = sim.state();
    for (std::size_t i = 0; i < s.size(); ++i) {
      if (sim.network().masses.pinned(i)) continue;
      const double d = distance(s.position(i));
      if (d < kDefaultThickness - kSlack) {
        ADD_FAILURE() << "node " << i << " at t=" << sim.time() << " is " << d
                      << " m from the surface, inside the thickness " << kDefaultThickness;
        return;
      }
    }
  }
}

// The free node nearest the solid: within a millimetre of the thickness when
// the cloth rests on it.
double nearest(const Simulation& sim, const Distance& distance) {
  double least = INFINITY;
  for (std::size_t i = 0; i < sim.state().size(); ++i)
    if (!sim.network().masses.pinned(i)) least = std::min(least, distance(sim.state().position(i)));
  return least;
}

TEST(ColliderModules, ContactPhaseNoStateAndTypeNames) {
  std::vector<std::unique_ptr<ConstraintModule>> all;
  all.push_back(make_collider(PlaneSpec{}));
  all.push_back(make_collider(BoxSpec{}));
  all.push_back(make_collider(SphereSpec{}));
  all.push_back(make_collider(CapsuleSpec{}));
  const char* names[] = {"plane", "box", "sphere", "capsule"};
  for (std::size_t k = 0; k < all.size(); ++k) {
    EXPECT_STREQ(all[k]->type(), names[k]);
    EXPECT_EQ(all[k]->phase(), ConstraintModule::contact);
    EXPECT_EQ(all[k]->state_bytes(), 0u);
  }
}

TEST(ColliderModules, SceneBuildsEveryColliderAndRunsIt) {
  Simulation sim = simulate(sheet(4, 0.3, 2.0).solver("network", 0.01).modules(R"([
      { "type": "plane", "point": [0, -5, 0] },
      { "type": "box", "center": [0, -5, 0], "size": [1, 1, 1] },
      { "type": "sphere", "center": [0, -5, 0], "radius": 1 },
      { "type": "capsule", "a": [0, -5, 0], "b": [1, -5, 0], "radius": 1 }])"));
  sim.advance(0.05);
  const auto reports = sim.module_reports();
  ASSERT_EQ(reports.size(), 4u);
  const char* names[] = {"plane", "box", "sphere", "capsule"};
  for (std::size_t k = 0; k < 4; ++k) {
    EXPECT_EQ(reports[k].type, names[k]);
    EXPECT_EQ(reports[k].calls, 5);
    EXPECT_EQ(reports[k].state_bytes, 0u);
  }
}

// A collider the cloth never reaches changes nothing, to the bit.
TEST(ColliderModules, UnreachedColliderChangesNothing) {
  SceneBuilder scene = sheet(6, 0.5, 1.0).solver("network", 0.005).pins({{0, 0}, {0, 5}});
  Simulation bare = simulate(scene);
  Simulation far = simulate(scene.module({{"type", "plane"}, {"point", {0, -50, 0}}}));
  bare.advance(0.5);
  far.advance(0.5);
  ASSERT_EQ(far.module_reports().size(), 1u);
  EXPECT_EQ(far.module_reports()[0].calls, 100);
  EXPECT_EQ(test::state_hash(bare.state()), test::state_hash(far.state()));
}

// The paper's table drape (the shipped scene, on a coarser grid with a middle
// node): the cloth falls on a table (a box) and hangs over its edges.
TEST(ColliderDrape, TableDrapeRestsOnTopAndHangsOverTheEdges) {
  const int n = 17;
  const Scene scene = resized_grid(test::asset_scene("table_drape"), n);
  const auto& box = std::get<BoxSpec>(scene.modules.at(0).spec);
  ASSERT_EQ(box.contact.thickness, kDefaultThickness);
  const double top = box.center.y() + box.half_extents.y();
  Simulation sim = scene.make_simulation();
  run_outside(sim, 3.0, 0.1,
              [&](const Vec3& p) { return box_distance(p, box.center, 2 * box.half_extents); });
  const ClothState& s = sim.state();
  const std::size_t middle = (n / 2) * n + n / 2;
  EXPECT_NEAR(s.y[middle], top + kDefaultThickness, 3 * kDefaultThickness);
  EXPECT_NEAR(s.x[middle], 0.0, 0.01);
  EXPECT_NEAR(s.z[middle], 0.0, 0.01);
  for (std::size_t corner :
       {std::size_t{0}, std::size_t(n - 1), std::size_t(n * (n - 1)), std::size_t(n * n - 1)})
    EXPECT_LT(s.y[corner], top - 0.1) << "corner " << corner << " does not hang";
}

TEST(ColliderDrape, ClothFallsOverASphere) {
  const Vec3 c(0, 0.3, 0);
  const double r = 0.25;
  const int n = 16;
  Simulation sim = simulate(sheet(n, 1.0, 0.7)
                                .solver("network", 0.02, true)
                                .module({{"type", "sphere"}, {"center", xyz(c)}, {"radius", r}}));
  const Distance distance = [&](const Vec3& p) { return (p - c).norm() - r; };
  run_outside(sim, 2.0, 0.1, distance);
  EXPECT_LT(nearest(sim, distance), kDefaultThickness + 1e-3)
      << "the cloth does not rest on the sphere";
  const ClothState& s = sim.state();
  EXPECT_GT(*std::max_element(s.y.begin(), s.y.end()), c.y() + 0.9 * r) << "it fell off";
  EXPECT_LT(s.y[0], c.y()) << "the corner does not hang";
}

// A towel over a bar: a capsule along x holds the middle, both halves hang.
TEST(ColliderDrape, ClothFoldsOverACapsuleBar) {
  const Vec3 a(-0.7, 0.3, 0), b(0.7, 0.3, 0);
  const double r = 0.05;
  const int n = 16;
  Simulation sim =
      simulate(sheet(n, 1.0, 0.45)
                   .solver("network", 0.02, true)
                   .module({{"type", "capsule"}, {"a", xyz(a)}, {"b", xyz(b)}, {"radius", r}}));
  const Distance distance = [&](const Vec3& p) { return segment_distance(p, a, b) - r; };
  run_outside(sim, 2.0, 0.1, distance);
  EXPECT_LT(nearest(sim, distance), kDefaultThickness + 1e-3)
      << "the cloth does not rest on the bar";
  const ClothState& s = sim.state();
  for (int col = 0; col < n; ++col) {
    EXPECT_LT(s.y[col], 0.3 - 0.2) << "first row, column " << col;
    EXPECT_LT(s.y[(n - 1) * n + col], 0.3 - 0.2) << "last row, column " << col;
  }
}

// A cloth falls flat onto a tilted floor with high friction and lies on it.
TEST(ColliderDrape, ClothLandsOnAPlaneAndLiesOnIt) {
  const Vec3 normal = Vec3(0.1, 1, 0).normalized();
  Simulation sim =
      simulate(sheet(10, 0.5, 0.2)
                   .solver("network", 0.02, true)
                   .module({{"type", "plane"}, {"normal", {0.1, 1, 0}}, {"friction", 0.8}}));
  run_outside(sim, 1.5, 0.1, [&](const Vec3& p) { return normal.dot(p); });
  const ClothState& s = sim.state();
  for (std::size_t i = 0; i < s.size(); ++i)
    EXPECT_NEAR(normal.dot(s.position(i)), kDefaultThickness, 1e-3) << "node " << i;
}

// The same drop onto a sphere with the other integrators. (Explicit Euler is
// left out: this cloth diverges with it even with no collider.)
class ColliderIntegrators : public ::testing::TestWithParam<const char*> {};

TEST_P(ColliderIntegrators, KeepNodesOutsideASphere) {
  const Vec3 c(0, 0, 0);
  const double r = 0.2;
  Simulation sim =
      simulate(sheet(8, 0.6, 0.3)
                   .solver(GetParam(), 0.02, true)
                   .module({{"type", "sphere"}, {"center", {0, 0, 0}}, {"radius", r}}));
  const Distance distance = [&](const Vec3& p) { return (p - c).norm() - r; };
  run_outside(sim, 1.5, 0.1, distance);
  EXPECT_LT(nearest(sim, distance), kDefaultThickness + 1e-3)
      << "the cloth does not rest on the sphere";
  const ClothState& s = sim.state();
  EXPECT_GT(*std::max_element(s.y.begin(), s.y.end()), 0.9 * r) << "it fell off";
  EXPECT_LT(sim.energy().kinetic, 0.05) << "not settling";
}

INSTANTIATE_TEST_SUITE_P(Colliders, ColliderIntegrators,
                         ::testing::Values("network", "verlet", "rk4", "implicit_euler"));

// A node at rest on a plane through the origin tilted by theta (tan theta =
// `slope`), just touching it; returns the node after `seconds`.
struct Slide {
  double along;  // displacement along the slope, m (downhill negative)
  double speed;  // velocity along the slope, m/s (downhill negative)
  double off;    // distance from the plane minus the thickness, m
};

// `contact_keys`: the plane's own friction keys, if any.
Slide slide(double slope, double material_friction, const Json& contact_keys,
            const char* integrator = "network", double seconds = 1.0) {
  const double theta = std::atan(slope);
  const Vec3 n(-std::sin(theta), std::cos(theta), 0), t(std::cos(theta), std::sin(theta), 0);
  const Vec3 start = kDefaultThickness * n;
  Json plane = {{"type", "plane"}, {"point", {0, 0, 0}}, {"normal", xyz(n)}};
  plane.update(contact_keys);
  Simulation sim = simulate(free_node(start, material_friction, integrator).module(plane));
  EXPECT_EQ(sim.advance(seconds), RunStatus::ok);
  const Vec3 p = sim.state().position(0);
  return {(p - start).dot(t), sim.state().velocity(0).dot(t), n.dot(p) - kDefaultThickness};
}

double sliding_acceleration(double slope, double mu) {
  const double theta = std::atan(slope);
  return kG * (std::sin(theta) - mu * std::cos(theta));
}

class ColliderFriction : public ::testing::TestWithParam<const char*> {};

TEST_P(ColliderFriction, SticksBelowTheCoulombAngle) {
  const Slide s = slide(0.9 * 0.3, 0.0, {{"friction", 0.3}}, GetParam());
  EXPECT_LT(std::abs(s.along), 1e-9);
  EXPECT_LT(std::abs(s.speed), 1e-9);
  EXPECT_LT(std::abs(s.off), 1e-9);
}

TEST_P(ColliderFriction, SlidesAboveItWithCoulombAcceleration) {
  const double slope = 1.1 * 0.3, T = 1.0;
  const Slide s = slide(slope, 0.0, {{"friction", 0.3}}, GetParam(), T);
  const double a = sliding_acceleration(slope, 0.3);
  EXPECT_NEAR(-s.speed / T, a, 0.02 * a);
  EXPECT_LT(std::abs(s.off), 1e-9) << "the node leaves the plane";
  // It moves as far as its velocity says, within the integrator's own error in
  // the distance a step covers (at this dt explicit Euler falls 16% short,
  // verlet and rk4 7%; the network's semi-implicit Euler is 1% long).
  EXPECT_NEAR(-s.along, 0.5 * a * T * T, 0.25 * 0.5 * a * T * T);
  if (std::string(GetParam()) == "network") {
    EXPECT_NEAR(-s.along, 0.5 * a * T * T, 0.02 * 0.5 * a * T * T);
  }
}

INSTANTIATE_TEST_SUITE_P(Colliders, ColliderFriction,
                         ::testing::Values("network", "explicit_euler", "verlet", "rk4",
                                           "implicit_euler"));

// Between the kinetic and the static coefficient a node at rest stays; above
// the static one it slides, braked by the kinetic one.
TEST(ColliderStaticFriction, ThresholdIsTheStaticCoefficient) {
  const Json keys = {{"friction", 0.3}, {"static_friction", 0.45}};
  EXPECT_LT(std::abs(slide(0.4, 0.0, keys).along), 1e-9);
  EXPECT_GT(-slide(0.4, 0.0, {{"friction", 0.3}}).along, 0.1) << "no static friction: slides";
  const Slide s = slide(0.5, 0.0, keys);
  const double a = sliding_acceleration(0.5, 0.3);
  EXPECT_NEAR(-s.speed, a, 0.02 * a);
}

// Unset, the coefficients are the node's material friction.
TEST(ColliderStaticFriction, DefaultsToTheMaterialFriction) {
  EXPECT_LT(std::abs(slide(0.27, 0.3, Json::object()).along), 1e-9);
  const Slide s = slide(0.27, 0.2, Json::object());
  const double a = sliding_acceleration(0.27, 0.2);
  EXPECT_NEAR(-s.speed, a, 0.02 * a);
  // The collider's own coefficient wins over the material's.
  EXPECT_LT(std::abs(slide(0.27, 0.2, {{"friction", 0.3}}).along), 1e-9);
  EXPECT_GT(-slide(0.27, 0.3, {{"friction", 0.2}}).along, 0.1);
}

// A node with a given start and velocity, one step at a time.
Simulation fast_node(const Vec3& p, const Vec3& v, const Json& collider,
                     const char* integrator = "network") {
  Simulation sim = simulate(free_node(p, 0.3, integrator, 0.04).module(collider));
  ClothState s = sim.state();
  s.set_velocity(0, v);
  sim.set_state(s);
  return sim;
}

const Json kTable = {{"type", "box"}, {"center", {0, 0.375, 0}}, {"size", {0.8, 0.75, 0.8}}};

// The box's branch-free case (the block scan's) gives contact()'s bits where
// it claims a node, and claims the nodes resting on a face, not those whose
// step may have crossed the box or that sit off an edge or a corner.
TEST(ColliderBox, TheBranchFreeFaceContactIsTheExactOne) {
  BoxSpec spec;
  spec.center = Vec3(0.1, 0.375, -0.05);
  spec.half_extents = Vec3(0.4, 0.375, 0.3);
  const collider_shapes::BoxShape box(spec);
  std::mt19937_64 rng(27);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int claimed = 0, checked = 0;
  for (int n = 0; n < 200000; ++n) {
    // Ends anywhere within 1.5 half extents of the centre (inside, on faces,
    // off edges and corners); starts a small step away, or anywhere (a fast
    // node that may have crossed the box).
    Vec3 end, start;
    for (int k = 0; k < 3; ++k)
      end[k] = spec.center[k] + 1.5 * spec.half_extents[k] * u(rng);
    const double reach = n % 4 == 0 ? 1.0 : 0.02;
    for (int k = 0; k < 3; ++k)
      start[k] = end[k] + reach * u(rng);
    double phi = 0, nx = 0, ny = 0, nz = 0;
    const bool simple = box.face_contact(start.x(), start.y(), start.z(), end.x(), end.y(), end.z(),
                                         phi, nx, ny, nz);
    const collider_shapes::Contact c = box.contact(end, start);
    ++checked;
    if (!simple) continue;
    ++claimed;
    ASSERT_EQ(phi, c.phi) << n;
    ASSERT_EQ(nx, c.normal.x()) << n;
    ASSERT_EQ(ny, c.normal.y()) << n;
    ASSERT_EQ(nz, c.normal.z()) << n;
    ASSERT_GT(phi, 0.0) << n;  // only ever outside, on one face
  }
  // The face's common case is claimed: 76,970 of the 200,000 steps (38.5%) with
  // this seed, nearly every node outside one pair of faces whose step stayed
  // beyond it.
  EXPECT_GE(claimed, checked * 38 / 100);
  double phi = 0, nx = 0, ny = 0, nz = 0;
  const Vec3 top = spec.center + Vec3(0, spec.half_extents.y() + 0.001, 0);
  EXPECT_TRUE(box.face_contact(top.x(), top.y() + 0.01, top.z(), top.x(), top.y(), top.z(), phi, nx,
                               ny, nz));
  EXPECT_EQ(ny, 1.0);
  // Landed under the top from above it: left to contact(), which sends it back up.
  const Vec3 under = spec.center - Vec3(0, spec.half_extents.y() + 0.001, 0);
  EXPECT_FALSE(box.face_contact(top.x(), top.y(), top.z(), under.x(), under.y(), under.z(), phi, nx,
                                ny, nz));
  // Off an edge (outside two pairs of faces): contact() measures to the edge.
  const Vec3 edge = spec.center + spec.half_extents + Vec3(0.01, 0.01, -0.1);
  EXPECT_FALSE(box.face_contact(edge.x(), edge.y(), edge.z(), edge.x(), edge.y(), edge.z(), phi, nx,
                                ny, nz));
}

// Falling at 10 m/s the node is 0.4 m deep after one step, deeper below the top
// than inside the nearest side: it must still come out on top.
TEST(ColliderTunnelling, FastNodeLandsOnTheBoxTop) {
  for (const char* integrator : {"network", "rk4"})
    for (const Vec3& xz :
         {Vec3(0, 0, 0), Vec3(0.37, 0, 0), Vec3(-0.38, 0, 0.2), Vec3(0.39, 0, -0.39)}) {
      Simulation sim = fast_node(xz + Vec3(0, 0.8, 0), Vec3(0, -10, 0), kTable, integrator);
      sim.advance(0.04);
      EXPECT_NEAR(sim.state().y[0], 0.75 + kDefaultThickness, 1e-12)
          << integrator << " at " << xz.transpose();
      sim.advance(0.96);
      const Vec3 p = sim.state().position(0);
      EXPECT_NEAR(p.y(), 0.75 + kDefaultThickness, 1e-12) << integrator << " at " << xz.transpose();
      EXPECT_NEAR(p.x(), xz.x(), 1e-12);
      EXPECT_NEAR(p.z(), xz.z(), 1e-12);
    }
}

// A step longer than the box is thick ends beyond it: the node goes back on top.
TEST(ColliderTunnelling, FastNodeDoesNotCrossAThinBox) {
  Simulation sim = fast_node(Vec3(0.1, 0.6, 0), Vec3(0, -10, 0),
                             {{"type", "box"}, {"center", {0, 0.5, 0}}, {"size", {1, 0.02, 1}}});
  sim.advance(0.04);
  EXPECT_NEAR(sim.state().y[0], 0.51 + kDefaultThickness, 1e-12);
  sim.advance(0.5);
  EXPECT_NEAR(sim.state().y[0], 0.51 + kDefaultThickness, 1e-12);
}

// Thrown sideways into the box, the node stops at the side it hit.
TEST(ColliderTunnelling, FastNodeHitsTheSideItCameFrom) {
  Simulation sim = fast_node(Vec3(-0.5, 0.5, 0.1), Vec3(10, 0, 0), kTable);
  sim.advance(0.04);
  const Vec3 p = sim.state().position(0);
  EXPECT_NEAR(p.x(), -0.4 - kDefaultThickness, 1e-12);
  EXPECT_GT(p.y(), 0.45);
  EXPECT_NEAR(p.z(), 0.1, 1e-12);
  EXPECT_LE(sim.state().vx[0], 0.0) << "the approach speed is not removed";
}

// A pinned node inside a collider stays where its pin holds it; the free
// nodes around it are still kept out.
TEST(ColliderPins, PinnedNodeIsNeverMoved) {
  const int n = 4;
  const double width = 0.3, height = 0.5;
  const Vec3 pin(-width / 2, height, -width / 2);  // node (0, 0)
  const double r = 0.12;
  const Json sphere = {{"type", "sphere"}, {"center", xyz(pin)}, {"radius", r}};
  const SceneBuilder scene = sheet(n, width, height).solver("network", 0.005).pins({{0, 0}});
  for (const Json& shape :
       {sphere, Json{{"type", "plane"}, {"point", xyz(pin + Vec3(0, 0.05, 0))}}}) {
    Simulation sim = simulate(SceneBuilder(scene).module(shape));
    sim.advance(0.5);
    const ClothState& s = sim.state();
    EXPECT_EQ(s.x[0], pin.x()) << shape.dump();
    EXPECT_EQ(s.y[0], pin.y()) << shape.dump();
    EXPECT_EQ(s.z[0], pin.z()) << shape.dump();
    EXPECT_EQ(s.velocity(0), Vec3::Zero()) << shape.dump();
  }
  // The sphere keeps the free nodes out around the pin.
  Simulation sim = simulate(SceneBuilder(scene).module(sphere));
  run_outside(sim, 0.5, 0.1, [&](const Vec3& p) { return (p - pin).norm() - r; });
}

}  // namespace
}  // namespace neurocloth
