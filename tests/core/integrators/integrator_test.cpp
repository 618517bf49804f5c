// Every integrator against an independent truth: closed-form free fall, the
// analytic oscillator, conservation of momentum, the energy it must keep or
// lose, and its order of convergence measured from a dt sweep.
#include "core/integrators/integrator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "core/simulation/simulation.h"
#include "support/test_support.h"

namespace neurocloth {
namespace {

class IntegratorTest : public ::testing::TestWithParam<IntegratorKind> {
 protected:
  Simulation run(Scene scene, double dt, double seconds) {
    scene.solver.integrator = GetParam();
    scene.solver.dt = dt;
    scene.solver.adaptive = false;
    Simulation sim = scene.make_simulation();
    sim.advance(seconds);
    return sim;
  }
};

// The step-by-step closed form of each method for constant acceleration g:
// symplectic and backward Euler use the new velocity, forward Euler the old,
// Verlet and RK4 are exact.
TEST_P(IntegratorTest, FreeFallMatchesItsDiscreteClosedForm) {
  const Scene scene = test::asset_scene("free_fall");
  const double h = scene.solver.dt, g = -9.81, y0 = 10.0;
  const int n = 100;
  Simulation sim = run(scene, h, n * h);
  ASSERT_EQ(sim.steps(), n);
  double expected = 0;
  switch (GetParam()) {
    case IntegratorKind::network:
    case IntegratorKind::implicit_euler:
    case IntegratorKind::projective:
    case IntegratorKind::vbd:
      expected = y0 + g * h * h * n * (n + 1) / 2.0;
      break;
    case IntegratorKind::explicit_euler:
      expected = y0 + g * h * h * n * (n - 1) / 2.0;
      break;
    default:
      expected = y0 + 0.5 * g * (n * h) * (n * h);
      break;
  }
  EXPECT_NEAR(sim.state().y[0], expected, 1e-11);
  EXPECT_NEAR(sim.state().vy[0], g * n * h, 1e-11);
  EXPECT_EQ(sim.state().x[0], 0.0);
}

// Mass m on a spring k hanging from a pin, released at the spring's rest length:
// y(t) = y_eq + A cos(w t), w = sqrt(k/m), A = m g / k.
struct Oscillator {
  double k, m, w, A, y_eq;
  explicit Oscillator(const Scene& s)
      : k(s.material.spring_constant),
        m(s.material.node_mass),
        w(std::sqrt(k / m)),
        A(m * 9.81 / k),
        y_eq(s.topology.rest_positions[1].y() - m * 9.81 / k) {}
  double y(double t) const { return y_eq + A * std::cos(w * t); }
};

TEST_P(IntegratorTest, SpringMassPeriodAndAmplitude) {
  const Scene scene = test::asset_scene("spring_mass");
  const Oscillator osc(scene);
  Scene s = scene;
  s.solver.integrator = GetParam();
  s.solver.dt = 1e-5;
  Simulation sim = s.make_simulation();
  const double period = 2 * M_PI / osc.w;
  // Upward crossings of y_eq, interpolated linearly, and the largest excursion.
  std::vector<double> crossings;
  double prev = sim.state().y[1] - osc.y_eq, amplitude = 0;
  while (sim.time() < 2.2 * period) {
    sim.advance(s.solver.dt);
    const double cur = sim.state().y[1] - osc.y_eq;
    amplitude = std::max(amplitude, std::abs(cur));
    if (prev < 0 && cur >= 0) crossings.push_back(sim.time() - s.solver.dt * cur / (cur - prev));
    prev = cur;
  }
  ASSERT_EQ(crossings.size(), 2u);
  EXPECT_NEAR((crossings[1] - crossings[0]) / period, 1.0, 1e-3);
  EXPECT_NEAR(amplitude / osc.A, 1.0, 5e-3);
  EXPECT_EQ(sim.state().x[1], 0.0);  // stays on its line
}

TEST_P(IntegratorTest, MomentumIsConservedWithoutExternalForces) {
  Scene scene = test::asset_scene("free_cloth");
  scene.solver.integrator = GetParam();
  scene.solver.dt = 2e-4;  // inside forward Euler's (damped) stability region too
  ClothState s = scene.initial_state();
  unsigned seed = 3;
  auto rnd = [&seed] {
    seed = seed * 1103515245u + 12345u;
    return ((seed >> 8) % 2001) / 1000.0 - 1.0;
  };
  for (std::size_t i = 0; i < s.size(); ++i)
    s.set_velocity(i, 0.2 * Vec3(rnd(), rnd(), rnd()));
  Simulation sim(scene.build_network(), s, scene.solver);
  const Vec3 p0 = test::total_momentum(sim.network(), sim.state());
  ASSERT_GT(p0.norm(), 1e-3);
  ASSERT_EQ(sim.advance(0.5), RunStatus::ok);
  const Vec3 p1 = test::total_momentum(sim.network(), sim.state());
  // Springs act in equal and opposite pairs; the implicit solve is exact only
  // to its CG tolerance, the projective one to the factor's rounding, vbd's
  // (one node at a time) to its sweeps' convergence.
  const bool solves = GetParam() == IntegratorKind::implicit_euler || iterates_per_step(GetParam());
  const double tol = solves ? 1e-8 : 1e-12;
  EXPECT_LT((p1 - p0).norm(), tol * p0.norm()) << (p1 - p0).transpose();
  // ... and the cloth really moved and deformed.
  EXPECT_GT((sim.state().position(0) - s.position(0)).norm(), 1e-3);
}

// Undamped oscillator over many periods: the symplectic methods keep the energy
// bounded, forward Euler gains, backward Euler loses, RK4 loses a little.
TEST_P(IntegratorTest, EnergyBehaviourWithoutDamping) {
  Scene scene = test::asset_scene("spring_mass");
  scene.solver.integrator = GetParam();
  scene.solver.dt = 2e-3;  // h w = 0.04
  Simulation sim = scene.make_simulation();
  const double e0 = sim.energy().total();
  const double scale =
      0.5 * Oscillator(scene).k * std::pow(Oscillator(scene).A, 2);  // oscillation energy
  double worst_first = 0, worst_second = 0;
  for (int i = 0; i < 200; ++i) {  // 20 s, about 64 periods
    sim.advance(0.1);
    const double drift = (sim.energy().total() - e0) / scale;
    (i < 100 ? worst_first : worst_second) =
        std::max(i < 100 ? worst_first : worst_second, std::abs(drift));
    if (GetParam() == IntegratorKind::network || GetParam() == IntegratorKind::verlet) {
      ASSERT_LT(std::abs(drift), 0.05)
          << "symplectic energy error must stay bounded, t = " << sim.time();
    }
  }
  const double final_drift = (sim.energy().total() - e0) / scale;
  switch (GetParam()) {
    case IntegratorKind::network:
    case IntegratorKind::verlet:
      EXPECT_LT(worst_second, 1.5 * worst_first + 1e-6);  // no secular growth
      break;
    case IntegratorKind::explicit_euler:
      EXPECT_GT(final_drift, 1.0);
      break;
    case IntegratorKind::implicit_euler:
    case IntegratorKind::projective:  // backward Euler too, solved by its iterations
    case IntegratorKind::vbd:
      EXPECT_LT(final_drift, -0.5);
      break;
    case IntegratorKind::rk4:
      EXPECT_LT(std::abs(final_drift), 1e-3);
      break;
  }
}

// With viscosity c the oscillator's energy about its equilibrium,
// E = m v^2 / 2 + k (y - y_eq)^2 / 2, falls from one period to the next and
// decays on average as exp(-c t / m) (light damping).
TEST_P(IntegratorTest, ViscosityDissipatesEnergyAtTheAnalyticRate) {
  Scene scene = test::asset_scene("spring_mass");
  scene.material.viscosity = 0.2;  // c/m = 2 /s, damping ratio 0.05
  scene.solver.integrator = GetParam();
  scene.solver.dt = 1e-4;
  const Oscillator osc(scene);
  Simulation sim = scene.make_simulation();
  auto oscillation_energy = [&] {
    const double v = sim.state().vy[1], dy = sim.state().y[1] - osc.y_eq;
    return 0.5 * osc.m * v * v + 0.5 * osc.k * dy * dy;
  };
  const double e0 = oscillation_energy();
  double previous = e0;
  const double period = 2 * M_PI / osc.w;
  // Sampled once a period: within a period forward Euler's energy may rise
  // where the velocity (and so the damping) is small.
  for (int i = 0; i < 6; ++i) {
    sim.advance(period);
    const double e = oscillation_energy();
    ASSERT_LT(e, previous) << "energy grew over the period ending at t = " << sim.time();
    previous = e;
  }
  const double expected = std::exp(-scene.material.viscosity / osc.m * sim.time());
  EXPECT_NEAR(previous / e0 / expected, 1.0, 0.15);
}

// Global error at T against the analytic oscillator for a sweep of steps; the
// slope of log(error) against log(dt) is the order.
TEST_P(IntegratorTest, ConvergenceOrder) {
  const Scene scene = test::asset_scene("spring_mass");
  const Oscillator osc(scene);
  const std::map<IntegratorKind, std::pair<int, double>> expected = {
      {IntegratorKind::network, {1, 2e-4}},
      {IntegratorKind::explicit_euler, {1, 1e-4}},
      {IntegratorKind::verlet, {2, 2e-3}},
      {IntegratorKind::rk4, {4, 5e-3}},
      {IntegratorKind::implicit_euler, {1, 2e-4}},
      {IntegratorKind::projective, {1, 2e-4}},
      {IntegratorKind::vbd, {1, 2e-4}}};
  const auto [order, dt0] = expected.at(GetParam());
  const double T = 0.5;
  std::vector<double> errors;
  for (double dt : {dt0, dt0 / 2, dt0 / 4}) {
    Simulation sim = run(scene, dt, T);
    errors.push_back(std::abs(sim.state().y[1] - osc.y(T)));
  }
  const double p1 = std::log2(errors[0] / errors[1]), p2 = std::log2(errors[1] / errors[2]);
  EXPECT_NEAR(p1, order, 0.25) << errors[0] << " " << errors[1];
  EXPECT_NEAR(p2, order, 0.25) << errors[1] << " " << errors[2];
}

INSTANTIATE_TEST_SUITE_P(All, IntegratorTest, ::testing::ValuesIn(kAllIntegrators),
                         [](const auto& info) { return std::string(to_string(info.param)); });

}  // namespace
}  // namespace neurocloth
