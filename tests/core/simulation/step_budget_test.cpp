// The step budget (SolverSettings::step_budget): no advance() takes more than
// step_budget trial steps per dt asked for, so the adaptive step at its floor
// on a stiff, light cloth cannot hang a caller; the state stays healthy and
// the shortfall is reported. And bad input is refused, naming the field,
// before anything changes.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "core/scene/stability_probe.h"
#include "support/test_support.h"

namespace neurocloth {
namespace {

using stability::matrix_scene;

// The hard corner on a small grid: the adaptive cap is about 1e-7 s, so one
// refresh interval of 0.1 s would need about a million trial steps.
Simulation stiff_adaptive(long budget, IntegratorKind kind = IntegratorKind::network) {
  Scene scene = matrix_scene({1e7, 1e-5, 0.1, 0, 8});
  scene.solver.integrator = kind;
  scene.solver.adaptive = true;
  scene.solver.step_budget = budget;
  return scene.make_simulation();
}

long trials(const Simulation& sim) {
  return sim.steps() + sim.rejected_steps();
}

TEST(StepBudget, AnAdaptiveStepAtItsFloorStopsAtTheBudgetStillOk) {
  Simulation sim = stiff_adaptive(100);
  ASSERT_LT(sim.step_cap() * 1e5, 0.1);  // really more than the budget's worth of steps
  EXPECT_EQ(sim.advance(0.1), RunStatus::ok);
  EXPECT_TRUE(sim.budget_exhausted());
  EXPECT_EQ(trials(sim), 100 * (1 + 1));  // step_budget per dt asked, plus one
  EXPECT_GT(sim.time(), 0.0);
  EXPECT_LT(sim.time(), 0.1);
  EXPECT_TRUE(sim.state().all_finite());
  EXPECT_EQ(sim.check_now(), RunStatus::ok);

  // The next call goes on from there, under a budget of its own.
  const double t = sim.time();
  EXPECT_EQ(sim.advance(0.1), RunStatus::ok);
  EXPECT_TRUE(sim.budget_exhausted());
  EXPECT_EQ(trials(sim), 2 * 100 * (1 + 1));
  EXPECT_GT(sim.time(), t);

  sim.advance(0.0);  // a call that is not short clears it
  EXPECT_FALSE(sim.budget_exhausted());
}

// The budget is per dt of the time asked: five refresh intervals, five budgets (+1).
TEST(StepBudget, ScalesWithTheTimeAsked) {
  for (IntegratorKind kind : {IntegratorKind::network, IntegratorKind::rk4}) {
    Simulation sim = stiff_adaptive(10, kind);
    sim.advance(5 * 0.1);
    EXPECT_TRUE(sim.budget_exhausted()) << to_string(kind);
    EXPECT_EQ(trials(sim), 10 * (5 + 1)) << to_string(kind);
  }
}

// A plain fixed step never reaches it, even with a budget of one step per dt,
// and a run that fits is not flagged.
TEST(StepBudget, FixedStepsAndRunsThatFitNeverReachIt) {
  Scene scene = test::asset_scene("hanging");
  scene.solver.step_budget = 1;
  Simulation sim = scene.make_simulation();
  EXPECT_EQ(sim.advance(100 * scene.solver.dt), RunStatus::ok);
  EXPECT_FALSE(sim.budget_exhausted());
  EXPECT_EQ(sim.steps(), 100);
  EXPECT_EQ(sim.advance(2.5 * scene.solver.dt), RunStatus::ok);
  EXPECT_EQ(sim.steps(), 103);
  EXPECT_FALSE(sim.budget_exhausted());

  Scene adaptive = test::asset_scene("hanging_fuzzy");  // adaptive, a few steps per dt
  Simulation a = adaptive.make_simulation();
  EXPECT_EQ(a.advance(0.5), RunStatus::ok);
  EXPECT_FALSE(a.budget_exhausted());
  EXPECT_DOUBLE_EQ(a.time(), 0.5);
}

// The same budget bounds the substeps of a guarded fixed step (SolverSettings::
// substep_above_cap): a dt a million times the cap stops at the budget.
TEST(StepBudget, BoundsTheSubstepsOfAGuardedFixedStep) {
  Scene scene = matrix_scene({1e7, 1e-5, 0.1, 0, 8});
  scene.solver.substep_above_cap = true;
  scene.solver.step_budget = 50;
  Simulation sim = scene.make_simulation();
  ASSERT_GT(sim.substeps(), 1000);
  EXPECT_EQ(sim.advance(0.1), RunStatus::ok);
  EXPECT_TRUE(sim.budget_exhausted());
  EXPECT_EQ(sim.steps(), 50 * (1 + 1));
  EXPECT_LT(sim.time(), 0.1);
  EXPECT_TRUE(sim.state().all_finite());
}

// One frame at the step's floor can be millions of steps: the interrupt is
// asked within it too, every 1024 steps, and stops it there, healthy, on the
// path of the uninterrupted run (the same bits as a budget of as many steps).
TEST(StepBudget, AnInterruptIsAskedWithinOneLongFrame) {
  for (const bool adaptive : {true, false}) {
    SCOPED_TRACE(adaptive ? "adaptive" : "fixed, in substeps");
    Scene scene = matrix_scene({1e7, 1e-5, 0.1, 0, 8});
    scene.solver.adaptive = adaptive;
    scene.solver.substep_above_cap = !adaptive;
    scene.solver.step_budget = 1000000;
    Simulation cut = scene.make_simulation();
    int asks = 0;
    cut.set_interrupt([&](const Simulation&) { return ++asks == 3; });
    EXPECT_EQ(cut.advance(0.1), RunStatus::ok);  // one frame (dt = 0.1 s)
    EXPECT_TRUE(cut.interrupted());
    EXPECT_FALSE(cut.budget_exhausted());
    EXPECT_EQ(asks, 3);
    EXPECT_EQ(trials(cut), 3 * 1024);
    EXPECT_GT(cut.time(), 0.0);
    EXPECT_LT(cut.time(), 0.1);
    EXPECT_EQ(cut.check_now(), RunStatus::ok);

    scene.solver.step_budget = 3 * 1024 / 2;  // per dt asked, plus one dt
    Simulation budgeted = scene.make_simulation();
    budgeted.advance(0.1);
    EXPECT_TRUE(budgeted.budget_exhausted());
    EXPECT_EQ(trials(budgeted), trials(cut));
    EXPECT_EQ(budgeted.time(), cut.time());
    EXPECT_EQ(test::state_hash(budgeted.state()), test::state_hash(cut.state()));
  }
}

// --- Bad input: a clear error naming the field; nothing lost. ---

bool says(const std::invalid_argument& e, const std::string& part) {
  return std::string(e.what()).find(part) != std::string::npos;
}

TEST(BadInput, SolverSettingsNameTheFieldAndChangeNothing) {
  Simulation sim = test::asset_scene("hanging").make_simulation();
  sim.advance(0.01);
  const auto hash = test::state_hash(sim.state());
  const SolverSettings good = sim.settings();
  struct Case {
    const char* field;
    void (*spoil)(SolverSettings&);
  };
  const Case cases[] = {
      {"solver.dt", [](SolverSettings& s) { s.dt = NAN; }},
      {"solver.dt", [](SolverSettings& s) { s.dt = INFINITY; }},
      {"solver.dt", [](SolverSettings& s) { s.dt = -1e-3; }},
      // The floor: a step this small would make any run a hang.
      {"solver.dt", [](SolverSettings& s) { s.dt = 5e-324; }},
      {"solver.dt", [](SolverSettings& s) { s.dt = 1e-12; }},
      {"solver.safety", [](SolverSettings& s) { s.adaptive_settings.safety = 1.5; }},
      {"solver.growth_tolerance",
       [](SolverSettings& s) { s.adaptive_settings.growth_tolerance = -1; }},
      {"solver.min_step_fraction",
       [](SolverSettings& s) { s.adaptive_settings.min_step_fraction = 0; }},
      {"solver.min_step_fraction",
       [](SolverSettings& s) { s.adaptive_settings.min_step_fraction = 1e-300; }},
      {"solver.check_interval", [](SolverSettings& s) { s.divergence.check_interval = 0; }},
      {"solver.runaway_factor", [](SolverSettings& s) { s.divergence.runaway_factor = 0.5; }},
      {"solver.runaway_checks", [](SolverSettings& s) { s.divergence.runaway_checks = 0; }},
      {"solver.hard_factor", [](SolverSettings& s) { s.divergence.hard_factor = 10; }},
      {"solver.step_budget", [](SolverSettings& s) { s.step_budget = 0; }},
      {"solver.integrator",
       [](SolverSettings& s) { s.integrator = static_cast<IntegratorKind>(9); }},
  };
  for (const Case& c : cases) {
    SolverSettings bad = good;
    c.spoil(bad);
    try {
      sim.set_solver_settings(bad);
      ADD_FAILURE() << c.field << " was accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_TRUE(says(e, c.field)) << e.what();
    }
    Scene scene = test::asset_scene("hanging");
    scene.solver = bad;
    EXPECT_THROW(scene.make_simulation(), std::invalid_argument) << c.field;
  }
  EXPECT_EQ(sim.settings().dt, good.dt);
  EXPECT_EQ(sim.settings().step_budget, good.step_budget);
  EXPECT_EQ(test::state_hash(sim.state()), hash);
  EXPECT_EQ(sim.advance(0.01), RunStatus::ok);  // and it runs on
}

TEST(BadInput, StatesForcesAndMaterialsNameWhatIsWrong) {
  const Scene scene = test::asset_scene("hanging");
  Simulation sim = scene.make_simulation();
  sim.advance(0.01);
  const auto hash = test::state_hash(sim.state());

  ClothState nan_state = sim.state();
  nan_state.vy[7] = NAN;
  try {
    sim.set_state(nan_state);
    ADD_FAILURE() << "a NaN state was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_TRUE(says(e, "node 7")) << e.what();
  }
  EXPECT_THROW(Simulation(scene.build_network(), nan_state, scene.solver), std::invalid_argument);

  EXPECT_THROW(sim.set_external_force(0, Vec3(NAN, 0, 0)), std::invalid_argument);
  EXPECT_THROW(sim.set_external_force(sim.network().node_count(), Vec3::Zero()), std::out_of_range);

  Material weightless = scene.material;
  weightless.node_mass = 0;
  try {
    sim.ramp_to_material(weightless);
    ADD_FAILURE() << "a massless material was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_TRUE(says(e, "masses.inverse_mass")) << e.what();
  }
  EXPECT_FALSE(sim.ramping());

  ClothNetwork net = scene.build_network();
  net.springs.stiffness[3] = -1;
  try {
    Simulation(net, scene.initial_state(), scene.solver);
    ADD_FAILURE() << "a negative stiffness was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_TRUE(says(e, "springs.stiffness[3]")) << e.what();
  }

  EXPECT_EQ(test::state_hash(sim.state()), hash);
  EXPECT_EQ(sim.advance(0.01), RunStatus::ok);
}

}  // namespace
}  // namespace neurocloth
