// The implicit step's matrix-free product (ImplicitSystem::apply): walked in
// the spring layer's chunks, it is the spring-by-spring sum of the blocks of
// the last linearisation, and split over a team it gives one thread's bits.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include "core/base/step_threads.h"
#include "core/integrators/implicit_system.h"
#include "core/io/asset_paths.h"
#include "core/scene/scene.h"
#include "core/simulation/simulation.h"

namespace neurocloth {
namespace {

// The table drape at n x n, 0.3 s in (falling onto the table, its springs
// turned every way), with one corner pinned so the pinned rows are exercised.
Simulation falling(int n) {
  Scene scene = resized_grid(load_scene(assets_directory() + "/scenes/table_drape.json"), n);
  scene.solver.integrator = IntegratorKind::implicit_euler;
  scene.solver.adaptive = false;
  scene.solver.dt = 1.0 / 60;
  scene.solver.linear_tolerance = 1e-6;
  Simulation sim = scene.make_simulation();
  EXPECT_EQ(sim.advance(0.3), RunStatus::ok);
  return sim;
}

std::vector<double> varied(std::size_t size) {
  std::vector<double> u(size);
  for (std::size_t i = 0; i < size; ++i)
    u[i] = std::sin(0.37 * static_cast<double>(i)) + 0.1 * std::cos(1.3 * static_cast<double>(i));
  return u;
}

// y = alpha M u + beta D u + gamma K u, spring after spring from the blocks
// the system keeps: what the product must equal.
std::vector<double> spring_by_spring(const ClothNetwork& net, const ImplicitSystem& system,
                                     double alpha, double beta, double gamma,
                                     const std::vector<double>& u) {
  const std::size_t n = net.node_count();
  std::vector<double> y(3 * n);
  for (std::size_t i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c)
      y[3 * i + c] = alpha / net.masses.inverse_mass[i] * u[3 * i + c];
  const SpringLayer& L = net.springs;
  for (std::size_t s = 0; s < L.size(); ++s) {
    const std::size_t a = 3 * static_cast<std::size_t>(L.node_a[s]);
    const std::size_t b = 3 * static_cast<std::size_t>(L.node_b[s]);
    const double K[6] = {system.stiffness(s, 0), system.stiffness(s, 1), system.stiffness(s, 2),
                         system.stiffness(s, 3), system.stiffness(s, 4), system.stiffness(s, 5)};
    const double d[3] = {system.direction(s, 0), system.direction(s, 1), system.direction(s, 2)};
    const double k[9] = {K[0], K[1], K[2], K[1], K[3], K[4], K[2], K[4], K[5]};
    const double du[3] = {u[a] - u[b], u[a + 1] - u[b + 1], u[a + 2] - u[b + 2]};
    const double along = beta * L.damping[s] * (d[0] * du[0] + d[1] * du[1] + d[2] * du[2]);
    for (int r = 0; r < 3; ++r) {
      const double f =
          gamma * (k[3 * r] * du[0] + k[3 * r + 1] * du[1] + k[3 * r + 2] * du[2]) + along * d[r];
      y[a + r] += f;
      y[b + r] -= f;
    }
  }
  for (std::size_t i = 0; i < n; ++i)
    if (net.masses.free[i] == 0.0) y[3 * i] = y[3 * i + 1] = y[3 * i + 2] = 0.0;
  return y;
}

double largest(const std::vector<double>& v) {
  double m = 0;
  for (double x : v)
    m = std::max(m, std::abs(x));
  return m;
}

TEST(ImplicitProduct, IsTheSpringBySpringSum) {
  const Simulation sim = falling(24);
  ClothNetwork net = sim.network();
  net.masses.free[0] = 0.0;
  ImplicitSystem system(net);
  system.linearise(net, sim.state());
  const std::vector<double> u = varied(3 * net.node_count());
  // The step's coefficients, then others: the blocks are remade when they change.
  const double h = 1.0 / 60;
  for (const auto& coefficients :
       {std::vector<double>{1.0, h, h * h}, {0.0, 0.0, 1.0}, {2.0, 0.5, 0.0}, {1.0, h, h * h}}) {
    const double alpha = coefficients[0], beta = coefficients[1], gamma = coefficients[2];
    std::vector<double> y(u.size());
    system.apply(net, alpha, beta, gamma, u, y);
    const std::vector<double> expected = spring_by_spring(net, system, alpha, beta, gamma, u);
    const double scale = largest(expected);
    ASSERT_GT(scale, 0.0);
    double worst = 0;
    for (std::size_t i = 0; i < y.size(); ++i)
      worst = std::max(worst, std::abs(y[i] - expected[i]));
    // Measured 2026-12-06: at most 2.5e-16 of the largest component (the sums
    // differ only in their order and grouping).
    EXPECT_LE(worst, 1e-15 * scale)
        << "alpha " << alpha << " beta " << beta << ": " << worst / scale;
    EXPECT_EQ(y[0], 0.0);  // the pinned node
  }
  // A new linearisation is not the old one's product.
  ClothState moved = sim.state();
  for (std::size_t i = 0; i < moved.size(); ++i)
    moved.x[i] += 0.01 * std::sin(static_cast<double>(i));
  system.linearise(net, moved);
  std::vector<double> y(u.size());
  system.apply(net, 1.0, h, h * h, u, y);
  const std::vector<double> expected = spring_by_spring(net, system, 1.0, h, h * h, u);
  double worst = 0;
  for (std::size_t i = 0; i < y.size(); ++i)
    worst = std::max(worst, std::abs(y[i] - expected[i]));
  EXPECT_LE(worst, 1e-15 * largest(expected));
}

TEST(ImplicitProduct, ATeamGivesOneThreadsBits) {
  const Simulation sim = falling(64);  // large enough to be split (kMinThreadedNodes)
  const ClothNetwork& net = sim.network();
  ASSERT_GE(net.node_count(), kMinThreadedNodes);
  ImplicitSystem system(net);
  system.linearise(net, sim.state());
  const std::vector<double> u = varied(3 * net.node_count());
  std::vector<double> one(u.size()), split(u.size());
  const double h = 1.0 / 60;
  system.apply(net, 1.0, h, h * h, u, one);
  for (int threads : {2, 3}) {
    StepThreads team(threads);
    system.apply(net, 1.0, h, h * h, u, split, &team);
    EXPECT_EQ(0, std::memcmp(one.data(), split.data(), one.size() * sizeof(double)))
        << threads << " threads";
  }
}

}  // namespace
}  // namespace neurocloth
