// The cylinder collider (collider_shapes.h, colliders.cpp): its distance and
// normal against a signed distance written here independently, its
// branch-free case against its exact one, its derivatives against finite
// differences, and in a run: a cloth rests on its top and hangs past its rim,
// a node pressed on its side or its rim stays out, fast nodes do not tunnel,
// and friction on its top holds and slips where Coulomb says.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "core/modules/collider_shapes.h"
#include "core/modules/module_factories.h"
#include "core/scene/scene.h"
#include "support/scene_builder.h"

namespace neurocloth::cylinder_collider_test {

using collider_shapes::Contact;
using collider_shapes::CylinderShape;
using collider_shapes::Mat3;
using test::SceneBuilder;
using Json = SceneBuilder::Json;

constexpr double kThickness = 0.005;  // the default
constexpr double kSlack = 1e-9;       // "outside" allows this much round-off

Json xyz(const Vec3& v) {
  return {v.x(), v.y(), v.z()};
}

CylinderSpec tilted() {
  CylinderSpec s;
  s.center = Vec3(0.1, 0.4, -0.05);
  s.axis = Vec3(0.2, 1, -0.3).normalized();
  s.radius = 0.09;
  s.height = 0.2;
  return s;
}

Json declaration(const CylinderSpec& s) {
  return {{"type", "cylinder"},
          {"center", xyz(s.center)},
          {"axis", xyz(s.axis)},
          {"radius", s.radius},
          {"height", s.height}};
}

// The signed distance to the solid, written apart from the module: the
// distance to the rectangle (radius, half height) in (across, along) space.
double distance(const CylinderSpec& s, const Vec3& p) {
  const Vec3 d = p - s.center;
  const double along = d.dot(s.axis), across = (d - along * s.axis).norm();
  const double wr = across - s.radius, wy = std::abs(along) - 0.5 * s.height;
  return std::hypot(std::max(wr, 0.0), std::max(wy, 0.0)) + std::min(std::max(wr, wy), 0.0);
}

Vec3 distance_gradient(const CylinderSpec& s, const Vec3& p) {
  const double h = 1e-7;
  Vec3 g;
  for (int k = 0; k < 3; ++k) {
    const Vec3 e = h * Vec3::Unit(k);
    g[k] = (distance(s, p + e) - distance(s, p - e)) / (2 * h);
  }
  return g;
}

// A point `radial` from the axis and `along` it, at angle `turn` around it.
Vec3 at(const CylinderSpec& s, double radial, double along, double turn) {
  const Vec3 helper = std::abs(s.axis.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  const Vec3 u = s.axis.cross(helper).normalized(), v = s.axis.cross(u);
  return s.center + along * s.axis + radial * (std::cos(turn) * u + std::sin(turn) * v);
}

TEST(CylinderCollider, IsAContactModuleNamedCylinderAndASceneRunsIt) {
  const auto module = make_collider(CylinderSpec{});
  EXPECT_STREQ(module->type(), "cylinder");
  EXPECT_EQ(module->phase(), ConstraintModule::contact);
  EXPECT_EQ(module->state_bytes(), 0u);
  EXPECT_TRUE(module->has_adjoint());
  Simulation sim = SceneBuilder(4, 4, 0.1).module(declaration(tilted())).parse().make_simulation();
  sim.advance(0.05);
  ASSERT_EQ(sim.module_reports().size(), 1u);
  EXPECT_EQ(sim.module_reports()[0].type, "cylinder");
  EXPECT_EQ(sim.module_reports()[0].calls, 50);
}

// A node that did not cross the solid in its step (here: it did not move) is
// given its signed distance and the direction it grows fastest: on the side,
// the ends, the rims and inside.
TEST(CylinderCollider, DistanceAndNormalAreTheSolidsOwn) {
  const CylinderSpec s = tilted();
  const CylinderShape shape(s);
  std::mt19937_64 rng(44);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int inside = 0, rims = 0;
  for (int n = 0; n < 20000; ++n) {
    const Vec3 p = s.center + Vec3(u(rng), u(rng), u(rng)) * 0.2;
    const Contact c = shape.contact(p, p);
    const double d = distance(s, p);
    ASSERT_NEAR(c.phi, d, 1e-12) << n;
    ASSERT_NEAR(c.normal.norm(), 1, 1e-12) << n;
    // Where the gradient is defined (off the ridges inside, where two faces are as near).
    const Vec3 g = distance_gradient(s, p);
    if (std::abs(g.norm() - 1) < 1e-6) {
      EXPECT_LT((c.normal - g).norm(), 1e-5) << n;
    }
    inside += d < 0;
    const Vec3 r = p - s.center;
    const double along = r.dot(s.axis);
    rims += (r - along * s.axis).norm() > s.radius && std::abs(along) > 0.5 * s.height;
  }
  EXPECT_GT(inside, 1000);
  EXPECT_GT(rims, 1000);
}

// The block scan's case (a node over an end whose step started beyond it)
// gives contact()'s bits, and claims a cloth resting on the top, not a node
// beside the side or one that came through.
TEST(CylinderCollider, TheBranchFreeEndContactIsTheExactOne) {
  const CylinderSpec s = tilted();
  const CylinderShape shape(s);
  std::mt19937_64 rng(9073);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int claimed = 0;
  for (int n = 0; n < 100000; ++n) {
    const Vec3 end = s.center + Vec3(u(rng), u(rng), u(rng)) * 0.15;
    const double reach = n % 4 == 0 ? 0.5 : 0.02;
    const Vec3 start = end + reach * Vec3(u(rng), u(rng), u(rng));
    double phi = 0, nx = 0, ny = 0, nz = 0;
    if (!shape.face_contact(start.x(), start.y(), start.z(), end.x(), end.y(), end.z(), phi, nx, ny,
                            nz))
      continue;
    ++claimed;
    const Contact c = shape.contact(end, start);
    ASSERT_EQ(phi, c.phi) << n;
    ASSERT_EQ(nx, c.normal.x()) << n;
    ASSERT_EQ(ny, c.normal.y()) << n;
    ASSERT_EQ(nz, c.normal.z()) << n;
    ASSERT_GT(phi, 0.0) << n;
  }
  EXPECT_GT(claimed, 5000);
  double phi, nx, ny, nz;
  const Vec3 top = at(s, 0.05, 0.5 * s.height + 0.001, 1.0);
  EXPECT_TRUE(shape.face_contact(top.x() + 0.001, top.y() + 0.01, top.z(), top.x(), top.y(),
                                 top.z(), phi, nx, ny, nz));
  EXPECT_NEAR(phi, 0.001, 1e-12);
  EXPECT_LT((Vec3(nx, ny, nz) - s.axis).norm(), 1e-15);
  const Vec3 beside = at(s, s.radius + 0.001, 0.0, 2.0);
  EXPECT_FALSE(shape.face_contact(beside.x(), beside.y(), beside.z(), beside.x(), beside.y(),
                                  beside.z(), phi, nx, ny, nz));
  const Vec3 under = at(s, 0.05, -0.5 * s.height - 0.001, 1.0);
  EXPECT_FALSE(shape.face_contact(top.x(), top.y(), top.z(), under.x(), under.y(), under.z(), phi,
                                  nx, ny, nz));
}

// d phi / dp and d normal / dp against central differences of contact(), the
// step's start held, at points well inside each part: side, ends, rims,
// inside, and where a step came in through the side and went past the axis
// or out of the far side (the plane tangent where it came in).
TEST(CylinderCollider, TheJacobianIsContactsDerivative) {
  const CylinderSpec s = tilted();
  const CylinderShape shape(s);
  const double r = s.radius, hh = 0.5 * s.height;
  struct Case {
    const char* part;
    Vec3 p, before;
  };
  std::vector<Case> cases;
  for (double turn : {0.3, 2.0, 4.4}) {
    cases.push_back({"side", at(s, r + 0.002, 0.03, turn), at(s, r + 0.01, 0.03, turn)});
    cases.push_back(
        {"side, pressed in", at(s, r - 0.003, -0.04, turn), at(s, r + 0.004, -0.04, turn)});
    cases.push_back({"top", at(s, 0.04, hh + 0.003, turn), at(s, 0.04, hh + 0.01, turn)});
    cases.push_back(
        {"top, pressed in", at(s, 0.04, hh - 0.002, turn), at(s, 0.04, hh + 0.01, turn)});
    cases.push_back({"bottom", at(s, 0.06, -hh - 0.002, turn), at(s, 0.06, -hh - 0.01, turn)});
    cases.push_back(
        {"top rim", at(s, r + 0.003, hh + 0.002, turn), at(s, r + 0.01, hh + 0.01, turn)});
    cases.push_back(
        {"bottom rim", at(s, r + 0.002, -hh - 0.004, turn), at(s, r + 0.01, -hh - 0.01, turn)});
    cases.push_back({"inside from the start", at(s, 0.05, 0.01, turn), at(s, 0.05, 0.012, turn)});
    cases.push_back({"past the axis", at(s, 0.03, 0.02, turn + 3.0), at(s, r + 0.05, 0.01, turn)});
    cases.push_back(
        {"through and out", at(s, r + 0.02, 0.0, turn + 2.9), at(s, r + 0.03, 0.01, turn)});
  }
  for (const Case& k : cases) {
    SCOPED_TRACE(k.part);
    const Contact c = shape.contact(k.p, k.before);
    Vec3 grad;
    Mat3 dn;
    shape.jacobian(k.p, k.before, c, grad, dn);
    const double h = 1e-7;
    for (int j = 0; j < 3; ++j) {
      const Vec3 e = h * Vec3::Unit(j);
      const Contact hi = shape.contact(k.p + e, k.before), lo = shape.contact(k.p - e, k.before);
      EXPECT_NEAR(grad[j], (hi.phi - lo.phi) / (2 * h), 1e-6) << "d phi / dp" << j;
      const Vec3 fd = (hi.normal - lo.normal) / (2 * h);
      EXPECT_LT((dn.col(j) - fd).norm(), 1e-5 * std::max(1.0, fd.norm()))
          << "d normal / dp" << j << ": " << dn.col(j).transpose() << " against " << fd.transpose();
    }
  }
}

// Where a run leaves a free node: never closer than the thickness to the solid.
void expect_outside(const Simulation& sim, const CylinderSpec& s) {
  for (std::size_t i = 0; i < sim.state().size(); ++i) {
    const double d = distance(s, sim.state().position(i));
    ASSERT_GE(d, kThickness - kSlack) << "node " << i << " at t = " << sim.time();
  }
}

CylinderSpec upright(const Vec3& center, double radius, double height) {
  CylinderSpec s;
  s.center = center;
  s.radius = radius;
  s.height = height;
  return s;
}

// A sheet dropped centred on a post rests on its top and hangs past its rim
// all round; no node gets into the post on the way.
TEST(CylinderCollider, ASheetRestsOnTheTopAndHangsPastTheRim) {
  const CylinderSpec s = upright(Vec3(0, 0.3, 0), 0.12, 0.6);  // top at 0.6
  const int n = 15;
  const double width = 0.5;
  Simulation sim = SceneBuilder(n, n, width / (n - 1))
                       .origin(Vec3(-width / 2, 0.62, -width / 2))
                       .material(100.0, 0.002, 0.05)
                       .friction(0.3)
                       .solver("network", 0.02, true)
                       .module(declaration(s))
                       .parse()
                       .make_simulation();
  for (int k = 0; k < 15; ++k) {
    ASSERT_EQ(sim.advance(0.1), RunStatus::ok) << sim.divergence_reason();
    expect_outside(sim, s);
  }
  const ClothState& x = sim.state();
  const std::size_t middle = (n / 2) * n + n / 2;
  EXPECT_NEAR(x.y[middle], 0.6 + kThickness, 2e-3);
  EXPECT_NEAR(x.x[middle], 0.0, 0.01);
  for (std::size_t corner :
       {std::size_t{0}, std::size_t(n - 1), std::size_t(n * (n - 1)), std::size_t(n * n - 1)})
    EXPECT_LT(x.y[corner], 0.6 - 0.05) << "corner " << corner << " does not hang";
}

// One free node with no springs: what the contact acts on undisturbed.
Simulation free_node(const Vec3& p, const Vec3& v, const CylinderSpec& s, double friction = 0.0,
                     double dt = 0.04, const Vec3& gravity = Vec3(0, -9.81, 0)) {
  Simulation sim = SceneBuilder(1, 1, 0.1)
                       .origin(p)
                       .springs({})
                       .material(0.0, 0.1, 0.0)
                       .friction(friction)
                       .gravity(gravity)
                       .solver("network", dt)
                       .module(declaration(s))
                       .parse()
                       .make_simulation();
  ClothState state = sim.state();
  state.set_velocity(0, v);
  sim.set_state(state);
  return sim;
}

// Pulled sideways against the side (gravity along x), a node stops on it,
// the thickness out, and stays: frictionless where the side faces the pull
// straight, held by friction where the side is 17 degrees off it (tan 0.31 <
// 0.5).
TEST(CylinderCollider, ANodePulledOntoTheSideStaysOnIt) {
  const CylinderSpec s = upright(Vec3(0, 0, 0), 0.1, 0.4);
  for (const auto& [z, friction] :
       std::vector<std::pair<double, double>>{{0.0, 0.0}, {0.03, 0.5}}) {
    Simulation sim =
        free_node(Vec3(-0.2, 0.05, z), Vec3::Zero(), s, friction, 0.01, Vec3(9.81, 0, 0));
    for (int k = 0; k < 5; ++k) {
      sim.advance(0.1);
      expect_outside(sim, s);
    }
    const Vec3 rested = sim.state().position(0);
    sim.advance(0.5);
    const Vec3 p = sim.state().position(0);
    // Held, it keeps where its step started across the normal: on a curved
    // side that is a hair (0.3 um here) outside the thickness.
    EXPECT_NEAR(distance(s, p), kThickness, 1e-6) << z;
    EXPECT_LT((p - rested).norm(), 1e-12) << z << ": it creeps";
    EXPECT_EQ(p.y(), 0.05) << z << ": no force along the axis, no motion along it";
    EXPECT_LT(sim.state().velocity(0).norm(), 1e-9) << z;
    if (z == 0.0) {
      EXPECT_EQ(p.z(), 0.0);
    }
  }
}

// A node dropped just past the rim is held off the rim's edge by the
// thickness, rolls off it outwards and falls past the side.
TEST(CylinderCollider, ANodeOnTheRimRollsOffIt) {
  const CylinderSpec s = upright(Vec3(0, 0, 0), 0.1, 0.4);  // top at 0.2
  Simulation sim = free_node(Vec3(0.102, 0.21, 0), Vec3::Zero(), s, 0.0, 0.005);
  double least = 1;
  for (int k = 0; k < 100; ++k) {
    sim.advance(0.005);
    expect_outside(sim, s);
    least = std::min(least, distance(s, sim.state().position(0)));
  }
  EXPECT_LT(least, kThickness + 1e-3) << "it never touched the rim";
  const Vec3 p = sim.state().position(0);
  EXPECT_LT(p.y(), 0.1) << "it did not fall past the rim";
  EXPECT_GT(p.x(), 0.1 + kThickness - kSlack);
}

// Falling at 10 m/s onto a disc 2 cm thick, a node ends its first step under
// it: it comes back on top, not out of the bottom.
TEST(CylinderCollider, AFastNodeDoesNotFallThroughAThinDisc) {
  const CylinderSpec s = upright(Vec3(0, 0.5, 0), 0.3, 0.02);  // top at 0.51
  for (const Vec3& xz : {Vec3(0, 0, 0), Vec3(0.25, 0, 0.1), Vec3(-0.1, 0, -0.28)}) {
    Simulation sim = free_node(xz + Vec3(0, 0.6, 0), Vec3(0, -10, 0), s);
    sim.advance(0.04);
    EXPECT_NEAR(sim.state().y[0], 0.51 + kThickness, 1e-12) << xz.transpose();
    sim.advance(0.5);
    const Vec3 p = sim.state().position(0);
    EXPECT_NEAR(p.y(), 0.51 + kThickness, 1e-12) << xz.transpose();
    EXPECT_NEAR(p.x(), xz.x(), 1e-12);
    EXPECT_NEAR(p.z(), xz.z(), 1e-12);
  }
}

// Thrown sideways at a thin post, a node whose step ends past its axis or out
// of its far side goes back to the side it hit: onto the plane tangent to the
// side where it came in, the thickness out, its approach speed gone.
TEST(CylinderCollider, AFastNodeStopsAtTheSideItCameFrom) {
  const CylinderSpec s = upright(Vec3(0, 0, 0), 0.05, 1.0);
  const double z = 0.01;
  const Vec3 entry_normal(-std::sqrt(1 - z * z / (s.radius * s.radius)), 0, z / s.radius);
  for (const double speed : {3.0, 10.0}) {  // 12 cm (past the axis) and 40 cm (through) a step
    Simulation sim = free_node(Vec3(-0.1, 0.2, z), Vec3(speed, 0, 0), s, 0.0, 0.04, Vec3::Zero());
    sim.advance(0.04);
    const Vec3 p = sim.state().position(0);
    EXPECT_LT(p.x(), -0.03) << speed << ": it came out of the far side";
    expect_outside(sim, s);
    EXPECT_NEAR(entry_normal.dot(p - s.center) - s.radius, kThickness, 1e-12) << speed;
    EXPECT_NEAR(sim.state().velocity(0).dot(entry_normal), 0.0, 1e-12) << speed;
    EXPECT_EQ(p.y(), 0.2);
  }
}

// On the top of a post tilted by theta a node sticks while tan(theta) <= mu
// and slides with Coulomb's acceleration above.
TEST(CylinderCollider, FrictionOnTheTopIsCoulombs) {
  const double mu = 0.3;
  for (const double slope : {0.9 * mu, 1.2 * mu}) {
    const double theta = std::atan(slope);
    CylinderSpec s = upright(Vec3::Zero(), 0.5, 0.2);
    s.axis = Vec3(-std::sin(theta), std::cos(theta), 0);
    const Vec3 downhill = Vec3(-std::cos(theta), -std::sin(theta), 0);
    const Vec3 start = (0.1 + kThickness) * s.axis;
    Simulation sim = free_node(start, Vec3::Zero(), s, mu, 0.01);
    sim.advance(0.5);
    const Vec3 p = sim.state().position(0);
    EXPECT_NEAR((p - s.center).dot(s.axis), 0.1 + kThickness, 1e-9) << slope;
    const double moved = (p - start).dot(downhill);
    if (slope < mu) {
      EXPECT_LT(std::abs(moved), 1e-9) << slope;
    } else {
      const double a = 9.81 * (std::sin(theta) - mu * std::cos(theta));
      EXPECT_NEAR(sim.state().velocity(0).dot(downhill), a * 0.5, 0.02 * a * 0.5) << slope;
    }
  }
}

}  // namespace neurocloth::cylinder_collider_test
