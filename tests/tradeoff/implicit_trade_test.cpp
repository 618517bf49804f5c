// The implicit step's conjugate-gradient tolerance as a measured accuracy knob:
// the sweep runs each tolerance at every step it tries, and a picked row's
// tolerance reaches the settings it stands for.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "support/short_trade_plan.h"
#include "support/test_support.h"
#include "tradeoff/accuracy_choice.h"
#include "tradeoff/tradeoff_sweep.h"

namespace neurocloth {
namespace {

TradeoffPlan implicit_plan() {
  TradeoffPlan plan = test::short_trade_plan("implicit_euler");
  plan.implicit_tolerances = {1e-10, 1e-2};
  return plan;
}

SampledRun reference_run(const Scene& scene, const TradeTable& t,
                         const std::vector<double>& times) {
  SolverSettings r = scene.solver;
  r.integrator = IntegratorKind::rk4;
  r.adaptive = false;
  r.dt = t.reference.dt;
  return run_sampled(scene, r, times);
}

TEST(ImplicitTrade, EveryStepTriedRunsEachTolerance) {
  const Scene scene = test::asset_scene("hanging");
  const TradeoffPlan plan = implicit_plan();
  const TradeTable t = measure_tradeoff(scene, "hanging.json", plan);
  ASSERT_EQ(t.rows.size(), 4u);
  const double first =
      first_step(scene, IntegratorKind::implicit_euler, plan.seconds / plan.samples);
  const double dts[] = {first, first, first / 2, first / 2};
  const double tolerances[] = {1e-10, 1e-2, 1e-10, 1e-2};
  for (std::size_t i = 0; i < t.rows.size(); ++i) {
    const TradeRow& r = t.rows[i];
    SCOPED_TRACE(describe_setting(r));
    EXPECT_EQ(r.method, "implicit_euler");
    EXPECT_EQ(r.parameter, "dt");
    EXPECT_EQ(r.dt, dts[i]);
    EXPECT_EQ(r.value, r.dt);
    EXPECT_EQ(r.linear_tolerance, tolerances[i]);
    EXPECT_EQ(r.iterations, 0);
    EXPECT_TRUE(r.ok()) << r.status;
  }
  // The tolerance changes the motion: same step, different errors.
  EXPECT_NE(t.rows[0].position_error_max, t.rows[1].position_error_max);
  EXPECT_NE(t.rows[2].position_error_max, t.rows[3].position_error_max);
  EXPECT_EQ(t.sweep_stops, (std::vector<std::string>{"implicit_euler tol 1e-10: levels",
                                                     "implicit_euler tol 0.01: levels"}));

  // A row's settings are the ones that measured it: run again, the same error;
  // at the scene's own tolerance instead, another one.
  const TradeRow& row = t.rows[3];
  SolverSettings s = settings_for(row, scene.solver);
  EXPECT_EQ(s.linear_tolerance, 1e-2);
  const std::vector<double> times = sample_times(plan.seconds, plan.samples);
  const SampledRun reference = reference_run(scene, t, times);
  const ErrorScale scale = error_scale(scene);
  EXPECT_EQ(compare_runs(run_sampled(scene, s, times), reference, scale).position_max,
            row.position_error_max);
  s.linear_tolerance = scene.solver.linear_tolerance;
  EXPECT_NE(compare_runs(run_sampled(scene, s, times), reference, scale).position_max,
            row.position_error_max);
}

TEST(ImplicitTrade, TheBudgetStopsEveryToleranceLine) {
  const Scene scene = test::asset_scene("hanging");
  TradeoffPlan plan = implicit_plan();
  plan.method_budget_seconds = 0;  // no run fits: one step, then the budget
  const TradeTable t = measure_tradeoff(scene, "hanging.json", plan);
  ASSERT_EQ(t.rows.size(), 2u);
  EXPECT_EQ(t.rows[0].linear_tolerance, 1e-10);
  EXPECT_EQ(t.rows[1].linear_tolerance, 1e-2);
  EXPECT_EQ(t.sweep_stops, (std::vector<std::string>{"implicit_euler tol 1e-10: budget",
                                                     "implicit_euler tol 0.01: budget"}));
}

// The plan's own steps (--dt): each tolerance at each of them, no halving.
TEST(ImplicitTrade, GivenStepsRunEachTolerance) {
  const Scene scene = test::asset_scene("hanging");
  TradeoffPlan plan = implicit_plan();
  plan.steps = {0.0125, 0.00625};
  const TradeTable t = measure_tradeoff(scene, "hanging.json", plan);
  ASSERT_EQ(t.rows.size(), 4u);
  const double dts[] = {0.0125, 0.0125, 0.00625, 0.00625};
  const double tolerances[] = {1e-10, 1e-2, 1e-10, 1e-2};
  for (std::size_t i = 0; i < t.rows.size(); ++i) {
    EXPECT_EQ(t.rows[i].dt, dts[i]) << i;
    EXPECT_EQ(t.rows[i].linear_tolerance, tolerances[i]) << i;
  }
}

TEST(ImplicitTrade, RefusesToleranceItCannotRun) {
  const Scene scene = test::asset_scene("hanging");
  TradeoffPlan plan = implicit_plan();
  for (std::vector<double> bad : {std::vector<double>{}, {0}, {1e-6, 0.5}, {1e-15}}) {
    plan.implicit_tolerances = bad;
    EXPECT_THROW(measure_tradeoff(scene, "", plan), std::invalid_argument);
  }
  plan.methods = {"network"};  // implicit_euler not swept: its tolerances are not used
  plan.implicit_tolerances = {};
  plan.max_levels = 1;
  EXPECT_NO_THROW(measure_tradeoff(scene, "", plan));
}

// The cheapest row meeting the budget is implicit at 1e-6: its settings carry
// the tolerance over the scene's own; another method's pick keeps the scene's.
TEST(ImplicitTrade, APickedImplicitRowCarriesItsTolerance) {
  TradeTable t;
  t.scene = "hand";
  t.reference.change = 1e-6;
  TradeRow loose;
  loose.method = "implicit_euler";
  loose.parameter = "dt";
  loose.value = loose.dt = 1.0 / 256;
  loose.linear_tolerance = 1e-6;
  loose.position_error_max = 0.04;
  loose.wall_per_simulated_second = 0.6;
  TradeRow tight = loose;
  tight.linear_tolerance = 1e-10;
  tight.position_error_max = 0.039;
  tight.wall_per_simulated_second = 1.5;
  TradeRow verlet = loose;
  verlet.method = "verlet";
  verlet.linear_tolerance = 0;
  verlet.position_error_max = 0.3;
  verlet.wall_per_simulated_second = 0.1;
  t.rows = {tight, loose, verlet};
  SolverSettings base;
  base.linear_tolerance = 1e-9;
  const AccuracyChoice c = choose_for_accuracy(t, "t.csv", 0.05, base);
  EXPECT_EQ(c.row_index, 1u);
  EXPECT_EQ(c.settings.integrator, IntegratorKind::implicit_euler);
  EXPECT_EQ(c.settings.linear_tolerance, 1e-6);
  EXPECT_EQ(describe_setting(c.row), "implicit_euler tol 1e-6, dt 0.003906 s");
  EXPECT_EQ(choose_for_accuracy(t, "t.csv", 0.5, base).settings.linear_tolerance, 1e-9);
}

}  // namespace
}  // namespace neurocloth
