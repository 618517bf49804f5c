// The projective integrator against the equations it solves: its local-global
// iterations against backward Euler itself (the root of its nonlinear
// equations, found here by Newton's method), and its prefactored matrix.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Dense>

#include "core/integrators/implicit_system.h"
#include "core/integrators/integrator.h"
#include "core/integrators/spring_laplacian.h"
#include "core/simulation/simulation.h"
#include "support/scene_builder.h"

namespace neurocloth {
namespace {

// A cloth hanging from its top corners, moving: a few network steps from rest.
struct Moving {
  ClothNetwork net;
  ClothState state;
};

Moving moving_cloth(int n, bool stiffening = false) {
  test::SceneBuilder b(n, n, 0.3 / (n - 1));
  b.hanging().pins(nlohmann::json::array({nlohmann::json{0, 0}, nlohmann::json{0, n - 1}}));
  b.material(400.0, 0.02, 0.2);
  if (stiffening)
    b.set("/cloth/spring_function", {{"type", "stiffening"}, {"strain", 0.01}, {"factor", 20}});
  const Scene scene = b.parse();
  Moving m{scene.build_network(), scene.initial_state()};
  for (std::size_t i = 0; i < m.state.size(); ++i)  // a sideways push
    m.state.vz[i] = 0.5 * std::sin(0.7 * static_cast<double>(i));
  const auto integrator = make_integrator(IntegratorKind::network, m.net);
  NodeVectors f(m.net.node_count());
  ClothState next = m.state;
  for (int k = 0; k < 200; ++k) {
    m.net.net_forces(m.state, f);
    integrator->step(m.net, ForceInputs{}, ForceContext{}, m.state, f, 2e-4, next);
    std::swap(m.state, next);
  }
  return m;
}

double max_difference(const ClothState& a, const ClothState& b) {
  double worst = 0;
  for (std::size_t i = 0; i < a.size(); ++i)
    worst = std::max(worst, (a.position(i) - b.position(i)).norm());
  return worst;
}

// Backward Euler's residual at end velocities v: M (v - v0) - h (F(x0 + h v, v) + M g)
// on free nodes, relative to the largest force in play.
double backward_euler_residual(const ClothNetwork& net, const ClothState& in, const ClothState& out,
                               double h) {
  NodeVectors f(net.node_count());
  net.net_forces(out, f);
  double worst = 0, scale = 0;
  for (std::size_t i = 0; i < net.node_count(); ++i) {
    if (net.masses.free[i] == 0.0) continue;
    const double m = net.mass(i);
    const Vec3 force = f.at(i) + m * net.gravity;
    worst = std::max(worst, (m * (out.velocity(i) - in.velocity(i)) / h - force).norm());
    scale = std::max(scale, force.norm() + m * net.gravity.norm());
  }
  return worst / scale;
}

// Newton's method on backward Euler (the Jacobian M + h D + h^2 K with the
// exact stiffness; the damping's dependence on direction is left out, so it
// converges linearly where the cloth is damped): the root to rounding.
ClothState backward_euler(const ClothNetwork& net, const ClothState& in, double h) {
  const std::size_t n = net.node_count();
  ImplicitSystem system(net);
  ClothState at = in;
  std::vector<double> r(3 * n), dv(3 * n);
  NodeVectors f(n);
  for (int it = 0; it < 100; ++it) {
    for (std::size_t i = 0; i < n; ++i)
      at.set_position(i, in.position(i) + h * at.velocity(i));
    net.net_forces(at, f);
    for (std::size_t i = 0; i < n; ++i) {
      const double m = net.mass(i), free = net.masses.free[i];
      const Vec3 res = h * (f.at(i) + m * net.gravity) - m * (at.velocity(i) - in.velocity(i));
      for (int c = 0; c < 3; ++c)
        r[3 * i + c] = free * res[c];
    }
    system.linearise(net, at, true);
    std::fill(dv.begin(), dv.end(), 0.0);
    system.solve(net, 1.0, h, h * h, r, dv, 1e-14, 10000);
    for (std::size_t i = 0; i < n; ++i)
      at.set_velocity(i, at.velocity(i) + Vec3(dv[3 * i], dv[3 * i + 1], dv[3 * i + 2]));
  }
  for (std::size_t i = 0; i < n; ++i)
    at.set_position(i, in.position(i) + h * at.velocity(i));
  return at;
}

ClothState iterated_step(IntegratorKind kind, const ClothNetwork& net, const ClothState& in,
                         double h, int iterations) {
  const auto integrator = make_integrator(kind, net, kDefaultMinStepFraction, iterations);
  NodeVectors f(net.node_count());
  net.net_forces(in, f);
  ClothState out = in;
  // The first step measures how fast plain iterations converge; the second,
  // from the same state, is Chebyshev-accelerated by that rate.
  integrator->step(net, ForceInputs{}, ForceContext{}, in, f, h, out);
  integrator->step(net, ForceInputs{}, ForceContext{}, in, f, h, out);
  return out;
}

void converges_to_backward_euler(IntegratorKind kind, bool stiffening,
                                 const std::vector<int>& counts) {
  const Moving m = moving_cloth(8, stiffening);
  const double h = 1.0 / 60;
  const ClothState reference = backward_euler(m.net, m.state, h);
  ASSERT_LT(backward_euler_residual(m.net, m.state, reference, h), 1e-9);
  // The step itself moves the cloth by centimetres: the errors below are small against it.
  const double moved = max_difference(reference, m.state);
  ASSERT_GT(moved, 1e-3);
  std::vector<double> errors;
  for (int iterations : counts) {
    errors.push_back(max_difference(iterated_step(kind, m.net, m.state, h, iterations), reference));
    if (errors.size() > 1) {
      EXPECT_LT(errors.back(), errors[errors.size() - 2]) << iterations;
    }
  }
  if (stiffening && kind == IntegratorKind::projective)  // its matrix holds the stiff branch
    EXPECT_LT(errors.back(), 0.1 * errors.front());      // everywhere: slower, still converging
  else
    EXPECT_LT(errors.back(), 1e-7 * moved) << counts.back() << " iterations";
}

TEST(Projective, ConvergesToBackwardEulerAsItsIterationsGrow) {
  converges_to_backward_euler(IntegratorKind::projective, false, {2, 8, 32, 128, 512});
}

TEST(Projective, ConvergesToBackwardEulerOnStiffeningSprings) {
  converges_to_backward_euler(IntegratorKind::projective, true, {2, 8, 32, 128, 512});
}

// Vertex block descent solves the same minimisation one node at a time, each
// with its own Hessian (the stiff branch only where a spring is on it).
TEST(VertexBlockDescent, ConvergesToBackwardEulerAsItsSweepsGrow) {
  converges_to_backward_euler(IntegratorKind::vbd, false, {2, 8, 32, 128, 512});
}

TEST(VertexBlockDescent, ConvergesToBackwardEulerOnStiffeningSprings) {
  converges_to_backward_euler(IntegratorKind::vbd, true, {2, 8, 32, 128, 512});
}

// A node between two pinned ones on springs squeezed to half their rest
// length, nudged off their line: the springs push it sideways, and only its
// mass resists (a compressed spring's transverse stiffness is left out of the
// Hessian), so the Newton step is long and overshoots the springs' rest far
// enough to climb. Halved twice it lowers the node's energy, and that is the
// step taken.
struct SqueezedNode {
  ClothNetwork net;
  ClothState state;
  std::size_t free_node = 0;
};

SqueezedNode squeezed_node(double k, double mass) {
  test::SceneBuilder b(1, 3, 1.0);
  b.springs({"structural"})
      .pins(nlohmann::json::array({nlohmann::json{0, 0}, nlohmann::json{0, 2}}));
  const Scene scene = b.parse();
  SqueezedNode s{scene.build_network(), scene.initial_state()};
  s.net.gravity = Vec3::Zero();
  double side = -1;
  for (std::size_t i = 0; i < s.net.node_count(); ++i) {
    s.state.set_velocity(i, Vec3::Zero());
    if (s.net.masses.free[i] != 0.0) {
      s.free_node = i;
      s.net.masses.inverse_mass[i] = 1 / mass;
      s.state.set_position(i, Vec3(0, 0.1, 0));
    } else {
      s.state.set_position(i, Vec3(side, 0, 0));
      side = -side;
    }
  }
  for (std::size_t sp = 0; sp < s.net.spring_count(); ++sp) {
    s.net.springs.stiffness[sp] = k;
    s.net.springs.damping[sp] = 0;
    s.net.springs.rest_length[sp] = 2;
  }
  return s;
}

TEST(VertexBlockDescent, HalvesANewtonStepThatWouldRaiseTheNodesEnergy) {
  const double k = 1e4, mass = 1, h = 0.1;
  const SqueezedNode s = squeezed_node(k, mass);
  ASSERT_EQ(s.net.spring_count(), 2u);
  ASSERT_EQ(s.net.springs.function.kind, SpringFunctionKind::linear);
  const Vec3 x0 = s.state.position(s.free_node);
  std::vector<Vec3> pinned;
  for (std::size_t i = 0; i < s.net.node_count(); ++i)
    if (i != s.free_node) pinned.push_back(s.state.position(i));
  ASSERT_EQ(pinned.size(), 2u);

  // The node's block of the backward-Euler energy (no velocity, no gravity:
  // its inertial target is where it is), h^2-scaled as vbd's, at displacement u.
  const double kh = h * h * k;
  auto energy = [&](const Vec3& u) {
    double e = 0.5 * mass * u.squaredNorm();
    for (const Vec3& p : pinned) {
      const double stretch = (x0 + u - p).norm() - 2;
      e += 0.5 * kh * stretch * stretch;
    }
    return e;
  };
  // Its Newton step from u = 0, the compressed springs' transverse part left out.
  Eigen::Matrix3d hessian = mass * Eigen::Matrix3d::Identity();
  Vec3 gradient = Vec3::Zero();
  for (const Vec3& p : pinned) {
    const Vec3 d = x0 - p;
    const Vec3 n = d.normalized();
    ASSERT_LT(d.norm(), 2.0);  // compressed
    gradient += kh * (d.norm() - 2) * n;
    hessian += kh * n * n.transpose();
  }
  const Vec3 step = -hessian.inverse() * gradient;
  ASSERT_GT(energy(step), energy(Vec3::Zero()));         // the full step climbs
  ASSERT_GT(energy(0.5 * step), energy(Vec3::Zero()));   // so does half of it
  ASSERT_LT(energy(0.25 * step), energy(Vec3::Zero()));  // a quarter descends

  // One sweep: the node lands a quarter of its Newton step along.
  const auto vbd = make_integrator(IntegratorKind::vbd, s.net, kDefaultMinStepFraction, 1);
  NodeVectors f(s.net.node_count());
  s.net.net_forces(s.state, f);
  ClothState out = s.state;
  vbd->step(s.net, ForceInputs{}, ForceContext{}, s.state, f, h, out);
  const Vec3 landed = out.position(s.free_node);
  // Measured: exactly there, 0 m apart, with either spring kernel (vbd forms
  // its springs' terms itself); the full step would end 5 m off, a refused one
  // 1.7 m. Bound 1e-12 of the step (6.6 m).
  EXPECT_LT((landed - (x0 + 0.25 * step)).norm(), 1e-12 * step.norm());
  EXPECT_LT(energy(landed - x0), energy(Vec3::Zero()));
}

TEST(Projective, RefactorsWhenAWeightChanges) {
  Moving m = moving_cloth(6);
  const double h = 1.0 / 60;
  const auto used = make_integrator(IntegratorKind::projective, m.net, kDefaultMinStepFraction, 64);
  NodeVectors f(m.net.node_count());
  ClothState out = m.state, fresh_out = m.state;
  m.net.net_forces(m.state, f);
  used->step(m.net, ForceInputs{}, ForceContext{}, m.state, f, h, out);
  const ClothState before = out;
  for (double& k : m.net.springs.stiffness)  // a material slider moves
    k *= 3;
  m.net.net_forces(m.state, f);
  used->step(m.net, ForceInputs{}, ForceContext{}, m.state, f, h,
             out);  // once: solved near the old factor
  used->step(m.net, ForceInputs{}, ForceContext{}, m.state, f, h, out);  // kept: refactored
  // An integrator that never saw the old weights steps to the same bits; a
  // stale factor (or a stale convergence rate) would not.
  const auto fresh =
      make_integrator(IntegratorKind::projective, m.net, kDefaultMinStepFraction, 64);
  fresh->step(m.net, ForceInputs{}, ForceContext{}, m.state, f, h, fresh_out);
  EXPECT_EQ(max_difference(out, fresh_out), 0.0);
  EXPECT_GT(max_difference(out, before), 1e-6);  // and the change mattered
}

// A one-off step (another h: the end of a frame, an adaptive trial) is solved
// by CG preconditioned with the factor it has, to the same fixed point.
TEST(Projective, AOneOffStepSolvesItsOwnMatrix) {
  const Moving m = moving_cloth(8);
  const double h = 1.0 / 60, other = 0.37 / 60;
  NodeVectors f(m.net.node_count());
  m.net.net_forces(m.state, f);
  const auto used =
      make_integrator(IntegratorKind::projective, m.net, kDefaultMinStepFraction, 512);
  ClothState out = m.state, direct = m.state;
  used->step(m.net, ForceInputs{}, ForceContext{}, m.state, f, h, out);  // factored for h
  const StepReport r = used->step(m.net, ForceInputs{}, ForceContext{}, m.state, f, other, out);
  EXPECT_TRUE(r.cg_converged);
  const auto fresh =
      make_integrator(IntegratorKind::projective, m.net, kDefaultMinStepFraction, 512);
  fresh->step(m.net, ForceInputs{}, ForceContext{}, m.state, f, other,
              direct);  // factored for `other`
  const ClothState reference = backward_euler(m.net, m.state, other);
  const double moved = max_difference(reference, m.state);
  EXPECT_LT(max_difference(out, reference), 1e-7 * moved);
  EXPECT_LT(max_difference(direct, reference), 1e-7 * moved);
}

// Its factor is made for one step: the adaptive rule, which would ask for a new
// one at every trial, is refused by name.
TEST(Projective, TakesFixedStepsOnly) {
  SolverSettings s;
  s.integrator = IntegratorKind::projective;
  s.adaptive = true;
  try {
    validate(s);
    FAIL() << "no refusal";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("solver.adaptive"), std::string::npos) << e.what();
  }
  s.adaptive = false;
  EXPECT_NO_THROW(validate(s));
}

// A cloth whose factor would not fit is refused by name, and a live change of
// integrator to it leaves the simulation as it was.
TEST(Projective, RefusesAClothBeyondItsFactorsLimit) {
  ClothTopology big;
  big.rest_positions.assign(513 * 513, Vec3(0, 0, 0));
  for (std::size_t i = 0; i < big.rest_positions.size(); ++i)
    big.rest_positions[i] = Vec3(static_cast<double>(i % 513), 0, static_cast<double>(i / 513));
  Material material;
  const ClothNetwork net = ClothNetwork::build(big, material);
  try {
    make_integrator(IntegratorKind::projective, net);
    FAIL() << "no refusal";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("263169 nodes"), std::string::npos) << e.what();
  }
  Simulation sim(net, net.rest_state(big.rest_positions), SolverSettings{});
  SolverSettings projective = sim.settings();
  projective.integrator = IntegratorKind::projective;
  EXPECT_THROW(sim.set_solver_settings(projective), std::invalid_argument);
  EXPECT_EQ(sim.settings().integrator, IntegratorKind::network);
  EXPECT_EQ(sim.advance(1e-3), RunStatus::ok);  // still steps, with what it had
}

// The largest difference between P x and rhs, P row by row from the
// matrix's definition (planar: all x, then y, then z).
double residual(const Moving& m, const std::vector<double>& node, const std::vector<double>& spring,
                const std::vector<double>& xyz, const std::vector<double>& rhs) {
  const std::size_t n = m.net.node_count();
  std::vector<double> px(3 * n);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t c = 0; c < 3; ++c)
      px[c * n + i] = (m.net.masses.free[i] != 0.0 ? node[i] : 1.0) * xyz[c * n + i];
  for (std::size_t s = 0; s < spring.size(); ++s) {
    const std::size_t a = std::size_t(m.net.springs.node_a[s]);
    const std::size_t b = std::size_t(m.net.springs.node_b[s]);
    const bool fa = m.net.masses.free[a] != 0.0, fb = m.net.masses.free[b] != 0.0;
    for (std::size_t c = 0; c < 3; ++c) {
      if (fa) px[c * n + a] += spring[s] * (xyz[c * n + a] - (fb ? xyz[c * n + b] : 0.0));
      if (fb) px[c * n + b] += spring[s] * (xyz[c * n + b] - (fa ? xyz[c * n + a] : 0.0));
    }
  }
  double worst = 0;
  for (std::size_t i = 0; i < 3 * n; ++i)
    worst = std::max(worst, std::abs(px[i] - rhs[i]));
  return worst;
}

struct Weights {
  std::vector<double> node, spring;
};
Weights varied_weights(const Moving& m) {
  Weights w{std::vector<double>(m.net.node_count()), std::vector<double>(m.net.spring_count())};
  for (std::size_t i = 0; i < w.node.size(); ++i)
    w.node[i] = 0.01 * (1 + 0.1 * static_cast<double>(i % 3));
  for (std::size_t s = 0; s < w.spring.size(); ++s)
    w.spring[s] = 0.5 + 0.01 * static_cast<double>(s % 7);
  return w;
}

// The Laplacian solve against the matrix it factors.
TEST(SpringLaplacian, SolvesItsMatrix) {
  const Moving m = moving_cloth(5);
  const std::size_t n = m.net.node_count();
  const Weights w = varied_weights(m);
  SpringLaplacian P;
  ASSERT_TRUE(P.factor(m.net.springs, w.node, w.spring, m.net.masses.free));
  EXPECT_FALSE(P.dissected());  // too small to pay for two threads
  std::vector<double> xyz(3 * n), rhs(3 * n);
  for (std::size_t i = 0; i < 3 * n; ++i)
    xyz[i] = rhs[i] = std::cos(1.3 * static_cast<double>(i));
  P.solve3(xyz.data());
  EXPECT_LE(residual(m, w.node, w.spring, xyz, rhs), 1e-12);
  // A free cloth without mass has no factor (and says so).
  std::vector<double> none(n, 0.0), all_free(n, 1.0);
  EXPECT_FALSE(P.factor(m.net.springs, none, w.spring, all_free));
  EXPECT_FALSE(P.factored());
}

// From kMinThreadedNodes the factor is two halves and a separator: it solves
// its matrix as well, and a team's two threads give one thread's bits.
TEST(SpringLaplacian, ADissectedFactorSolvesItsMatrixOnAnyTeam) {
  const Moving m = moving_cloth(64);
  const std::size_t n = m.net.node_count();
  ASSERT_GE(n, kMinThreadedNodes);
  const Weights w = varied_weights(m);
  SpringLaplacian P;
  ASSERT_TRUE(P.factor(m.net.springs, w.node, w.spring, m.net.masses.free));
  EXPECT_TRUE(P.dissected());
  std::vector<double> rhs(3 * n);
  for (std::size_t i = 0; i < 3 * n; ++i)
    rhs[i] = std::cos(1.3 * static_cast<double>(i));
  std::vector<double> one = rhs;
  P.solve3(one.data());
  // Measured 2026-12-06: 2.7e-15 (the right-hand side is of order 1).
  EXPECT_LE(residual(m, w.node, w.spring, one, rhs), 4e-15);
  for (int threads : {2, 3}) {
    StepThreads team(threads);
    std::vector<double> split = rhs;
    P.solve3(split.data(), &team);
    EXPECT_EQ(split, one) << threads << " threads";
  }
}

}  // namespace
}  // namespace neurocloth
