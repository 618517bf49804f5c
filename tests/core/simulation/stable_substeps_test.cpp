// The run-time guard in the core: with SolverSettings::substep_above_cap (what
// the live simulation thread runs with) a fixed step above step_cap() is taken
// as equal substeps under it, whatever made it so — a new dt, a stiffer
// material, a ramp, another integrator. Oracles: the same run without the
// guard diverges; within the cap the guard changes no bit. And the adaptive
// step's cap is recomputed right after a change (never stale).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/integrators/stability.h"
#include "support/test_support.h"

namespace neurocloth {
namespace {

Scene hanging(bool guarded, double dt = 1e-3) {
  Scene scene = test::asset_scene("hanging");
  scene.solver.substep_above_cap = guarded;
  scene.solver.dt = dt;
  return scene;
}

// The cap computed afresh from the network as it is now (not the cached one),
// with the bound a ramp in progress takes (Gershgorin's) or the settings' own.
double fresh_cap(const Simulation& sim) {
  const auto integrator = make_integrator(sim.settings(), sim.network());
  const StepBound kind = sim.ramping() ? StepBound::gershgorin : sim.settings().step_bound;
  return std::min(sim.settings().dt, sim.settings().adaptive_settings.safety *
                                         integrator_step_bound(sim.network(), *integrator, kind));
}

TEST(StableSubsteps, AFixedStepAboveTheCapRunsAsSubstepsInsteadOfExploding) {
  Simulation plain = hanging(false, 0.01).make_simulation();
  EXPECT_EQ(plain.advance(2.0), RunStatus::diverged);  // the oracle: dt is unstable

  Simulation guarded = hanging(true, 0.01).make_simulation();
  const long n = guarded.substeps();
  EXPECT_EQ(n, static_cast<long>(std::ceil(0.01 / guarded.step_cap())));
  EXPECT_GT(n, 5);
  EXPECT_EQ(guarded.advance(2.0), RunStatus::ok) << guarded.divergence_reason();
  EXPECT_EQ(guarded.check_now(), RunStatus::ok);
  EXPECT_EQ(guarded.time(), 2.0);
  EXPECT_EQ(guarded.steps(), 200 * n);  // every dt, n substeps
  EXPECT_TRUE(guarded.state().all_finite());

  // The substeps are steps of dt / n: a plain run at that step lands within round-off.
  Simulation small = hanging(false, 0.01 / static_cast<double>(n)).make_simulation();
  Simulation again = hanging(true, 0.01).make_simulation();
  small.advance(0.05);
  again.advance(0.05);
  for (std::size_t i = 0; i < small.state().size(); ++i)
    ASSERT_LT((small.state().position(i) - again.state().position(i)).norm(), 1e-9) << i;
}

TEST(StableSubsteps, WithinTheCapTheGuardChangesNoBit) {
  Simulation plain = hanging(false).make_simulation();
  Simulation guarded = hanging(true).make_simulation();
  ASSERT_EQ(guarded.substeps(), 1);
  Material softer = test::asset_scene("hanging").material;
  softer.spring_constant = 100;
  plain.ramp_to_material(softer);
  guarded.ramp_to_material(softer);
  plain.advance(0.5);
  guarded.advance(0.5);
  EXPECT_EQ(test::state_hash(guarded.state()), test::state_hash(plain.state()));
  EXPECT_EQ(guarded.steps(), plain.steps());
}

// A live stiffness change (the path of a SetParameter or of learning) makes
// the fixed step unstable: guarded, the very next step is split.
TEST(StableSubsteps, AStiffnessChangeMidRunIsCaughtAtOnce) {
  for (bool guarded : {false, true}) {
    Simulation sim = hanging(guarded).make_simulation();
    sim.advance(0.2);
    ASSERT_EQ(sim.substeps(), 1);
    for (double& k : sim.mutable_network().springs.stiffness)
      k *= 100;
    if (guarded) {
      EXPECT_GT(sim.substeps(), 5);
      EXPECT_LE(sim.settings().dt / sim.substeps(), fresh_cap(sim));
      EXPECT_EQ(sim.advance(1.0), RunStatus::ok) << sim.divergence_reason();
      EXPECT_TRUE(sim.state().all_finite());
    } else {
      EXPECT_EQ(sim.advance(1.0), RunStatus::diverged);  // the oracle
    }
  }
}

// A material ramp (a linguistic input, a new rule base) that stiffens a
// thousandfold over 64 steps: the guard follows it step by step.
TEST(StableSubsteps, AStiffeningRampIsFollowed) {
  for (bool guarded : {false, true}) {
    Simulation sim = hanging(guarded).make_simulation();
    sim.advance(0.1);
    Material stiff = test::asset_scene("hanging").material;
    stiff.spring_constant *= 1000;
    sim.ramp_to_material(stiff);
    const RunStatus s = sim.advance(1.0);
    if (guarded) {
      EXPECT_EQ(s, RunStatus::ok) << sim.divergence_reason();
      EXPECT_EQ(sim.substeps(), static_cast<long>(std::ceil(1e-3 / fresh_cap(sim))));
      EXPECT_GT(sim.substeps(), 20);
      EXPECT_GT(sim.steps(), 100 + 900 * 20);
    } else {
      EXPECT_EQ(s, RunStatus::diverged);
    }
  }
}

// Switching the integrator (or dt) between steps: the cap of the new one applies.
TEST(StableSubsteps, ANewIntegratorBringsItsOwnCap) {
  Simulation sim = hanging(true, 0.01).make_simulation();
  SolverSettings s = sim.settings();
  s.integrator = IntegratorKind::implicit_euler;
  sim.set_solver_settings(s);
  EXPECT_EQ(sim.substeps(), 1);  // unconditionally stable: no split
  sim.advance(0.1);
  s.integrator = IntegratorKind::rk4;
  sim.set_solver_settings(s);
  EXPECT_EQ(sim.substeps(), static_cast<long>(std::ceil(0.01 / fresh_cap(sim))));
  EXPECT_EQ(sim.advance(1.0), RunStatus::ok);
  EXPECT_EQ(sim.check_now(), RunStatus::ok);
}

// The adaptive step after a live change: every step at most the cap of the
// weights it was taken with, computed afresh (a stale cache would let the
// first steps after a stiffening through).
TEST(AdaptiveCap, IsRecomputedRightAfterAChangeAndThroughARamp) {
  Scene scene = hanging(false, 0.02);
  scene.solver.adaptive = true;
  Simulation sim = scene.make_simulation();
  sim.advance(0.1);
  const double before = sim.step_cap();

  std::vector<double> steps, caps;
  sim.set_observer([&](const StepEvent& e) {
    if (!e.accepted) return;
    steps.push_back(e.step);
    caps.push_back(fresh_cap(sim));
  });
  for (double& w : sim.mutable_network().masses.inverse_mass)
    w *= 100;  // nodes 100 times lighter: the bound drops tenfold
  sim.advance(0.1);
  ASSERT_FALSE(steps.empty());
  EXPECT_LT(caps.front(), 0.2 * before);
  for (std::size_t i = 0; i < steps.size(); ++i)
    ASSERT_LE(steps[i], caps[i] * (1 + 1e-12)) << "step " << i << " after the change";

  steps.clear();
  caps.clear();
  Material stiff = scene.material;
  stiff.spring_constant *= 1000;
  stiff.node_mass /= 100;  // and the ramp's masses are lighter still
  sim.ramp_to_material(stiff);
  sim.advance(0.1);
  ASSERT_GT(steps.size(), 64u);
  for (std::size_t i = 0; i < steps.size(); ++i)
    ASSERT_LE(steps[i], caps[i] * (1 + 1e-12)) << "step " << i << " of the ramp";
  EXPECT_LT(caps.back(), 0.1 * caps.front());  // the ramp did stiffen: k 1000 times
  EXPECT_EQ(sim.status(), RunStatus::ok) << sim.divergence_reason();
}

// Forward Euler gains energy at steps above viscosity / stiffness: its adaptive
// cap keeps it below that (with the Gershgorin cap alone, ten times larger on
// this cloth, the same run diverges).
TEST(AdaptiveCap, KeepsForwardEulerBelowItsDampedLimit) {
  Scene scene = test::asset_scene("hanging");
  scene.solver.integrator = IntegratorKind::explicit_euler;
  scene.solver.adaptive = true;
  scene.solver.dt = 0.04;
  Simulation sim = scene.make_simulation();
  const double damped = explicit_euler_step_bound(sim.network());
  EXPECT_NEAR(damped, 0.05 / 200.0, 1e-12);
  EXPECT_DOUBLE_EQ(sim.step_cap(), 0.5 * damped);
  EXPECT_LT(sim.step_cap(), 0.5 * stable_step_bound(sim.network(), 2.0));
  EXPECT_EQ(sim.advance(4.0), RunStatus::ok) << sim.divergence_reason();
  EXPECT_EQ(sim.check_now(), RunStatus::ok) << sim.divergence_reason();
  EXPECT_FALSE(sim.budget_exhausted());
  EXPECT_EQ(sim.time(), 4.0);
}

}  // namespace
}  // namespace neurocloth
