// The live controls the simulation thread uses on the core, between steps:
// Simulation::set_solver_settings, Simulation::set_pinned and a module's
// set_parameter (the wind's mean velocity). Oracles: a simulation built with
// the new settings from the start, a pinned node that does not move, and a wind
// module built with the new velocity. Then the run-time guard as LiveScene
// applies it: a change that makes the step unstable is taken in substeps and
// said so (oracle: the same change in a batch run diverges).
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "core/modules/module_factories.h"
#include "core/scene/scene.h"
#include "core/simulation/simulation.h"
#include "runtime/live_scene.h"
#include "support/test_support.h"

namespace neurocloth {
namespace {

// Switching the integrator and dt between steps is the same as having started
// from that state with those settings: nothing of the old integrator lingers.
TEST(SimulationLiveControls, NewSolverSettingsActAsIfBuiltWithThem) {
  for (IntegratorKind kind : kAllIntegrators) {
    const Scene scene = test::asset_scene("hanging");
    Simulation live = scene.make_simulation();
    live.advance(0.03);  // the network integrator at dt 1e-3
    SolverSettings s = live.settings();
    s.integrator = kind;
    s.dt = 5e-4;
    live.set_solver_settings(s);

    Scene changed = scene;
    changed.solver = s;
    Simulation fresh = changed.make_simulation();
    fresh.set_state(live.state());

    live.advance(0.01);
    fresh.advance(0.01);
    EXPECT_EQ(live.settings().dt, 5e-4);
    EXPECT_EQ(live.settings().integrator, kind);
    EXPECT_EQ(test::state_hash(live.state()), test::state_hash(fresh.state())) << to_string(kind);
    EXPECT_EQ(live.status(), RunStatus::ok);
  }
}

TEST(SimulationLiveControls, SolverSettingsRefuseANonPositiveDt) {
  Simulation sim = test::asset_scene("hanging").make_simulation();
  SolverSettings s = sim.settings();
  s.dt = 0;
  EXPECT_THROW(sim.set_solver_settings(s), std::invalid_argument);
  EXPECT_EQ(sim.settings().dt, 1e-3);
}

// A node pinned while it swings stops where it is (its velocity is cleared)
// and a node freed again falls, under every integrator.
TEST(SimulationLiveControls, PinningStopsANodeAndFreeingReleasesIt) {
  for (IntegratorKind kind : kAllIntegrators) {
    Scene scene = test::asset_scene("hanging");
    scene.solver.integrator = kind;
    Simulation sim = scene.make_simulation();
    const std::size_t corner = sim.network().node_count() - 1;  // the free far corner
    sim.advance(0.05);
    ASSERT_GT(sim.state().velocity(corner).norm(), 0.01) << to_string(kind);
    sim.set_pinned(corner, true);
    EXPECT_TRUE(sim.network().masses.pinned(corner));
    EXPECT_EQ(sim.state().velocity(corner), Vec3::Zero());
    const Vec3 held = sim.state().position(corner);
    sim.advance(0.03);
    EXPECT_EQ(sim.state().position(corner), held) << to_string(kind);

    sim.set_pinned(corner, false);
    sim.advance(0.01);
    EXPECT_NE(sim.state().position(corner), held) << to_string(kind);
    EXPECT_EQ(sim.status(), RunStatus::ok);
  }
  Simulation sim = test::asset_scene("hanging").make_simulation();
  EXPECT_THROW(sim.set_pinned(sim.network().node_count(), true), std::out_of_range);
}

// A mass that fell for a long time carries energy gravity released; switch
// gravity off and that energy must not count as runaway.
TEST(SimulationLiveControls, RebasedDivergenceCheckAcceptsAGravityChange) {
  Simulation sim = test::asset_scene("free_fall").make_simulation();
  sim.advance(300.0);  // about 1.5 MJ of kinetic energy per kg
  ASSERT_EQ(sim.status(), RunStatus::ok);
  sim.mutable_network().gravity = Vec3::Zero();
  sim.rebase_divergence_check();
  const Vec3 v = sim.state().velocity(0);
  sim.advance(10.0);
  EXPECT_EQ(sim.status(), RunStatus::ok) << sim.divergence_reason();
  EXPECT_EQ(sim.state().velocity(0), v);  // coasting: no force, no change
}

// Changing the wind's mean velocity gives the forces of a wind declared with it.
TEST(SimulationLiveControls, WindVelocityChangesLikeADeclaredOne) {
  const Scene scene = test::asset_scene("flag");
  const WindSpec* declared = nullptr;
  for (const ModuleDeclaration& m : scene.modules)
    if (const auto* w = std::get_if<WindSpec>(&m.spec)) declared = w;
  ASSERT_NE(declared, nullptr);
  WindSpec target = *declared;
  target.velocity = Vec3(-3, 2, 11);

  const auto live = make_wind(*declared, scene.topology);
  auto velocity = [](int axis) { return ParameterId::module(0, ModuleParameter::velocity, axis); };
  EXPECT_TRUE(live->set_parameter(velocity(0), -3));
  EXPECT_TRUE(live->set_parameter(velocity(1), 2));
  EXPECT_TRUE(live->set_parameter(velocity(2), 11));
  EXPECT_FALSE(live->set_parameter(velocity(3), 2));
  const auto built = make_wind(target, scene.topology);

  const ClothNetwork net = scene.build_network();
  ClothState s = scene.initial_state();
  for (std::size_t i = 0; i < s.size(); ++i)  // tilt the velocities so every term acts
    s.set_velocity(i, Vec3(0.1 * (i % 3), -0.2, 0.05 * (i % 5)));
  for (double time : {0.0, 0.7, 1.3}) {  // the gust scales the new mean like the declared one
    ForceInputs inputs;
    inputs.time = time;
    NodeVectors a(s.size()), b(s.size());
    live->add_forces(net, inputs, s, a);
    built->add_forces(net, inputs, s, b);
    for (std::size_t i = 0; i < s.size(); ++i)
      ASSERT_EQ(a.at(i), b.at(i)) << "node " << i << " at t = " << time;
  }
}

// Other modules have no live parameters.
TEST(SimulationLiveControls, ModulesWithoutParametersSayNo) {
  const auto drag = make_air_drag(AirDragSpec{});
  EXPECT_FALSE(drag->set_parameter(ParameterId::module(0, ModuleParameter::velocity, 0), 1));
}

// --- The run-time guard (docs/stability.md): LiveScene runs with
// substep_above_cap and says, in one line, when the step is not what was asked.

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
