// The network step read backwards (network_propagation.h) against central
// differences of the forward step it differentiates: one step of the paper's
// propagation on a stretched, moving cloth with a pinned row, with and
// without a constraints' share, for the start state, the springs' weights and
// the inverse masses. The fit's gradient over whole runs is checked in
// tests/learn/fit/learn_gradient_test.cpp; this pins a wrong line to the step.
#include "core/simulation/network_propagation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/integrators/integrator_factory.h"
#include "support/scene_builder.h"

namespace neurocloth {
namespace {

constexpr double kStep = 1.0 / 240;

struct OneStep {
  ClothNetwork net;
  ClothState in;
  ClothState weight;   // E = weight . (p', v')
  NodeVectors before;  // a constraints' share of dE/dp through the start

  OneStep() {
    const Scene scene = test::SceneBuilder(5, 6, 0.05).pin_top_row().parse();
    net = scene.build_network();
    in = net.rest_state(scene.topology.rest_positions);
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    const std::size_t n = in.size();
    weight.resize(n);
    before.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      in.set_position(i, in.position(i) + 0.008 * Vec3(u(rng), u(rng), u(rng)));
      in.set_velocity(i, 0.5 * Vec3(u(rng), u(rng), u(rng)));
      weight.set_position(i, Vec3(u(rng), u(rng), u(rng)));
      weight.set_velocity(i, Vec3(u(rng), u(rng), u(rng)));
      before.x[i] = u(rng);
      before.y[i] = u(rng);
      before.z[i] = u(rng);
    }
  }

  // E after one forward step from `s` with network `m`, plus before . p.
  double loss(const ClothNetwork& m, const ClothState& s, bool with_before) const {
    ForceInputs inputs;
    ForceContext context;
    NodeVectors F(s.size());
    m.net_forces(s, inputs, context, F);
    ClothState out = s;
    make_network_propagation(m)->step(m, inputs, context, s, F, kStep, out);
    double E = 0;
    for (std::size_t i = 0; i < s.size(); ++i) {
      E += weight.position(i).dot(out.position(i)) + weight.velocity(i).dot(out.velocity(i));
      if (with_before) E += before.x[i] * s.x[i] + before.y[i] * s.y[i] + before.z[i] * s.z[i];
    }
    return E;
  }
};

// Central differences of step `eps` against the adjoint, relative to the
// largest component checked. Measured at most 6.7e-11 of it (the differences'
// round-off); bound 2e-10.
void expect_close(double adjoint, double up, double down, double eps, double scale,
                  const char* what, std::size_t i) {
  const double numeric = (up - down) / (2 * eps);
  EXPECT_NEAR(adjoint, numeric, 2e-10 * scale) << what << " " << i;
}

TEST(NetworkStepAdjoint, MatchesCentralDifferencesOfTheStep) {
  for (bool with_before : {false, true}) {
    SCOPED_TRACE(with_before ? "with a constraints' share" : "unconstrained");
    const OneStep s;
    const std::size_t n = s.in.size();
    ClothState adj = s.weight;
    NodeVectors adj_force(n), forces(n);
    SpringGradients g;
    g.resize(s.net.spring_count());
    std::vector<double> adj_w(n, 0.0);
    network_step_adjoint(s.net, ForceInputs{}, ForceContext{}, s.in, kStep,
                         with_before ? &s.before : nullptr, adj, adj_force, forces, g,
                         adj_w.data());

    const double eps = 1e-6;
    double scale = 0;
    for (std::size_t i = 0; i < n; ++i)
      scale = std::max({scale, std::abs(adj.x[i]), std::abs(adj.vy[i])});
    ASSERT_GT(scale, 0.0);
    for (std::size_t i = 0; i < n; i += 3) {  // the start's positions and velocities
      ClothState up = s.in, down = s.in;
      up.x[i] += eps;
      down.x[i] -= eps;
      expect_close(adj.x[i], s.loss(s.net, up, with_before), s.loss(s.net, down, with_before), eps,
                   scale, "dE/dx", i);
      up = down = s.in;
      up.vy[i] += eps;
      down.vy[i] -= eps;
      expect_close(adj.vy[i], s.loss(s.net, up, with_before), s.loss(s.net, down, with_before), eps,
                   scale, "dE/dvy", i);
    }
    for (std::size_t k = 0; k < s.net.spring_count(); k += 7) {  // the springs' weights
      const double eps_k = 1e-6 * s.net.springs.stiffness[k];
      ClothNetwork up = s.net, down = s.net;
      up.springs.stiffness[k] += eps_k;
      down.springs.stiffness[k] -= eps_k;
      const double numeric =
          (s.loss(up, s.in, with_before) - s.loss(down, s.in, with_before)) / (2 * eps_k);
      // Measured at most 1.5e-7 relative (a difference of relative step 1e-6).
      EXPECT_NEAR(g.stiffness[k], numeric, 3e-7 * std::abs(numeric) + 1e-12) << "spring " << k;
    }
    for (std::size_t i = 0; i < n; i += 5) {  // the inverse masses
      const double w = s.net.masses.inverse_mass[i], eps_w = 1e-6 * w;
      ClothNetwork up = s.net, down = s.net;
      up.masses.inverse_mass[i] += eps_w;
      down.masses.inverse_mass[i] -= eps_w;
      const double numeric =
          (s.loss(up, s.in, with_before) - s.loss(down, s.in, with_before)) / (2 * eps_w);
      // Measured at most 5.3e-9 relative; a pinned node's is exactly 0.
      EXPECT_NEAR(adj_w[i], numeric, 1e-8 * std::abs(numeric) + 1e-12) << "node " << i;
      if (s.net.masses.pinned(i)) {
        EXPECT_EQ(adj_w[i], 0.0) << "a pinned node's mass moves nothing";
      }
    }
  }
}

}  // namespace
}  // namespace neurocloth
