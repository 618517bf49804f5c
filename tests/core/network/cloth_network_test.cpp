// The spring and mass layers against hand-computed forces and energies. Every
// test that evaluates the force neurons runs through each spring kernel
// (spring_kernel.h): the portable one on every CPU, the AVX-512 one where the
// CPU has it (skipped elsewhere), so the loop a machine without AVX-512 runs
// is tested on one with it too.
#include "core/network/cloth_network.h"

#include <gtest/gtest.h>

#include <cmath>
#include <ostream>
#include <stdexcept>
#include <string>

#include "core/base/step_threads.h"
#include "core/scene/grid_builder.h"
#include "support/test_support.h"

namespace neurocloth {

// Test names and failures say the kernel by name.
void PrintTo(SpringKernel kernel, std::ostream* os) {
  *os << to_string(kernel);
}

namespace {

// Two free nodes, one spring, no gravity: a network small enough to check by hand.
ClothNetwork two_nodes(double k, double d, double rest) {
  ClothTopology t;
  t.rest_positions = {Vec3(0, 0, 0), Vec3(rest, 0, 0)};
  t.springs = {{0, 1, SpringFamily::structural}};
  Material m;
  m.spring_constant = k;
  m.viscosity = d;
  m.node_mass = 0.5;
  ClothNetwork net = ClothNetwork::build(t, m);
  net.gravity = Vec3::Zero();
  return net;
}

class ClothNetworkKernel : public ::testing::TestWithParam<SpringKernel> {
 protected:
  void SetUp() override {
    const std::string missing = kernel_unavailable(GetParam());
    if (!missing.empty()) GTEST_SKIP() << missing;
  }
  SpringKernel kernel() const { return GetParam(); }
  // One thread in double, as net_forces(state, force) evaluates, by this kernel.
  ForceContext context() const {
    ForceContext c;
    c.kernel = kernel();
    return c;
  }
};

INSTANTIATE_TEST_SUITE_P(Kernels, ClothNetworkKernel,
                         ::testing::Values(SpringKernel::portable, SpringKernel::avx512),
                         [](const ::testing::TestParamInfo<SpringKernel>& info) {
                           return std::string(to_string(info.param));
                         });

TEST_P(ClothNetworkKernel, LinearSpringForceByHand) {
  // Rest length 1, stretched to |(2, 1, 2)| = 3: elongation 2, force k * 2 = 20 N
  // along (2, 1, 2) / 3 on node 0, the opposite on node 1.
  const ClothNetwork net = two_nodes(10.0, 0.0, 1.0);
  ClothState s(2);
  s.set_position(1, Vec3(2, 1, 2));
  NodeVectors F(2);
  net.net_forces(s, ForceInputs{}, context(), F);
  EXPECT_NEAR(F.at(0).x(), 20.0 * 2 / 3, 1e-13);
  EXPECT_NEAR(F.at(0).y(), 20.0 * 1 / 3, 1e-13);
  EXPECT_NEAR(F.at(0).z(), 20.0 * 2 / 3, 1e-13);
  EXPECT_NEAR((F.at(0) + F.at(1)).norm(), 0.0, 1e-14);
}

TEST_P(ClothNetworkKernel, DampingActsAlongTheSpringOnly) {
  // Spring along x at rest; node 1 moves with (3, 4, 0): only the 3 m/s along the
  // spring is damped, force on node 0 = d * 3 = 6 N along +x.
  const ClothNetwork net = two_nodes(10.0, 2.0, 1.0);
  ClothState s(2);
  s.set_position(1, Vec3(1, 0, 0));
  s.set_velocity(1, Vec3(3, 4, 0));
  NodeVectors F(2);
  net.net_forces(s, ForceInputs{}, context(), F);
  EXPECT_NEAR(F.at(0).x(), 6.0, 1e-13);
  EXPECT_NEAR(F.at(0).y(), 0.0, 1e-13);
  EXPECT_NEAR(F.at(1).x(), -6.0, 1e-13);
}

TEST_P(ClothNetworkKernel, ZeroLengthSpringIsSkippedNotDividedBy) {
  const ClothNetwork net = two_nodes(10.0, 1.0, 1.0);
  ClothState s(2);  // both nodes at the origin: the spring has no direction
  s.set_velocity(1, Vec3(1, 2, 3));
  NodeVectors F(2);
  net.net_forces(s, ForceInputs{}, context(), F);
  EXPECT_TRUE(F.at(0).allFinite());
  EXPECT_EQ(F.at(0), Vec3::Zero());
  EXPECT_EQ(F.at(1), Vec3::Zero());
  EXPECT_EQ(net.degenerate_springs(s), 1);
  EXPECT_TRUE(std::isfinite(net.energy(s).total()));
}

TEST_P(ClothNetworkKernel, StiffeningSpringForceIsMinusEnergyGradient) {
  ClothNetwork net = two_nodes(100.0, 0.0, 1.0);
  net.springs.function = {SpringFunctionKind::stiffening, 0.1, 10.0};
  for (double len : {0.7, 1.05, 1.1 + 1e-3, 1.3, 2.0}) {
    ClothState s(2);
    s.set_position(1, Vec3(len, 0, 0));
    NodeVectors F(2);
    net.net_forces(s, ForceInputs{}, context(), F);
    const double h = 1e-6;
    ClothState sp = s, sm = s;
    sp.x[1] += h;
    sm.x[1] -= h;
    const double dE = (net.energy(sp).spring - net.energy(sm).spring) / (2 * h);
    EXPECT_NEAR(F.at(1).x(), -dE, 1e-6 * std::max(1.0, std::abs(dE))) << "length " << len;
  }
  // Beyond 10% strain the spring is 10 times stiffer: at strain 0.3,
  // force = k (0.3 + 9 * 0.2) = 210 N.
  ClothState s(2);
  s.set_position(1, Vec3(1.3, 0, 0));
  NodeVectors F(2);
  net.net_forces(s, ForceInputs{}, context(), F);
  EXPECT_NEAR(F.at(0).x(), 210.0, 1e-9);
}

TEST_P(ClothNetworkKernel, ExternalForceAndGravityReachTheAcceleration) {
  ClothNetwork net = two_nodes(0.0, 0.0, 1.0);
  net.gravity = Vec3(0, -10, 0);
  ForceInputs in;
  in.external_force.resize(2);
  in.external_force.x[1] = 3.0;  // N on a 0.5 kg node: 6 m/s^2
  net.set_pinned(0, true);
  ClothState s(2);
  s.set_position(1, Vec3(1, 0, 0));
  NodeVectors F(2), a(2);
  net.net_forces(s, in, context(), F);
  net.accelerations(F, a);
  EXPECT_EQ(a.at(0), Vec3::Zero());  // pinned
  EXPECT_NEAR(a.at(1).x(), 6.0, 1e-14);
  EXPECT_NEAR(a.at(1).y(), -10.0, 1e-14);
}

// The scene's start with every node moved up to 1 cm and given a velocity up
// to 1 m/s per axis, pseudo-randomly from `seed`.
ClothState shaken(const Scene& scene, unsigned seed) {
  ClothState s = scene.initial_state();
  auto rnd = [&seed] {
    seed = seed * 1103515245u + 12345u;
    return ((seed >> 8) % 2001) / 1000.0 - 1.0;
  };
  for (std::size_t i = 0; i < s.size(); ++i) {
    s.set_position(i, s.position(i) + 0.01 * Vec3(rnd(), rnd(), rnd()));
    s.set_velocity(i, Vec3(rnd(), rnd(), rnd()));
  }
  return s;
}

TEST_P(ClothNetworkKernel, ForcesSumToZeroOnAClothAndMatchTheSpringOutputs) {
  // Newton's third law through the +-1 incidence weights, on a real cloth in a
  // random configuration (exercises both the direct and the two-pass chunks).
  Scene scene = test::asset_scene("free_cloth");
  const ClothNetwork net = scene.build_network();
  const ClothState s = shaken(scene, 7);
  NodeVectors F(s.size());
  net.net_forces(s, ForceInputs{}, context(), F);
  Vec3 sum = Vec3::Zero();
  double scale = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    sum += F.at(i);
    scale += F.at(i).norm();
  }
  EXPECT_LT(sum.norm(), 1e-13 * scale);

  // The same forces, summed by hand from the per-spring outputs.
  SpringActivations act;
  net.spring_outputs(s, act, SpringPrecision::float64, kernel());
  std::vector<Vec3> by_hand(s.size(), Vec3::Zero());
  for (std::size_t k = 0; k < net.spring_count(); ++k) {
    const Vec3 f(act.fx[k], act.fy[k], act.fz[k]);
    by_hand[net.springs.node_a[k]] += f;
    by_hand[net.springs.node_b[k]] -= f;
  }
  for (std::size_t i = 0; i < s.size(); ++i)
    EXPECT_LT((by_hand[i] - F.at(i)).norm(), 1e-12 * scale) << i;
}

// Every spring's output of `precision` against the textbook formula in double
// (a true square root and a division), on a cloth whose chunks end in
// part-filled vectors (rows of 7 and 6 springs, as chunk tails leave them),
// linear and stiffening, with one spring of zero length (no direction: no
// force). Each term of a force may be off by `ulps` of its own size.
void expect_textbook_spring_outputs(SpringPrecision precision, SpringKernel kernel, double ulps) {
  for (const SpringFunctionKind kind :
       {SpringFunctionKind::linear, SpringFunctionKind::stiffening}) {
    Scene scene = test::asset_scene("free_cloth");
    ClothNetwork net = scene.build_network();
    net.springs.function = {kind, 0.05, 10.0};
    ClothState s = shaken(scene, 11);
    const int a0 = net.springs.node_a[3], b0 = net.springs.node_b[3];
    s.set_position(b0, s.position(a0));
    SpringActivations act;
    net.spring_outputs(s, act, precision, kernel);
    int springs_with_direction = 0;
    for (std::size_t k = 0; k < net.spring_count(); ++k) {
      const int a = net.springs.node_a[k], b = net.springs.node_b[k];
      const Vec3 d = s.position(b) - s.position(a);
      const double len = std::sqrt(d.squaredNorm());
      const Vec3 got(act.fx[k], act.fy[k], act.fz[k]);
      if (len <= kMinSpringLength) {
        EXPECT_EQ(got, Vec3::Zero()) << k;
        continue;
      }
      ++springs_with_direction;
      const double rest = net.springs.rest_length[k];
      const double b1 = net.springs.stiffness[k], b2 = net.springs.damping[k];
      const Vec3 dv = s.velocity(b) - s.velocity(a);
      const double magnitude =
          b1 * net.springs.function.force(len - rest, rest) + b2 * dv.dot(d) / len;
      const Vec3 want = magnitude / len * d;
      const double scale = b1 * net.springs.function.max_slope() * len + b2 * dv.norm();
      EXPECT_LT((got - want).norm(), ulps * scale) << "spring " << k << ", " << to_string(kind);
    }
    EXPECT_EQ(springs_with_direction, static_cast<int>(net.spring_count()) - 1);
  }
}

// The step's 1/len (reciprocal_sqrt.h, or the hand-vectorised estimate plus
// Newton steps) must be round-off: a few ulp of each term, and one Newton
// step fewer fails by 1e-9.
TEST_P(ClothNetworkKernel, EverySpringOutputIsTheTextbookForceToRoundOff) {
  expect_textbook_spring_outputs(SpringPrecision::float64, kernel(), 1e-14);
}

// float's unit round-off is 2^-24; its epsilon 2^-23.
constexpr double kFloatEpsilon = 1.1920928955078125e-7;

// The float path (SpringPrecision::float32): each input is rounded to float
// once (|d|, |dv| within 2^-24 relative), len and 1/len carry a few ulp, so
// every term is off by a few float ulp of its own size: 8 epsilon. One Newton
// step fewer on vrsqrt14ps (2^-14) or the portable seed's (5e-6 after two)
// fails it.
TEST_P(ClothNetworkKernel, EverySpringOutputInFloatIsTheForceToFloatRoundOff) {
  expect_textbook_spring_outputs(SpringPrecision::float32, kernel(), 8 * kFloatEpsilon);
}

// The step's own sweep in float (direct chunks, rows summed in registers,
// chunks through accumulate_chunk, on one thread and split over two) against
// double, node by node: each node's sum is off by at most its springs' float
// round-off (the test above), and the split gives the same bits as one thread.
TEST_P(ClothNetworkKernel, NetForcesInFloatAreTheDoubleForcesToFloatRoundOffOnAnyThreads) {
  // Large enough that two threads split the sweep (kMinThreadedNodes).
  Scene scene = resized_grid(test::asset_scene("hanging"), 72);
  const ClothNetwork net = scene.build_network();
  const ClothState s = shaken(scene, 5);
  NodeVectors in_double(s.size()), in_float(s.size()), split(s.size());
  ForceContext ctx = context();
  net.net_forces(s, ForceInputs{}, ctx, in_double);
  ctx.precision = SpringPrecision::float32;
  net.net_forces(s, ForceInputs{}, ctx, in_float);
  std::vector<double> bound(s.size(), 0.0);
  for (std::size_t k = 0; k < net.spring_count(); ++k) {
    const int a = net.springs.node_a[k], b = net.springs.node_b[k];
    const Vec3 d = s.position(b) - s.position(a);
    const double scale = net.springs.stiffness[k] * net.springs.function.max_slope() * d.norm() +
                         net.springs.damping[k] * (s.velocity(b) - s.velocity(a)).norm();
    bound[a] += 8 * kFloatEpsilon * scale;
    bound[b] += 8 * kFloatEpsilon * scale;
  }
  bool differs = false;
  for (std::size_t i = 0; i < s.size(); ++i) {
    EXPECT_LE((in_float.at(i) - in_double.at(i)).norm(), bound[i]) << i;
    differs = differs || in_float.at(i) != in_double.at(i);
  }
  EXPECT_TRUE(differs) << "the float path computed in double";
  OwnedStepThreads two(2);
  ctx.threads = two.get();
  net.net_forces(s, ForceInputs{}, ctx, split);
  for (std::size_t i = 0; i < s.size(); ++i)
    EXPECT_EQ(split.at(i), in_float.at(i)) << i;
}

// The double sweep split over two and three threads (an odd split cuts rows
// mid-row) gives each node the bits one thread gives: chunks that cross a
// part's edge are evaluated by both parts, each adding to its own nodes.
TEST_P(ClothNetworkKernel, NetForcesSplitOverThreadsAreTheOneThreadBits) {
  Scene scene = resized_grid(test::asset_scene("hanging"), 72);
  const ClothNetwork net = scene.build_network();
  const ClothState s = shaken(scene, 9);
  NodeVectors one(s.size()), split(s.size());
  ForceContext ctx = context();
  net.net_forces(s, ForceInputs{}, ctx, one);
  for (int threads : {2, 3}) {
    OwnedStepThreads team(threads);
    ctx.threads = team.get();
    net.net_forces(s, ForceInputs{}, ctx, split);
    for (std::size_t i = 0; i < s.size(); ++i)
      ASSERT_EQ(split.at(i), one.at(i)) << "node " << i << ", " << threads << " threads";
  }
}

TEST_P(ClothNetworkKernel, WeightsArePerSpringAndPerNodeAndWritable) {
  Scene scene = test::asset_scene("hanging");
  ClothNetwork net = scene.build_network();
  ASSERT_EQ(net.springs.stiffness.size(), net.spring_count());
  ASSERT_EQ(net.springs.damping.size(), net.spring_count());
  ASSERT_EQ(net.masses.inverse_mass.size(), net.node_count());
  EXPECT_DOUBLE_EQ(net.masses.inverse_mass[5], 1.0 / 0.01);
  // Doubling one spring's stiffness weight doubles that spring's force only.
  ClothState s = scene.initial_state();
  for (std::size_t i = 0; i < s.size(); ++i)
    s.y[i] -= 0.001 * static_cast<double>(i % 7);
  SpringActivations before, after;
  net.spring_outputs(s, before, SpringPrecision::float64, kernel());
  net.springs.stiffness[3] *= 2.0;
  net.spring_outputs(s, after, SpringPrecision::float64, kernel());
  EXPECT_NEAR(after.fy[3], 2.0 * before.fy[3], 1e-12 * std::abs(before.fy[3]) + 1e-15);
  EXPECT_EQ(after.fy[4], before.fy[4]);
}

TEST(ClothNetwork, EnergyByHand) {
  ClothNetwork net = two_nodes(10.0, 0.0, 1.0);
  net.gravity = Vec3(0, -10, 0);
  ClothState s(2);
  s.set_position(1, Vec3(3, 2, 0));  // length sqrt(13)
  s.set_velocity(0, Vec3(1, 0, 0));
  const Energy e = net.energy(s);
  EXPECT_NEAR(e.kinetic, 0.5 * 0.5 * 1.0, 1e-15);
  EXPECT_NEAR(e.spring, 0.5 * 10.0 * std::pow(std::sqrt(13.0) - 1.0, 2), 1e-12);
  EXPECT_NEAR(e.gravity, 0.5 * 10.0 * 2.0, 1e-12);
}

// The material is applied once, at build, with each node's share of it.
TEST(ClothNetwork, BuildWeighsEachNodeByItsShare) {
  ClothTopology t;
  t.rest_positions = {Vec3(0, 0, 0), Vec3(1, 0, 0)};
  t.springs = {{0, 1, SpringFamily::structural}};
  Material m;
  m.node_mass = 0.5;
  const ClothNetwork net = ClothNetwork::build(t, m, {}, {1.0, 0.25});
  EXPECT_EQ(net.mass(0), 0.5);
  EXPECT_EQ(net.mass(1), 0.125);
  EXPECT_EQ(ClothNetwork::build(t, m).mass(1), 0.5) << "no shares: one node mass each";
  EXPECT_THROW(ClothNetwork::build(t, m, {}, {1.0}), std::invalid_argument);
}

}  // namespace
}  // namespace neurocloth
