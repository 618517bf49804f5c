// The air modules against independent truths: the closed-form force on a flat
// plate at 0, 45 and 90 degrees to the wind, zero force in still relative air,
// exponential decay under linear drag, the gust's bounds and mean, and a
// curtain that must blow downwind under every integrator.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "core/integrators/integrator.h"
#include "core/modules/module_factories.h"
#include "core/scene/grid_builder.h"
#include "core/scene/scene.h"
#include "core/simulation/simulation.h"
#include "support/scene_builder.h"
#include "support/test_support.h"

namespace neurocloth {
namespace {

const double kPi = std::acos(-1.0);

// A flat square plate of n x n nodes, spacing h, spanned by the unit vectors
// `along_rows` and `along_cols` from the origin (normal = along_rows x along_cols).
ClothTopology plate(const Vec3& along_rows, const Vec3& along_cols, int n = 4, double h = 0.1) {
  GridSpec g;
  g.rows = n;
  g.cols = n;
  g.spacing = h;
  g.origin = Vec3(0.3, -0.2, 0.7);
  g.row_direction = along_rows;
  g.col_direction = along_cols;
  return build_grid(g);
}

double total_area(const ClothTopology& t) {
  double a = 0;
  for (const auto& tri : t.triangles) {
    const Vec3& p = t.rest_positions[tri[0]];
    a += 0.5 * (t.rest_positions[tri[1]] - p).cross(t.rest_positions[tri[2]] - p).norm();
  }
  return a;
}

// Coefficients all different, so a formula that mixes two of them up fails.
WindSpec wind_spec(const Vec3& velocity) {
  WindSpec w;
  w.velocity = velocity;
  w.density = 1.25;
  w.drag = 1.3;
  w.lift = 0.7;
  w.skin = 0.05;
  return w;
}

// The module's force on every node of `topology` at rest positions with
// velocity `cloth_velocity`, starting from zero, in a step that starts at `time`.
NodeVectors module_forces(const ForceModule& m, const ClothTopology& topology,
                          const Vec3& cloth_velocity = Vec3::Zero(), double time = 0.0) {
  const ClothNetwork net = ClothNetwork::build(topology, Material{});
  ClothState s = net.rest_state(topology.rest_positions);
  for (std::size_t i = 0; i < s.size(); ++i)
    s.set_velocity(i, cloth_velocity);
  NodeVectors F(s.size());
  ForceInputs inputs;
  inputs.time = time;
  m.add_forces(net, inputs, ForceContext{}, s, F);
  return F;
}

Vec3 sum(const NodeVectors& F) {
  Vec3 total = Vec3::Zero();
  for (std::size_t i = 0; i < F.size(); ++i)
    total += F.at(i);
  return total;
}

// 0.5 rho A |u|^2: the dynamic pressure times the area.
double pressure_force(const WindSpec& w, double area, double speed) {
  return 0.5 * w.density * area * speed * speed;
}

TEST(Wind, FlatClothParallelToTheWindFeelsOnlySkinDrag) {
  // A tilted plane, so no axis-aligned shortcut can pass.
  const Vec3 r = Vec3(1, 2, 2) / 3.0, c = Vec3(2, 1, -2) / 3.0;
  const ClothTopology t = plate(r, c);
  const Vec3 velocity = 3.0 * r - 4.0 * c;  // in the plane, |u| = 5
  const WindSpec spec = wind_spec(velocity);
  const Vec3 F = sum(module_forces(*make_wind(spec, t), t));
  const double expected = spec.skin * pressure_force(spec, total_area(t), 5.0);
  EXPECT_NEAR(F.dot(velocity.normalized()), expected, 1e-9 * expected);
  // Nothing across the flow: no pressure drag, no lift.
  EXPECT_LT((F - F.dot(velocity.normalized()) * velocity.normalized()).norm(), 1e-9 * expected);
}

TEST(Wind, PlatePerpendicularToTheWindFeelsFullDragAndNoLift) {
  const ClothTopology t = plate(Vec3::UnitZ(), Vec3::UnitX());  // normal +y
  for (const double sign : {1.0, -1.0}) {                       // wind onto either face
    SCOPED_TRACE(sign);
    const WindSpec spec = wind_spec(Vec3(0, 7.0 * sign, 0));
    const NodeVectors forces = module_forces(*make_wind(spec, t), t);
    const Vec3 F = sum(forces);
    const double expected = (spec.drag + spec.skin) * pressure_force(spec, total_area(t), 7.0);
    EXPECT_NEAR(F.y(), sign * expected, 1e-9 * expected);
    EXPECT_LT(std::hypot(F.x(), F.z()), 1e-12 * expected);
  }
}

TEST(Wind, EachCornerOfATriangleTakesAThird) {
  ClothTopology t;
  t.rest_positions = {Vec3(0, 0, 0), Vec3(0.4, 0, 0), Vec3(0, 0, 0.3)};
  t.triangles = {{0, 2, 1}};
  const WindSpec spec = wind_spec(Vec3(1, 4, -2));
  const NodeVectors F = module_forces(*make_wind(spec, t), t);
  const Vec3 total = sum(F);
  ASSERT_GT(total.norm(), 0.0);
  for (int i = 0; i < 3; ++i)
    EXPECT_LT((F.at(i) - total / 3.0).norm(), 1e-14 * total.norm()) << i;
}

// A plate at 45 degrees to the wind: c = cos 45, so the drag is
// 0.5 rho A |u|^2 (C_D / sqrt 2 + C_F) along the wind and the lift
// C_L / 2 * 0.5 rho A |u|^2 across it, in the plane of the wind and the normal.
TEST(Wind, PlateAtFortyFiveDegreesFeelsHalfTheLiftCoefficientAcrossTheFlow) {
  const Vec3 r = Vec3::UnitZ(), c = Vec3::UnitX();
  const Vec3 n = r.cross(c);  // +y
  ClothTopology t = plate(r, c);
  const double speed = 6.0;
  const Vec3 uhat = (n + c).normalized();
  const WindSpec spec = wind_spec(speed * uhat);
  const Vec3 F = sum(module_forces(*make_wind(spec, t), t));
  const double q = pressure_force(spec, total_area(t), speed);

  const double drag = F.dot(uhat);
  EXPECT_NEAR(drag, q * (spec.drag / std::sqrt(2.0) + spec.skin), 1e-9 * q);
  const Vec3 lift = F - drag * uhat;
  EXPECT_NEAR(lift.norm(), 0.5 * spec.lift * q, 1e-9 * q);
  // Across the flow towards n - c: the air deflected along the plate pushes it back.
  EXPECT_NEAR(lift.normalized().dot((n - c).normalized()), 1.0, 1e-12);

  // The other winding flips every normal; the force must not notice.
  for (auto& tri : t.triangles)
    std::swap(tri[1], tri[2]);
  const Vec3 flipped = sum(module_forces(*make_wind(spec, t), t));
  EXPECT_LT((flipped - F).norm(), 1e-12 * F.norm());
}

TEST(Wind, LiftFollowsSinTwoPhiAtEveryAngle) {
  const Vec3 n = Vec3::UnitY(), c = Vec3::UnitX();
  const ClothTopology t = plate(Vec3::UnitZ(), c, 2);
  for (const double deg : {10.0, 30.0, 60.0, 80.0}) {
    SCOPED_TRACE(deg);
    const double phi = deg * kPi / 180.0;  // between the wind and the plane's normal
    const Vec3 uhat = std::cos(phi) * n + std::sin(phi) * c;
    const WindSpec spec = wind_spec(2.0 * uhat);
    const Vec3 F = sum(module_forces(*make_wind(spec, t), t));
    const double q = pressure_force(spec, total_area(t), 2.0);
    EXPECT_NEAR(F.dot(uhat), q * (spec.drag * std::cos(phi) + spec.skin), 1e-9 * q);
    EXPECT_NEAR((F - F.dot(uhat) * uhat).norm(), q * spec.lift * std::sin(2 * phi) / 2, 1e-9 * q);
  }
}

TEST(Wind, ClothMovingWithTheWindFeelsNothing) {
  const ClothTopology t = plate(Vec3::UnitZ(), Vec3(1, 1, 0).normalized());
  const Vec3 velocity(2.5, -1.0, 4.0);
  const auto wind = make_wind(wind_spec(velocity), t);
  const NodeVectors still = module_forces(*wind, t, velocity);
  for (std::size_t i = 0; i < still.size(); ++i)
    EXPECT_LT(still.at(i).norm(), 1e-12) << i;
  // Only the relative velocity counts: half the wind's speed, a quarter of the force.
  const Vec3 full = sum(module_forces(*wind, t));
  const Vec3 half = sum(module_forces(*wind, t, 0.5 * velocity));
  ASSERT_GT(full.norm(), 1e-3);
  EXPECT_LT((half - 0.25 * full).norm(), 1e-12 * full.norm());
}

TEST(Wind, DegenerateTrianglesAndNoTrianglesGiveNoForce) {
  ClothTopology t;
  t.rest_positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0)};  // collinear
  t.triangles = {{0, 1, 2}};
  const NodeVectors F = module_forces(*make_wind(wind_spec(Vec3(0, 5, 0)), t), t);
  for (std::size_t i = 0; i < F.size(); ++i) {
    EXPECT_TRUE(std::isfinite(F.x[i]) && std::isfinite(F.y[i]) && std::isfinite(F.z[i]));
    EXPECT_EQ(F.at(i).norm(), 0.0) << i;
  }
  t.triangles.clear();  // a chain: wind has nothing to push on
  const auto none = make_wind(wind_spec(Vec3(0, 5, 0)), t);
  EXPECT_EQ(none->state_bytes(), 0u);
  EXPECT_EQ(sum(module_forces(*none, t)).norm(), 0.0);
}

TEST(Wind, StoresItsTriangles) {
  const ClothTopology t = plate(Vec3::UnitZ(), Vec3::UnitX(), 5);
  const auto wind = make_wind(wind_spec(Vec3(1, 0, 0)), t);
  EXPECT_STREQ(wind->type(), "wind");
  EXPECT_EQ(wind->state_bytes(), 3 * sizeof(std::int32_t) * t.triangles.size());
}

// The wind speed the module applies at `time`, as a multiple of the base speed:
// read back from the force on a plate facing it (|F| grows with speed^2).
double gust_factor(const ForceModule& wind, const ClothTopology& t, const WindSpec& spec,
                   double time) {
  const Vec3 F = sum(module_forces(wind, t, Vec3::Zero(), time));
  const double base = spec.velocity.norm();
  const double q = pressure_force(spec, total_area(t), base) * (spec.drag + spec.skin);
  const double sign = F.dot(spec.velocity) < 0 ? -1.0 : 1.0;
  return sign * std::sqrt(F.norm() / q);
}

TEST(WindGust, IsDeterministicBoundedSmoothAndAveragesToTheBaseSpeed) {
  const ClothTopology t = plate(Vec3::UnitZ(), Vec3::UnitX(), 2);
  WindSpec spec = wind_spec(Vec3(0, 4, 0));
  spec.gust.amplitude = 0.4;
  spec.gust.period = 1.5;
  const auto a = make_wind(spec, t), b = make_wind(spec, t);
  const double dt = 0.01;
  const int samples = static_cast<int>(std::lround(50 * spec.gust.period / dt));  // 50 periods
  double mean = 0, lo = 1e9, hi = -1e9, previous = 1.0, steepest = 0;
  for (int k = 0; k < samples; ++k) {
    const double time = k * dt;
    const double s = gust_factor(*a, t, spec, time);
    ASSERT_EQ(s, gust_factor(*b, t, spec, time)) << "two identical modules differ at t=" << time;
    mean += s / samples;
    lo = std::min(lo, s);
    hi = std::max(hi, s);
    if (k > 0) steepest = std::max(steepest, std::abs(s - previous) / dt);
    previous = s;
  }
  EXPECT_GE(lo, 1.0 - spec.gust.amplitude - 1e-12);
  EXPECT_LE(hi, 1.0 + spec.gust.amplitude + 1e-12);
  // It does gust: over 50 periods it sweeps most of its range.
  EXPECT_GT(hi - 1.0, 0.6 * spec.gust.amplitude);
  EXPECT_LT(lo - 1.0, -0.6 * spec.gust.amplitude);
  EXPECT_NEAR(mean, 1.0, 0.02 * spec.gust.amplitude);
  // Smooth, not noise: the slope stays within a few times amplitude * 2 pi / period.
  EXPECT_LT(steepest, 3.0 * spec.gust.amplitude * 2 * kPi / spec.gust.period);
  // Replaying a time replays the wind (no hidden state advances with the calls).
  EXPECT_EQ(gust_factor(*a, t, spec, 0.37), gust_factor(*b, t, spec, 0.37));
}

TEST(WindGust, IsFrozenForTheStep) {
  const ClothTopology t = plate(Vec3::UnitZ(), Vec3::UnitX(), 2);
  WindSpec spec = wind_spec(Vec3(0, 4, 0));
  spec.gust.amplitude = 0.5;
  const auto wind = make_wind(spec, t);
  const Vec3 first = sum(module_forces(*wind, t, Vec3::Zero(), 0.3));
  // Every evaluation of a step alike (the gust is read at the step's start) ...
  EXPECT_EQ(sum(module_forces(*wind, t, Vec3::Zero(), 0.3)), first);
  EXPECT_TRUE(wind->time_dependent());
  // ... and the next step differs.
  EXPECT_NE(sum(module_forces(*wind, t, Vec3::Zero(), 0.8)), first);
}

TEST(WindGust, ZeroAmplitudeIsASteadyWind) {
  const ClothTopology t = plate(Vec3::UnitZ(), Vec3::UnitX(), 2);
  WindSpec spec = wind_spec(Vec3(0, 4, 0));
  spec.gust.period = 0.7;
  const auto wind = make_wind(spec, t);
  const double first = gust_factor(*wind, t, spec, 0.0);
  EXPECT_NEAR(first, 1.0, 1e-12);
  for (const double time : {0.1, 0.35, 1.0, 12.3})
    EXPECT_EQ(gust_factor(*wind, t, spec, time), first) << time;
}

TEST(AirDrag, ForceIsMinusRateTimesMassTimesVelocityOnEveryNode) {
  ClothTopology t;
  t.rest_positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0)};
  ClothNetwork net = ClothNetwork::build(t, Material{});
  net.masses.inverse_mass = {1.0 / 0.5, 1.0 / 0.02, 1.0 / 3.0};
  net.set_pinned(2, true);
  ClothState s = net.rest_state(t.rest_positions);
  const Vec3 v[3] = {Vec3(1, -2, 3), Vec3(0, 5, 0), Vec3(-1, 0, 0.5)};
  for (int i = 0; i < 3; ++i)
    s.set_velocity(i, v[i]);
  AirDragSpec spec;
  spec.rate = 0.8;
  const auto drag = make_air_drag(spec);
  EXPECT_STREQ(drag->type(), "air_drag");
  NodeVectors F(3);
  F.x[1] = 10.0;  // adds to what is there
  drag->add_forces(net, ForceInputs{}, ForceContext{}, s, F);
  for (int i = 0; i < 3; ++i) {
    const Vec3 expected =
        -spec.rate * net.mass(i) * v[i] + (i == 1 ? Vec3(10, 0, 0) : Vec3::Zero());
    EXPECT_LT((F.at(i) - expected).norm(), 1e-14 * expected.norm()) << i;
  }
}

// One free node, no springs, no gravity: m dv/dt = -rate m v, so
// v = v0 exp(-rate t) and x = x0 + v0 (1 - exp(-rate t)) / rate. A pinned node
// beside it stays where it is.
TEST(AirDrag, FreeNodeDecaysExponentiallyAndPinnedNodeStays) {
  ClothTopology t;
  t.rest_positions = {Vec3(0, 0, 0), Vec3(1, 1, 1)};
  ClothNetwork net = ClothNetwork::build(t, Material{});
  net.gravity = Vec3::Zero();
  net.set_pinned(1, true);
  AirDragSpec spec;
  spec.rate = 1.5;
  net.force_modules.push_back(make_air_drag(spec));
  ClothState s = net.rest_state(t.rest_positions), next = s;
  const Vec3 v0(2, -1, 0.5);
  s.set_velocity(0, v0);
  const auto rk4 = make_integrator(IntegratorKind::rk4, net);
  NodeVectors F(2);
  const double h = 1e-3;
  const int steps = 1000;
  for (int k = 0; k < steps; ++k) {
    net.net_forces(s, F);
    rk4->step(net, ForceInputs{}, ForceContext{}, s, F, h, next);
    s = next;
  }
  const double time = steps * h, decay = std::exp(-spec.rate * time);
  EXPECT_LT((s.velocity(0) - v0 * decay).norm(), 1e-10 * v0.norm());
  EXPECT_LT((s.position(0) - v0 * (1 - decay) / spec.rate).norm(), 1e-10 * v0.norm());
  EXPECT_EQ(s.position(1), t.rest_positions[1]);
  EXPECT_EQ(s.velocity(1), Vec3::Zero());
}

// A 10 x 10 curtain in the x-y plane hanging from its top row, with the wind
// blowing through it along +z.
std::string curtain_scene(const std::string& integrator, const std::string& modules,
                          double dt = 1e-3) {
  return test::SceneBuilder(10, 10, 0.05)
      .name("curtain")
      .origin(Vec3(0, 1, 0))
      .hanging()
      .pin_top_row()
      .material(200.0, 0.01, 0.05)
      .gravity(Vec3(0, -9.81, 0))
      .solver(integrator, dt)
      .modules("[" + modules + "]")
      .text();
}

const char* const kWind = R"({ "type": "wind", "velocity": [0, 0, 8] })";

// Mean z of the free nodes, after `seconds`.
double mean_free_z(const std::string& integrator, const std::string& modules, double seconds,
                   double dt = 1e-3) {
  const Scene scene = parse_scene(curtain_scene(integrator, modules, dt), "test.json");
  Simulation sim = scene.make_simulation();
  EXPECT_EQ(sim.advance(seconds), RunStatus::ok) << sim.divergence_reason();
  double z = 0;
  int free = 0;
  for (std::size_t i = 0; i < sim.state().size(); ++i)
    if (!sim.network().masses.pinned(i)) {
      z += sim.state().z[i];
      ++free;
    }
  return z / free;
}

TEST(Wind, CurtainBlowsDownwindAndHangsStillWithout) {
  // 8 m/s on 0.2 m^2 is about 8 N against 9 N of weight: tens of degrees out.
  EXPECT_GT(mean_free_z("network", kWind, 2.0), 0.08);
  EXPECT_NEAR(mean_free_z("network", "", 2.0), 0.0, 1e-9);
  // A steady drag alone has no out-of-plane component to push with.
  EXPECT_NEAR(mean_free_z("network", R"({ "type": "air_drag", "rate": 0.5 })", 2.0), 0.0, 1e-9);
}

TEST(Wind, DeclaredInASceneItIsBuiltAndReported) {
  const Scene scene = parse_scene(curtain_scene("network", kWind), "test.json");
  const Simulation sim = scene.make_simulation();
  const auto reports = sim.module_reports();
  ASSERT_EQ(reports.size(), 1u);
  EXPECT_EQ(reports[0].type, "wind");
  EXPECT_EQ(reports[0].state_bytes, 3 * sizeof(std::int32_t) * scene.topology.triangles.size());
}

// The adaptive propagation samples the gust at the start of every trial step;
// a rejected trial retried at the same time must see the same wind.
TEST(Wind, GustingWindRunsUnderTheAdaptiveStep) {
  Scene scene = parse_scene(curtain_scene("network",
                                          R"({ "type": "wind", "velocity": [0, 0, 8],
                         "gust": { "amplitude": 0.5, "period": 0.4 } })"),
                            "test.json");
  scene.solver.adaptive = true;
  Simulation sim = scene.make_simulation();
  ASSERT_EQ(sim.advance(0.5), RunStatus::ok) << sim.divergence_reason();
  double z = 0;
  for (std::size_t i = 10; i < sim.state().size(); ++i)  // the free rows
    z += sim.state().z[i] / 90.0;
  EXPECT_GT(z, 0.05);
}

// The divergence check's energy budget counts what the wind can put in: a
// cloth at rest with no gravity (budget otherwise ~0) blown by the wind is a
// healthy run, not "runaway energy".
TEST(Wind, WeightlessClothInTheWindIsNotADivergence) {
  Scene scene = parse_scene(curtain_scene("network", kWind), "test.json");
  scene.gravity = Vec3::Zero();
  Simulation sim = scene.make_simulation();
  EXPECT_EQ(sim.advance(1.0), RunStatus::ok) << sim.divergence_reason();
  EXPECT_EQ(sim.check_now(), RunStatus::ok) << sim.divergence_reason();
  EXPECT_GT(sim.energy().kinetic, 0.0);
}

class WindIntegratorTest : public ::testing::TestWithParam<IntegratorKind> {};

// The wind is a force module, so it must reach every integrator's force
// evaluations (RK4 stages, the implicit solve's right-hand side).
TEST_P(WindIntegratorTest, PushesTheCurtainDownwind) {
  const std::string name = to_string(GetParam());
  // Forward Euler only damps these springs' fast modes with a ten times smaller step.
  const double dt = GetParam() == IntegratorKind::explicit_euler ? 1e-4 : 1e-3;
  const double moved = mean_free_z(name, kWind, 0.3, dt);
  EXPECT_GT(moved, 0.08) << name;
  // And by as much as under RK4: an integrator that saw the wind in only some of
  // its force evaluations (one RK4 stage of four, say) would fall well short.
  const double reference = mean_free_z("rk4", kWind, 0.3);
  EXPECT_NEAR(moved, reference, 0.05 * reference) << name;
  EXPECT_NEAR(mean_free_z(name, "", 0.3, dt), 0.0, 1e-9) << name;
}

INSTANTIATE_TEST_SUITE_P(AllIntegrators, WindIntegratorTest, ::testing::ValuesIn(kAllIntegrators),
                         [](const auto& info) { return std::string(to_string(info.param)); });

}  // namespace
}  // namespace neurocloth
