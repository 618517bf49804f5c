// The live controls the simulation thread uses on the core, between steps:
// Simulation::set_solver_settings, Simulation::set_pinned and a module's
// set_parameter (the wind's mean velocity). Oracles: a simulation built with
// the new settings from the start, a pinned node that does not move, and a wind
// module built with the new velocity. (The run-time guard LiveScene puts on
// them is tested in tests/runtime/live_scene_stability_test.cpp.)
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "core/modules/module_factories.h"
#include "core/scene/scene.h"
#include "core/simulation/simulation.h"
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
    live->add_forces(net, inputs, ForceContext{}, s, a);
    built->add_forces(net, inputs, ForceContext{}, s, b);
    for (std::size_t i = 0; i < s.size(); ++i)
      ASSERT_EQ(a.at(i), b.at(i)) << "node " << i << " at t = " << time;
  }
}

// Other modules have no live parameters.
TEST(SimulationLiveControls, ModulesWithoutParametersSayNo) {
  const auto drag = make_air_drag(AirDragSpec{});
  EXPECT_FALSE(drag->set_parameter(ParameterId::module(0, ModuleParameter::velocity, 0), 1));
}

}  // namespace
}  // namespace neurocloth
