// Projective's iterations per step as a measured accuracy knob: the sweep runs
// each iterations count at every step it tries, and a picked row's iterations
// reach the settings it stands for.
#include <gtest/gtest.h>

#include <set>
#include <string>
#include <vector>

#include "support/hand_made_trade.h"
#include "support/short_trade_plan.h"
#include "support/test_support.h"
#include "tradeoff/accuracy_choice.h"
#include "tradeoff/trade_summary.h"
#include "tradeoff/tradeoff_sweep.h"

namespace neurocloth {
namespace {

TradeoffPlan projective_plan() {
  TradeoffPlan plan = test::short_trade_plan("projective");
  plan.projective_iterations = {1, 4};
  return plan;
}

TEST(ProjectiveTrade, EveryStepTriedRunsEachIterationsCount) {
  const Scene scene = test::asset_scene("hanging");
  const TradeoffPlan plan = projective_plan();
  const TradeTable t = measure_tradeoff(scene, "hanging.json", plan);
  ASSERT_EQ(t.rows.size(), 4u);
  const double first = first_step(scene, IntegratorKind::projective, plan.seconds / plan.samples);
  const double dts[] = {first, first, first / 2, first / 2};
  const int iterations[] = {1, 4, 1, 4};
  for (std::size_t i = 0; i < t.rows.size(); ++i) {
    const TradeRow& r = t.rows[i];
    SCOPED_TRACE(describe_setting(r));
    EXPECT_EQ(r.method, "projective");
    EXPECT_EQ(r.parameter, "dt");
    EXPECT_EQ(r.dt, dts[i]);
    EXPECT_EQ(r.value, r.dt);
    EXPECT_EQ(r.iterations, iterations[i]);
    EXPECT_TRUE(r.ok()) << r.status;
  }
  // The iterations count changes the motion: same step, different errors.
  EXPECT_NE(t.rows[0].position_error_max, t.rows[1].position_error_max);
  EXPECT_NE(t.rows[2].position_error_max, t.rows[3].position_error_max);
  EXPECT_EQ(t.sweep_stops,
            (std::vector<std::string>{"projective 1 it.: levels", "projective 4 it.: levels"}));

  // A row's settings are the ones that measured it: run again, the same error.
  const TradeRow& row = t.rows[3];
  const SolverSettings s = settings_for(row, scene.solver);
  EXPECT_EQ(s.iterations, 4);
  const std::vector<double> times = sample_times(plan.seconds, plan.samples);
  const SampledRun again = run_sampled(scene, s, times);
  const SampledRun reference = run_sampled(
      scene,
      [&] {
        SolverSettings r = scene.solver;
        r.integrator = IntegratorKind::rk4;
        r.adaptive = false;
        r.dt = t.reference.dt;
        return r;
      }(),
      times);
  EXPECT_EQ(compare_runs(again, reference, error_scale(scene)).position_max,
            row.position_error_max);
}

TEST(ProjectiveTrade, ALineThatReachesTheFloorStopsAloneAndTheBudgetStopsAll) {
  const Scene scene = test::asset_scene("hanging");
  TradeoffPlan plan = projective_plan();
  plan.max_levels = 3;
  plan.error_floor = 1;  // every finished run is within the floor at once
  TradeTable t = measure_tradeoff(scene, "hanging.json", plan);
  ASSERT_EQ(t.rows.size(), 2u) << "both lines stop at their first step";
  EXPECT_EQ(t.sweep_stops, (std::vector<std::string>{"projective 1 it.: error floor",
                                                     "projective 4 it.: error floor"}));

  plan = projective_plan();
  plan.method_budget_seconds = 0;  // no run fits: one step, then the budget
  t = measure_tradeoff(scene, "hanging.json", plan);
  ASSERT_EQ(t.rows.size(), 2u);
  EXPECT_EQ(t.rows[0].iterations, 1);
  EXPECT_EQ(t.rows[1].iterations, 4);
  EXPECT_EQ(t.sweep_stops,
            (std::vector<std::string>{"projective 1 it.: budget", "projective 4 it.: budget"}));
}

TEST(ProjectiveTrade, RefusesAGridItCannotRun) {
  const Scene scene = test::asset_scene("hanging");
  TradeoffPlan plan = projective_plan();
  for (std::vector<int> bad : {std::vector<int>{}, {0}, {4, 1001}}) {
    plan.projective_iterations = bad;
    EXPECT_THROW(measure_tradeoff(scene, "", plan), std::invalid_argument);
  }
  plan.methods = {"network"};  // projective not swept: its grid is not used
  plan.projective_iterations = {};
  plan.max_levels = 1;
  EXPECT_NO_THROW(measure_tradeoff(scene, "", plan));
}

// The cheapest row meeting the budget is projective at 4 iterations: its
// settings carry them, over the scene's own, and the summary names them.
TEST(ProjectiveTrade, APickedProjectiveRowCarriesItsIterations) {
  TradeTable t = test::hand_made_trade();
  TradeRow four = test::row("projective", 0.6, 0.04);
  four.dt = four.value = 1.0 / 64;
  four.iterations = 4;
  TradeRow thirty = four;
  thirty.iterations = 30;
  thirty.wall_per_simulated_second = 1.5;
  thirty.position_error_max = 0.03;
  t.rows.push_back(thirty);
  t.rows.push_back(four);
  SolverSettings base;
  base.iterations = 10;
  const AccuracyChoice c = choose_for_accuracy(t, "t.csv", 0.05, base);
  EXPECT_EQ(c.row_index, t.rows.size() - 1);
  EXPECT_EQ(c.settings.integrator, IntegratorKind::projective);
  EXPECT_FALSE(c.settings.adaptive);
  EXPECT_EQ(c.settings.dt, 1.0 / 64);
  EXPECT_EQ(c.settings.iterations, 4);
  // Another method's pick keeps the scene's iterations.
  EXPECT_EQ(choose_for_accuracy(t, "t.csv", 0.5, base).settings.iterations, 10);

  const std::string md = trade_summary(t, Metric::node_max);
  EXPECT_NE(md.find("| 10% | projective 4 it., dt 0.01562 s | 0.04 |"), std::string::npos) << md;
  EXPECT_NE(md.find("- projective 4 it., dt 0.01562 s: node_max 0.04"), std::string::npos) << md;

  TradeRow wrong = t.rows[0];  // network
  wrong.iterations = 4;
  EXPECT_THROW(settings_for(wrong, base), std::invalid_argument);
}

}  // namespace
}  // namespace neurocloth
