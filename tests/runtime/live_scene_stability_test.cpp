// The run-time guard as LiveScene applies it (docs/stability.md): a live
// change that makes the step unstable is taken in substeps and said so, in one
// line. Oracle: the same change in a batch run, without the guard, diverges.
#include <gtest/gtest.h>

#include <string>

#include "core/scene/scene.h"
#include "core/simulation/simulation.h"
#include "runtime/live_scene.h"
#include "support/test_support.h"

namespace neurocloth {
namespace {

using test::contains;

// The oracle for every case below: the same change in a batch run (no guard) diverges.
RunStatus batch_after(Scene scene, void (*change)(Simulation&), double seconds) {
  Simulation sim = scene.make_simulation();
  sim.advance(0.05);
  change(sim);
  return sim.advance(seconds);
}

TEST(LiveStabilityGuard, ADtAboveTheStableStepRunsInSubstepsAndIsReported) {
  const Scene scene = test::asset_scene("hanging");
  ASSERT_EQ(batch_after(
                scene,
                [](Simulation& s) {
                  SolverSettings n = s.settings();
                  n.dt = 0.05;
                  s.set_solver_settings(n);
                },
                2.0),
            RunStatus::diverged);

  LiveScene live(scene, true);
  EXPECT_EQ(live.stability_notice(), "");
  live.simulation().advance(0.05);
  EXPECT_EQ(live.apply(SetParameter{test::parameter("dt"), 0.05}), "");  // accepted, not refused
  const std::string notice = live.stability_notice();
  EXPECT_TRUE(contains(notice, "dt = 0.05 s")) << notice;
  EXPECT_TRUE(contains(notice, "network")) << notice;
  EXPECT_TRUE(contains(notice, std::to_string(live.simulation().substeps()) + " substeps"))
      << notice;
  EXPECT_GT(live.simulation().substeps(), 20);
  EXPECT_EQ(live.simulation().advance(2.0), RunStatus::ok) << live.simulation().divergence_reason();
  EXPECT_EQ(live.simulation().check_now(), RunStatus::ok);

  EXPECT_EQ(live.apply(SetParameter{test::parameter("dt"), 1e-3}),
            "");  // back within the bound: no notice
  EXPECT_EQ(live.stability_notice(), "");
  EXPECT_EQ(live.simulation().substeps(), 1);
}

// Viscosity at the top of its range makes the network's step unstable through
// the damping term (h gamma): caught the same way.
TEST(LiveStabilityGuard, ViscosityAtTheTopOfItsRangeIsCaught) {
  const Scene scene = test::asset_scene("hanging");
  ASSERT_EQ(batch_after(
                scene,
                [](Simulation& s) {
                  for (double& d : s.mutable_network().springs.damping)
                    d = 100;
                },
                0.1),
            RunStatus::diverged);
  LiveScene live(scene, true);
  EXPECT_EQ(live.apply(SetParameter{test::parameter("viscosity"), 100}), "");
  EXPECT_GT(live.simulation().substeps(), 10);
  EXPECT_TRUE(contains(live.stability_notice(), "substeps")) << live.stability_notice();
  EXPECT_EQ(live.simulation().advance(0.02), RunStatus::ok)  // about 5000 substeps
      << live.simulation().divergence_reason();
  EXPECT_EQ(live.simulation().check_now(), RunStatus::ok);
}

// A linguistic input that stiffens the material (rule 4: small elasticity,
// mass not small: a very high spring constant) on a fixed step: the ramp
// raises the stiffness step by step and the substeps follow it.
TEST(LiveStabilityGuard, AnInputThatStiffensTheMaterialIsCaught) {
  LiveScene live(test::asset_scene("hanging_fuzzy"), true);
  ASSERT_EQ(live.apply(SetAdaptive{false}), "");
  Simulation& sim = live.simulation();
  const double k_before = sim.network().springs.stiffness[0];
  const long before = sim.substeps();
  ASSERT_EQ(live.apply(SetParameter{test::parameter(live.scene(), "input.elasticity"), 0}), "");
  EXPECT_EQ(sim.advance(0.2), RunStatus::ok) << sim.divergence_reason();
  EXPECT_FALSE(sim.ramping());
  EXPECT_GT(sim.network().springs.stiffness[0], 1.5 * k_before);  // measured: 606 -> 1071 N/m
  EXPECT_GT(sim.substeps(), before);
  EXPECT_TRUE(contains(live.stability_notice(), "substeps")) << live.stability_notice();
}

// Forward Euler gains energy at any step above viscosity / stiffness: the
// guard takes it in substeps below that; without viscosity no step is stable,
// and the notice says a divergence is coming.
TEST(LiveStabilityGuard, ForwardEulerIsKeptBelowItsDampedLimitOrWarned) {
  LiveScene live(test::asset_scene("hanging"), true);
  EXPECT_EQ(live.apply(SetIntegrator{IntegratorKind::explicit_euler}), "");
  Simulation& sim = live.simulation();
  const double limit = 0.05 / 200;  // viscosity / stiffness
  EXPECT_NEAR(sim.step_cap(), 0.5 * limit, 1e-12);
  EXPECT_EQ(sim.substeps(), 8);  // dt = 1 ms in steps of at most 0.125 ms
  std::string notice = live.stability_notice();
  EXPECT_TRUE(contains(notice, "8 substeps")) << notice;
  EXPECT_FALSE(contains(notice, "gains energy")) << notice;
  EXPECT_EQ(sim.advance(1.0), RunStatus::ok) << sim.divergence_reason();
  EXPECT_EQ(sim.check_now(), RunStatus::ok);

  EXPECT_EQ(live.apply(SetParameter{test::parameter("dt"), 1e-4}), "");
  EXPECT_EQ(live.stability_notice(), "");

  EXPECT_EQ(live.apply(SetParameter{test::parameter("viscosity"), 0}), "");
  notice = live.stability_notice();
  EXPECT_TRUE(contains(notice, "explicit_euler gains energy")) << notice;
  EXPECT_TRUE(contains(notice, "every step")) << notice;
}

// The live step budget: a cloth whose stable step is a ten-millionth of a
// second stops each advance at its budget, healthy, and says so.
TEST(LiveStabilityGuard, AnExhaustedStepBudgetIsReported) {
  Scene scene = test::asset_scene("hanging");
  scene.material.spring_constant = 1e7;
  scene.material.node_mass = 1e-5;
  scene.solver.adaptive = true;
  scene.solver.dt = 0.1;
  LiveScene live(scene, true);
  Simulation& sim = live.simulation();
  EXPECT_LT(sim.settings().step_budget, SolverSettings{}.step_budget);  // sized for the cloth
  EXPECT_EQ(sim.advance(0.1), RunStatus::ok);
  EXPECT_TRUE(sim.budget_exhausted());
  EXPECT_LT(sim.time(), 0.1);
  const std::string notice = live.stability_notice();
  EXPECT_TRUE(contains(notice, "step budget")) << notice;
  SimulationStatus status;
  live.describe(status);
  EXPECT_TRUE(status.step_budget_exhausted);
}

}  // namespace
}  // namespace neurocloth
