// The spring layer read backwards (spring_adjoint.h) against central
// differences of the forces it differentiates, through each kernel compiled
// in, on grids whose chunks take every path: a wide grid's rows (neighbours
// summed in registers) and columns (direct chunks), a narrow grid's columns
// (chunks stored and accumulated). The fit's gradient as a whole is checked in
// tests/learn/fit/learn_gradient_test.cpp; this pins a wrong line to the layer.
#include "core/network/spring_adjoint.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "support/scene_builder.h"

namespace neurocloth {
namespace {

double dot(const NodeVectors& a, const NodeVectors& b) {
  double sum = 0;
  for (std::size_t i = 0; i < a.size(); ++i)
    sum += a.x[i] * b.x[i] + a.y[i] * b.y[i] + a.z[i] * b.z[i];
  return sum;
}

// lF . F(state): what the adjoint differentiates.
double weighted_forces(const ClothNetwork& net, const ClothState& s, const NodeVectors& lF,
                       SpringKernel kernel) {
  ForceContext context;
  context.kernel = kernel;
  NodeVectors F(s.size());
  net.net_forces(s, ForceInputs{}, context, F);
  return dot(F, lF);
}

struct Case {
  const char* name;
  int rows, cols;
  SpringFunctionKind kind;
};

// A stretched, moving cloth: nodes up to 1 cm off their rest on a 5 cm grid
// (strains to 40%, so stiffening springs on both sides of their threshold),
// velocities up to 1 m/s, weights of every size; random dE/dF.
struct StretchedCloth {
  ClothNetwork net;
  ClothState state;
  NodeVectors adj_force;

  explicit StretchedCloth(const Case& c) {
    const Scene scene = test::SceneBuilder(c.rows, c.cols, 0.05).parse();
    net = scene.build_network();
    net.springs.function.kind = c.kind;
    state = net.rest_state(scene.topology.rest_positions);
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    const std::size_t n = state.size();
    adj_force.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      state.set_position(i, state.position(i) + 0.01 * Vec3(u(rng), u(rng), u(rng)));
      state.set_velocity(i, Vec3(u(rng), u(rng), u(rng)));
      adj_force.x[i] = u(rng);
      adj_force.y[i] = u(rng);
      adj_force.z[i] = u(rng);
    }
    for (std::size_t k = 0; k < net.spring_count(); ++k) {
      net.springs.stiffness[k] *= 1.0 + 0.5 * u(rng);
      net.springs.damping[k] *= 1.0 + 0.5 * u(rng);
      net.springs.rest_length[k] *= 1.0 + 0.1 * u(rng);
    }
  }
};

const Case kCases[] = {{"24 columns, linear", 6, 24, SpringFunctionKind::linear},
                       {"24 columns, stiffening", 6, 24, SpringFunctionKind::stiffening},
                       {"6 columns, linear", 7, 6, SpringFunctionKind::linear},
                       {"6 columns, stiffening", 7, 6, SpringFunctionKind::stiffening}};

TEST(SpringAdjoint, IsTheDerivativeOfTheForcesThroughEachKernel) {
  for (const SpringKernel kernel : {SpringKernel::portable, SpringKernel::avx512}) {
    if (!kernel_unavailable(kernel).empty()) continue;
    for (const Case& c : kCases) {
      SCOPED_TRACE(std::string(c.name) + ", " + to_string(kernel) + " kernel");
      const StretchedCloth cloth(c);
      const ClothNetwork& net = cloth.net;
      const std::size_t n = cloth.state.size(), springs = net.spring_count();
      ClothState adj(n);
      SpringGradients g;
      g.resize(springs);
      spring_forces_adjoint(net, cloth.state, cloth.adj_force, adj, g, kernel);

      // Along one random direction of the state, and one of the weights. A
      // step of 1e-7: no spring's strain crosses its threshold within it.
      std::mt19937 rng(5);
      std::uniform_real_distribution<double> u(-1.0, 1.0);
      const double eps = 1e-7;
      ClothState up = cloth.state, down = cloth.state;
      double predicted = 0;
      for (std::size_t i = 0; i < n; ++i) {
        for (auto field : {&ClothState::x, &ClothState::y, &ClothState::z, &ClothState::vx,
                           &ClothState::vy, &ClothState::vz}) {
          const double d = u(rng);
          (up.*field)[i] += eps * d;
          (down.*field)[i] -= eps * d;
          predicted += (adj.*field)[i] * d;
        }
      }
      const double differences = (weighted_forces(net, up, cloth.adj_force, kernel) -
                                  weighted_forces(net, down, cloth.adj_force, kernel)) /
                                 (2 * eps);
      EXPECT_NEAR(predicted, differences, 1e-6 * std::abs(differences)) << "state";

      ClothNetwork heavier = net, lighter = net;
      double predicted_w = 0;
      for (std::size_t k = 0; k < springs; ++k) {
        const double d1 = u(rng) * net.springs.stiffness[k], d2 = u(rng) * net.springs.damping[k],
                     dL = u(rng) * net.springs.rest_length[k];
        heavier.springs.stiffness[k] += eps * d1;
        lighter.springs.stiffness[k] -= eps * d1;
        heavier.springs.damping[k] += eps * d2;
        lighter.springs.damping[k] -= eps * d2;
        heavier.springs.rest_length[k] += eps * dL;
        lighter.springs.rest_length[k] -= eps * dL;
        predicted_w += g.stiffness[k] * d1 + g.damping[k] * d2 + g.rest_length[k] * dL;
      }
      const double differences_w =
          (weighted_forces(heavier, cloth.state, cloth.adj_force, kernel) -
           weighted_forces(lighter, cloth.state, cloth.adj_force, kernel)) /
          (2 * eps);
      EXPECT_NEAR(predicted_w, differences_w, 1e-6 * std::abs(differences_w)) << "weights";
    }
  }
}

// The kernels' forces differ in their last bits (spring_kernel.h); so do
// their adjoints, and no more.
TEST(SpringAdjoint, TheKernelsAgreeToRoundOff) {
  if (!avx512_kernel_available()) GTEST_SKIP() << kernel_unavailable(SpringKernel::avx512);
  for (const Case& c : kCases) {
    SCOPED_TRACE(c.name);
    const StretchedCloth cloth(c);
    const std::size_t n = cloth.state.size();
    ClothState adj[2] = {ClothState(n), ClothState(n)};
    SpringGradients g[2];
    const SpringKernel kernels[2] = {SpringKernel::portable, SpringKernel::avx512};
    for (int j = 0; j < 2; ++j) {
      g[j].resize(cloth.net.spring_count());
      spring_forces_adjoint(cloth.net, cloth.state, cloth.adj_force, adj[j], g[j], kernels[j]);
    }
    const auto expect_close = [](const auto& a, const auto& b, const char* what) {
      double scale = 0, worst = 0;
      for (std::size_t i = 0; i < a.size(); ++i) {
        scale = std::max(scale, std::abs(a[i]));
        worst = std::max(worst, std::abs(a[i] - b[i]));
      }
      EXPECT_LE(worst, 1e-12 * scale) << what;
    };
    expect_close(adj[0].x, adj[1].x, "dE/dx");
    expect_close(adj[0].vz, adj[1].vz, "dE/dvz");
    expect_close(g[0].stiffness, g[1].stiffness, "dE/db1");
    expect_close(g[0].damping, g[1].damping, "dE/db2");
    expect_close(g[0].rest_length, g[1].rest_length, "dE/dL");
  }
}

TEST(SpringAdjoint, AKernelTheCpuCannotRunIsRefusedBeforeAnyWork) {
  if (avx512_kernel_available()) GTEST_SKIP() << "this CPU runs the AVX-512 kernel";
  const StretchedCloth cloth(kCases[0]);
  ClothState adj(cloth.state.size());
  SpringGradients g;
  g.resize(cloth.net.spring_count());
  EXPECT_THROW(
      spring_forces_adjoint(cloth.net, cloth.state, cloth.adj_force, adj, g, SpringKernel::avx512),
      std::invalid_argument);
  EXPECT_EQ(g.stiffness, std::vector<double>(cloth.net.spring_count(), 0.0));
}

}  // namespace
}  // namespace neurocloth
