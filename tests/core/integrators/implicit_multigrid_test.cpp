// The implicit step's multigrid preconditioner: the solve it preconditions
// against Jacobi's, its iterations as the cloth is refined, and its rebuild
// when a weight changes.
#include "core/integrators/implicit_multigrid.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/integrators/implicit_system.h"
#include "core/integrators/integrator.h"
#include "core/io/asset_paths.h"
#include "core/scene/scene.h"
#include "core/simulation/simulation.h"

namespace neurocloth {
namespace {

constexpr double kStep = 1.0 / 64;

// The benchmark's cloth (bench/large_step_benchmark.cpp) at n x n, swinging:
// 0.1 s of implicit steps from rest, so its springs have turned.
Simulation swinging(int n) {
  Scene scene = resized_grid(load_scene(assets_directory() + "/scenes/hanging.json"), n);
  scene.solver.integrator = IntegratorKind::implicit_euler;
  scene.solver.adaptive = false;
  scene.solver.dt = kStep;
  Simulation sim = scene.make_simulation();
  EXPECT_EQ(sim.advance(0.1), RunStatus::ok);
  return sim;
}

// The step's linear system at the simulation's state: A dv = b with
// A = M + h D + h^2 K and b the step's right-hand side, here M g h on free nodes.
struct StepSystem {
  ImplicitSystem system;
  std::vector<double> b;
  explicit StepSystem(const Simulation& sim) : system(sim.network()) {
    const ClothNetwork& net = sim.network();
    system.linearise(net, sim.state());
    b.assign(3 * net.node_count(), 0.0);
    for (std::size_t i = 0; i < net.node_count(); ++i)
      for (int c = 0; c < 3; ++c)  // gravity, and a sideways push that varies along the cloth
        b[3 * i + c] = net.masses.free[i] * kStep / net.masses.inverse_mass[i] *
                       (net.gravity[c] + std::sin(0.37 * static_cast<double>(3 * i + c)));
  }
  CgResult solve(const ClothNetwork& net, std::vector<double>& x, const ImplicitMultigrid* mg) {
    x.assign(b.size(), 0.0);
    return system.solve(net, 1.0, kStep, kStep * kStep, b, x, 1e-12, 100000, mg);
  }
};

TEST(ImplicitMultigrid, PreconditionedSolveMatchesJacobis) {
  const Simulation sim = swinging(24);
  const ClothNetwork& net = sim.network();
  StepSystem s(sim);
  ImplicitMultigrid mg;
  ASSERT_TRUE(mg.build(net, s.system, 1.0, kStep, kStep * kStep));
  EXPECT_GE(mg.levels(), 2);
  std::vector<double> jacobi, cycled;
  const CgResult j = s.solve(net, jacobi, nullptr);
  const CgResult m = s.solve(net, cycled, &mg);
  ASSERT_TRUE(j.converged);
  ASSERT_TRUE(m.converged);
  double scale = 0, difference = 0;
  for (std::size_t i = 0; i < jacobi.size(); ++i) {
    scale = std::max(scale, std::abs(jacobi[i]));
    difference = std::max(difference, std::abs(jacobi[i] - cycled[i]));
  }
  EXPECT_GT(scale, 0.0);
  EXPECT_LE(difference, 1e-9 * scale);
  EXPECT_LT(m.iterations * 4, j.iterations);  // and it pays: far fewer iterations
}

// Jacobi's iterations grow with the nodes per side; a V-cycle's stay nearly flat.
TEST(ImplicitMultigrid, IterationsDoNotGrowWithTheCloth) {
  int cycled[2], jacobi[2];
  const int sizes[2] = {16, 48};
  for (int k = 0; k < 2; ++k) {
    const Simulation sim = swinging(sizes[k]);
    StepSystem s(sim);
    ImplicitMultigrid mg;
    ASSERT_TRUE(mg.build(sim.network(), s.system, 1.0, kStep, kStep * kStep));
    std::vector<double> x;
    const CgResult m = s.solve(sim.network(), x, &mg);
    const CgResult j = s.solve(sim.network(), x, nullptr);
    ASSERT_TRUE(m.converged && j.converged);
    cycled[k] = m.iterations;
    jacobi[k] = j.iterations;
  }
  EXPECT_LE(cycled[1], 1.5 * cycled[0]) << cycled[0] << " -> " << cycled[1];
  EXPECT_GT(jacobi[1], 2 * jacobi[0]) << jacobi[0] << " -> " << jacobi[1];  // the test can tell
}

TEST(ImplicitMultigrid, KnowsWhatItWasMadeFor) {
  const Simulation sim = swinging(8);
  ClothNetwork net = sim.network();
  StepSystem s(sim);
  ImplicitMultigrid mg;
  EXPECT_FALSE(mg.made_for(net));
  ASSERT_TRUE(mg.build(net, s.system, 1.0, kStep, kStep * kStep));
  EXPECT_TRUE(mg.made_for(net, 1.0, kStep, kStep * kStep));
  EXPECT_FALSE(mg.made_for(net, 1.0, kStep / 2, kStep * kStep / 4));
  net.springs.damping[3] *= 2;
  EXPECT_FALSE(mg.made_for(net));
}

// A material slider moves: the next step rebuilds the hierarchy, so it is the
// same bits as an integrator that never saw the old weights; a stale
// hierarchy preconditions differently and would not be.
TEST(ImplicitMultigrid, TheImplicitStepRebuildsItWhenAWeightChanges) {
  const Simulation sim = swinging(48);  // large enough to be given a hierarchy
  ClothNetwork net = sim.network();
  ASSERT_GE(net.node_count(), ImplicitMultigrid::kMinNodes);
  const ClothState in = sim.state();
  // The multigrid named: from 48 x 48 the automatic choice is the Laplacian.
  auto make = [](const ClothNetwork& of) {
    return make_integrator(IntegratorKind::implicit_euler, of, kDefaultMinStepFraction,
                           kDefaultProjectiveIterations, kDefaultLinearTolerance,
                           ImplicitPreconditioner::multigrid);
  };
  const auto used = make(net);
  NodeVectors f(net.node_count());
  ClothState out = in, fresh_out = in;
  net.net_forces(in, f);
  used->step(net, ForceInputs{}, ForceContext{}, in, f, kStep, out);
  const ClothState before = out;
  for (double& k : net.springs.stiffness)
    k *= 3;
  net.net_forces(in, f);
  const StepReport report = used->step(net, ForceInputs{}, ForceContext{}, in, f, kStep, out);
  const auto fresh = make(net);
  const StepReport fresh_report =
      fresh->step(net, ForceInputs{}, ForceContext{}, in, f, kStep, fresh_out);
  EXPECT_EQ(report.cg_iterations, fresh_report.cg_iterations);
  for (std::size_t i = 0; i < in.size(); ++i)
    ASSERT_EQ(out.position(i), fresh_out.position(i)) << "node " << i;
  double moved = 0;
  for (std::size_t i = 0; i < in.size(); ++i)
    moved = std::max(moved, (out.position(i) - before.position(i)).norm());
  EXPECT_GT(moved, 1e-9);  // and the change mattered
}

// Beyond its limit it holds nothing (the implicit step then keeps Jacobi),
// rather than assembling hundreds of MB.
TEST(ImplicitMultigrid, RefusesAClothBeyondItsLimit) {
  const Scene scene = resized_grid(load_scene(assets_directory() + "/scenes/hanging.json"), 257);
  const ClothNetwork net = scene.build_network();
  ASSERT_GT(net.node_count(), ImplicitMultigrid::kMaxNodes);
  ImplicitSystem system(net);
  system.linearise(net, scene.initial_state());
  ImplicitMultigrid mg;
  EXPECT_FALSE(mg.build(net, system, 1.0, kStep, kStep * kStep));
  EXPECT_FALSE(mg.built());
}

// The step's linear tolerance is the scene's solver.linear_tolerance: a looser
// one takes fewer iterations; one outside its range is refused by name.
TEST(ImplicitMultigrid, TheStepsToleranceIsASolverSetting) {
  Scene scene = resized_grid(load_scene(assets_directory() + "/scenes/hanging.json"), 16);
  scene.solver.integrator = IntegratorKind::implicit_euler;
  scene.solver.adaptive = false;
  scene.solver.dt = kStep;
  long iterations[2];
  const double tolerances[2] = {1e-10, 1e-4};
  for (int k = 0; k < 2; ++k) {
    scene.solver.linear_tolerance = tolerances[k];
    Simulation sim = scene.make_simulation();
    ASSERT_EQ(sim.advance(0.1), RunStatus::ok);
    iterations[k] = sim.cg_iterations();
  }
  EXPECT_LT(2 * iterations[1], iterations[0]);
  scene.solver.linear_tolerance = 0;
  try {
    scene.make_simulation();
    FAIL() << "a zero tolerance was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("solver.linear_tolerance"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace neurocloth
