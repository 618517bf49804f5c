// The speed-against-accuracy trade: the error metrics, the converged reference,
// the sweep, the Pareto front, the picker and the summary (the CSV: trade_csv_test.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>

#include "core/integrators/stability.h"
#include "core/io/input_error.h"
#include "support/hand_made_trade.h"
#include "support/test_support.h"
#include "tradeoff/accuracy_choice.h"
#include "tradeoff/pareto_front.h"
#include "tradeoff/sampled_run.h"
#include "tradeoff/trade_csv.h"
#include "tradeoff/trade_summary.h"
#include "tradeoff/tradeoff_sweep.h"

namespace neurocloth {
namespace {

using test::hand_made;
using test::hand_made_trade;
using test::kNaN;
using test::row;

// hanging.json: 20 x 20 nodes 0.05 m apart in x and z, 0.01 kg each, two pinned.
constexpr double kHangingSize = 0.95 * 1.4142135623730951;

SampledRun short_hanging_run(IntegratorKind kind = IntegratorKind::network, double dt = 1e-3) {
  const Scene scene = test::asset_scene("hanging");
  SolverSettings s = scene.solver;
  s.integrator = kind;
  s.dt = dt;
  return run_sampled(scene, s, sample_times(0.05, 4));
}

// ---- metrics ----

TEST(TradeoffMetrics, SampleTimesAreEvenAndEndOnTheRun) {
  const std::vector<double> t = sample_times(2, 8);
  ASSERT_EQ(t.size(), 8u);
  EXPECT_DOUBLE_EQ(t[0], 0.25);
  EXPECT_DOUBLE_EQ(t[3], 1.0);
  EXPECT_EQ(t.back(), 2.0);
}

TEST(TradeoffMetrics, ScaleIsTheDiagonalAndTheWeightDroppedByIt) {
  const ErrorScale scale = error_scale(test::asset_scene("hanging"));
  EXPECT_NEAR(scale.size, kHangingSize, 1e-12);
  EXPECT_NEAR(scale.energy, 398 * 0.01 * 9.81 * kHangingSize, 1e-9);
  EXPECT_EQ(std::accumulate(scale.free.begin(), scale.free.end(), 0), 398);
}

TEST(TradeoffMetrics, IdenticalRunsHaveNoError) {
  const SampledRun a = short_hanging_run(), b = short_hanging_run();
  ASSERT_TRUE(a.complete(4));
  const RunError e = compare_runs(a, b, error_scale(test::asset_scene("hanging")));
  EXPECT_EQ(e.position_max, 0.0);
  EXPECT_EQ(e.position_rms, 0.0);
  EXPECT_EQ(e.energy, 0.0);
  EXPECT_EQ(e.position_max_by_sample, std::vector<double>(4, 0.0));
}

TEST(TradeoffMetrics, AnOffsetOnOneNodeGivesItsSizeAsMaxAndItsShareAsRms) {
  const ErrorScale scale = error_scale(test::asset_scene("hanging"));
  const SampledRun reference = short_hanging_run();
  SampledRun run = reference;
  // Node 210 is free; a (3, 0, 4) mm offset at the third sample is 5 mm away.
  run.positions[2][3 * 210] += 0.003;
  run.positions[2][3 * 210 + 2] += 0.004;
  run.energy[1] += 0.25;
  const RunError e = compare_runs(run, reference, scale);
  EXPECT_NEAR(e.position_max, 0.005 / kHangingSize, 1e-13);
  EXPECT_NEAR(e.position_rms, std::sqrt(0.005 * 0.005 / (398 * 4)) / kHangingSize, 1e-13);
  EXPECT_NEAR(e.energy, 0.25 / scale.energy, 1e-13);
  EXPECT_EQ(e.position_max_by_sample[0], 0.0);
  EXPECT_NEAR(e.position_max_by_sample[2], 0.005 / kHangingSize, 1e-13);
}

TEST(TradeoffMetrics, PinnedNodesAreNotCompared) {
  const ErrorScale scale = error_scale(test::asset_scene("hanging"));
  const SampledRun reference = short_hanging_run();
  SampledRun run = reference;
  for (auto& p : run.positions) {
    p[1] += 1.0;  // node 0 (pinned) moved a metre
    for (std::size_t i = 3; i < p.size(); i += 3)
      p[i] -= 0.002;  // every other node 2 mm in x
  }
  const RunError e = compare_runs(run, reference, scale);
  EXPECT_NEAR(e.position_max, 0.002 / kHangingSize, 1e-13);
  EXPECT_NEAR(e.position_rms, 0.002 / kHangingSize, 1e-13);
}

TEST(TradeoffMetrics, RunsAtDifferentTimesCannotBeCompared) {
  const SampledRun a = short_hanging_run();
  SampledRun b = a;
  b.times.pop_back();
  b.positions.pop_back();
  b.energy.pop_back();
  EXPECT_THROW(compare_runs(a, b, error_scale(test::asset_scene("hanging"))),
               std::invalid_argument);
}

TEST(TradeoffMetrics, ADivergedRunIsNotComplete) {
  // Explicit Euler at 4 ms on the hanging cloth blows up within 0.5 s.
  const Scene scene = test::asset_scene("hanging");
  SolverSettings s = scene.solver;
  s.integrator = IntegratorKind::explicit_euler;
  s.dt = 0.004;
  const SampledRun run = run_sampled(scene, s, sample_times(0.5, 3));
  EXPECT_EQ(run.status, RunStatus::diverged);
  EXPECT_FALSE(run.complete(3));
  EXPECT_LT(run.times.size(), 3u);
}

// ---- the converged reference ----

// What a test checks must not depend on how fast this machine is: its plans
// get wall-time budgets no run of it comes near, so only the step counts and
// error targets decide where a sweep or a reference stops. (The budgets
// themselves are tested with one no run can meet.)
constexpr double kUnboundedWallSeconds = 1e6;

ReferencePlan unbounded_reference() {
  ReferencePlan plan;
  plan.budget_seconds = kUnboundedWallSeconds;
  return plan;
}

TradeoffPlan unbounded_sweep() {
  TradeoffPlan plan;
  plan.reference = unbounded_reference();
  plan.method_budget_seconds = kUnboundedWallSeconds;
  return plan;
}

// One mass on one spring (k = 40 N/m, m = 0.1 kg, no damping), let go at rest
// length: y(t) = y0 - (m g / k)(1 - cos(w t)).
TEST(TradeoffReference, ConvergesOnTheOscillatorAndMatchesItsClosedForm) {
  const Scene scene = test::asset_scene("spring_mass");
  const std::vector<double> times = sample_times(1.0, 4);
  const ErrorScale scale = error_scale(scene);
  const ConvergedReference ref = converge_reference(
      scene, times, scale, first_step(scene, IntegratorKind::rk4, 0.25), unbounded_reference());
  const ReferenceReport& r = ref.report;
  EXPECT_TRUE(r.met);
  EXPECT_EQ(r.stopped_by, "target");
  EXPECT_LT(r.change, 1e-9);
  EXPECT_GE(r.change, 0.0);
  EXPECT_EQ(r.dt, ref.run.settings.dt);
  EXPECT_EQ(r.runs, static_cast<int>(ref.coarser.size()) + 1);
  // It stopped at the first halving that met the target: the one before did not.
  ASSERT_GE(ref.coarser.size(), 2u);
  const RunError before =
      compare_runs(ref.coarser[ref.coarser.size() - 2], ref.coarser.back(), scale);
  EXPECT_GE(before.position_max, 1e-9);
  const RunError last = compare_runs(ref.coarser.back(), ref.run, scale);
  EXPECT_EQ(last.position_max, r.change);

  const double w = std::sqrt(40.0 / 0.1), drop = 0.1 * 9.81 / 40.0;
  for (std::size_t j = 0; j < times.size(); ++j) {
    const double y = 0.9 - drop * (1 - std::cos(w * times[j]));
    EXPECT_NEAR(ref.run.positions[j][4], y, 1e-9 * scale.size) << "t = " << times[j];
  }
}

TEST(TradeoffReference, UnreachableTargetStopsAtTheHalvingCapAndSaysSo) {
  const Scene scene = test::asset_scene("hanging");
  const std::vector<double> times = sample_times(0.05, 2);
  const ErrorScale scale = error_scale(scene);
  ReferencePlan plan = unbounded_reference();
  plan.target = 1e-30;  // below round-off: no step reaches it
  plan.max_halvings = 2;
  const ConvergedReference ref = converge_reference(scene, times, scale, 0.002, plan);
  EXPECT_FALSE(ref.report.met);
  EXPECT_EQ(ref.report.stopped_by, "halvings");
  EXPECT_EQ(ref.report.runs, 3);
  EXPECT_DOUBLE_EQ(ref.report.dt, 0.0005);
  EXPECT_GT(ref.report.change, 0.0);
  EXPECT_EQ(ref.report.change, compare_runs(ref.coarser.back(), ref.run, scale).position_max);
  EXPECT_EQ(ref.report.change_by_sample.size(), 2u);
}

TEST(TradeoffReference, ANoTimeBudgetReferenceComparesNothingAndClaimsNothing) {
  const Scene scene = test::asset_scene("hanging");
  ReferencePlan plan;
  plan.budget_seconds = 1e-9;
  const ConvergedReference ref =
      converge_reference(scene, sample_times(0.02, 2), error_scale(scene), 0.002, plan);
  EXPECT_EQ(ref.report.runs, 1);
  EXPECT_EQ(ref.report.stopped_by, "budget");
  EXPECT_FALSE(ref.report.met);
  EXPECT_LT(ref.report.change, 0.0);  // never compared
}

TEST(TradeoffReference, StartsPastTheStabilityBoundAndHalvesIntoIt) {
  // Twice RK4's step bound, rounded down to the interval over a power of two.
  const Scene scene = test::asset_scene("hanging");
  const double h = first_step(scene, IntegratorKind::rk4, 0.25);
  const double k = std::log2(0.25 / h);
  EXPECT_EQ(k, std::round(k));
  const ClothNetwork net = scene.build_network();
  const double bound =
      integrator_step_bound(net, *make_integrator(IntegratorKind::rk4, net), StepBound::gershgorin);
  EXPECT_LE(h, 2 * bound);
  EXPECT_GT(2 * h, 2 * bound);
  EXPECT_EQ(first_step(scene, IntegratorKind::implicit_euler, 0.25), 0.0625);
}

// ---- the sweep ----

TEST(TradeoffSweep, ErrorsShrinkAtEachIntegratorsOrder) {
  const Scene scene = test::asset_scene("hanging");
  TradeoffPlan plan = unbounded_sweep();
  plan.seconds = 0.1;
  plan.samples = 2;
  plan.max_levels = 3;
  plan.error_floor = 0;  // every level, however accurate
  plan.methods = {"network", "verlet", "rk4"};
  const TradeTable t = measure_tradeoff(scene, "hanging.json", plan);
  EXPECT_TRUE(t.reference.met) << t.reference.change;
  auto errors = [&](const std::string& method) {
    std::vector<double> e;
    for (const TradeRow& r : t.rows)
      if (r.method == method) {
        EXPECT_TRUE(r.ok()) << describe_setting(r);
        EXPECT_EQ(r.value, r.dt);
        if (!e.empty()) {
          EXPECT_EQ(r.dt, 0.5 * t.rows[&r - &t.rows[0] - 1].dt);
        }
        e.push_back(r.position_error_max);
      }
    return e;
  };
  // Halving the step divides the error by about 2^order.
  const std::vector<double> network = errors("network"), verlet = errors("verlet"),
                            rk4 = errors("rk4");
  ASSERT_EQ(network.size(), 3u);
  ASSERT_EQ(verlet.size(), 3u);
  for (std::size_t i = 1; i < 3; ++i) {
    EXPECT_NEAR(network[i - 1] / network[i], 2, 0.4) << i;
    EXPECT_NEAR(verlet[i - 1] / verlet[i], 4, 1.2) << i;
  }
  // RK4's line is the reference's own coarser runs, from past its stability
  // bound down; its first step is not yet in the asymptotic range.
  ASSERT_GE(rk4.size(), 4u);
  for (std::size_t i = 2; i < rk4.size(); ++i)
    EXPECT_NEAR(rk4[i - 1] / rk4[i], 16, 4) << i;
  EXPECT_EQ(t.sweep_stops, (std::vector<std::string>{"network: levels", "verlet: levels"}));
  for (const TradeRow& r : t.rows) {
    EXPECT_GT(r.wall_per_simulated_second, 0) << describe_setting(r);
    EXPECT_GE(r.force_evaluations, r.steps) << describe_setting(r);
  }
}

TEST(TradeoffSweep, AdaptiveSweepsItsSafetyAndSkipsEqualCaps) {
  // hanging's t_delta (1 ms) is below safety * bound for safety 1 and 1/2: one setting.
  const Scene scene = test::asset_scene("hanging");
  TradeoffPlan plan = unbounded_sweep();
  plan.seconds = 0.05;
  plan.samples = 1;
  plan.max_levels = 3;
  plan.error_floor = 0;
  plan.methods = {"adaptive"};
  const TradeTable t = measure_tradeoff(scene, "hanging.json", plan);
  ASSERT_EQ(t.rows.size(), 3u);
  EXPECT_EQ(t.rows[0].value, 1.0);
  EXPECT_EQ(t.rows[1].value, 0.25);
  EXPECT_EQ(t.rows[2].value, 0.125);
  for (const TradeRow& r : t.rows) {
    EXPECT_EQ(r.method, "adaptive");
    EXPECT_EQ(r.parameter, "safety");
    EXPECT_EQ(r.dt, scene.solver.dt);
  }
  EXPECT_GT(t.rows[0].position_error_max, t.rows[2].position_error_max);
}

TEST(TradeoffSweep, RefusesAPlanItCannotRun) {
  const Scene scene = test::asset_scene("hanging");
  TradeoffPlan plan;
  plan.seconds = 0;
  EXPECT_THROW(measure_tradeoff(scene, "", plan), std::invalid_argument);
  plan.seconds = 1;
  plan.methods = {"leapfrog"};
  EXPECT_THROW(measure_tradeoff(scene, "", plan), std::invalid_argument);
}

// ---- Pareto front and picker, on hand-made tables ----

TEST(TradeoffPareto, FrontHoldsWhatNothingBeatsCheapestFirst) {
  EXPECT_EQ(pareto_front(hand_made(), Metric::node_max), (std::vector<std::size_t>{3, 0, 1, 5, 6}));
}

TEST(TradeoffPareto, CheapestMeetingABudget) {
  const std::vector<TradeRow> rows = hand_made();
  EXPECT_EQ(cheapest_meeting(rows, 1.0, Metric::node_max), 3u);
  EXPECT_EQ(cheapest_meeting(rows, 0.1, Metric::node_max), 0u);    // the budget itself is met
  EXPECT_EQ(cheapest_meeting(rows, 0.05, Metric::node_max), 1u);   // ties with 5: the earlier row
  EXPECT_EQ(cheapest_meeting(rows, 0.002, Metric::node_max), 6u);  // same cost as 7, smaller error
  EXPECT_EQ(cheapest_meeting(rows, 0.0005, Metric::node_max), std::nullopt);
  EXPECT_EQ(most_accurate(rows, Metric::node_max), 6u);
}

TEST(TradeoffPareto, EqualCostGoesToTheSmallerErrorWhicheverComesFirst) {
  std::vector<TradeRow> rows = {row("rk4", 2, 0.004), row("verlet", 2, 0.003)};
  EXPECT_EQ(cheapest_meeting(rows, 0.01, Metric::node_max), 1u);
  std::swap(rows[0], rows[1]);
  EXPECT_EQ(cheapest_meeting(rows, 0.01, Metric::node_max), 0u);
}

TEST(TradeoffPareto, NothingFinishedMeansNothingToPick) {
  const std::vector<TradeRow> rows = {row("rk4", 1, kNaN, "diverged"),
                                      row("verlet", 1, kNaN, "stopped")};
  EXPECT_TRUE(pareto_front(rows, Metric::node_max).empty());
  EXPECT_EQ(cheapest_meeting(rows, 1e9, Metric::node_max), std::nullopt);
  EXPECT_EQ(most_accurate(rows, Metric::node_max), std::nullopt);
}

TEST(TradeoffAccuracy, PicksTheCheapestAndItsSettings) {
  SolverSettings base;
  base.adaptive = true;                // a scene propagated adaptively (table_drape)...
  base.divergence.check_interval = 7;  // ...and the rest of its settings, which stay
  const AccuracyChoice c = choose_for_accuracy(hand_made_trade(), "t.csv", 0.05, base);
  EXPECT_EQ(c.row_index, 1u);
  EXPECT_EQ(c.settings.integrator, IntegratorKind::verlet);
  EXPECT_FALSE(c.settings.adaptive);
  EXPECT_EQ(c.settings.dt, 0.001);
  EXPECT_EQ(c.settings.divergence.check_interval, 7);

  TradeRow adaptive = hand_made_trade().rows[7];
  adaptive.dt = 0.04;
  const SolverSettings a = settings_for(adaptive, base);
  EXPECT_TRUE(a.adaptive);
  EXPECT_EQ(a.integrator, IntegratorKind::network);
  EXPECT_EQ(a.adaptive_settings.safety, 0.25);
  EXPECT_EQ(a.dt, 0.04);
}

InputError accuracy_error(const TradeTable& t, double accuracy) {
  try {
    choose_for_accuracy(t, "trade.csv", accuracy, SolverSettings{});
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "accuracy " << accuracy << " was accepted";
  return InputError("", "", "");
}

TEST(TradeoffAccuracy, UnreachableAccuracyNamesTheBestAchievable) {
  const InputError e = accuracy_error(hand_made_trade(), 1e-4);
  EXPECT_EQ(e.file(), "trade.csv");
  EXPECT_EQ(e.field(), "--accuracy");
  const std::string what = e.what();
  EXPECT_NE(what.find("best achievable is rk4, dt 0.001 s"), std::string::npos) << what;
  EXPECT_NE(what.find("0.001"), std::string::npos) << what;
}

TEST(TradeoffAccuracy, RefusesWhatTheReferenceCannotResolve) {
  TradeTable t = hand_made_trade();
  t.reference.change = 0.02;
  t.reference.met = false;
  const std::string what = accuracy_error(t, 0.01).what();
  EXPECT_NE(what.find("only converged to 0.02"), std::string::npos) << what;
  EXPECT_NO_THROW(choose_for_accuracy(t, "trade.csv", 0.05, SolverSettings{}));
  t.reference.change = -1;  // never compared two runs: nothing is certified
  EXPECT_NE(std::string(accuracy_error(t, 0.5).what()).find("cannot be measured"),
            std::string::npos);
}

TEST(TradeoffAccuracy, RefusesNonPositiveAccuracy) {
  for (double bad : {0.0, -0.01, kNaN, std::numeric_limits<double>::infinity()}) {
    const std::string what = accuracy_error(hand_made_trade(), bad).what();
    EXPECT_NE(what.find("must be a finite number > 0"), std::string::npos) << what;
  }
}

TEST(TradeoffAccuracy, CommittedTradesLiveUnderAssets) {
  EXPECT_EQ(committed_trade_path("/somewhere/scenes/flag.json"),
            assets_directory() + "/tradeoff/flag.csv");
}

// ---- the summary ----

TEST(TradeoffSummary, NamesTheCheapestForEveryBudget) {
  TradeTable t = hand_made_trade();
  const std::string md = trade_summary(t, Metric::node_max, "chart.png");
  EXPECT_NE(md.find("![error against cost](chart.png)"), std::string::npos);
  EXPECT_NE(md.find("| 10% | network, dt 0.001 s | 0.1 |"), std::string::npos) << md;
  EXPECT_NE(md.find("| 1% | verlet, dt 0.001 s | 0.01 |"), std::string::npos) << md;
  EXPECT_NE(md.find("| 0.1% | rk4, dt 0.001 s | 0.001 |"), std::string::npos) << md;
  EXPECT_NE(md.find("| 0.01% | none measured; the best: rk4, dt 0.001 s at 0.001"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("target was **met**"), std::string::npos) << md;
  t.reference.met = false;
  t.reference.change = 0.003;
  const std::string unmet = trade_summary(t, Metric::node_max);
  EXPECT_NE(unmet.find("| 0.1% | not certified"), std::string::npos) << unmet;
  EXPECT_NE(unmet.find("**not met**"), std::string::npos) << unmet;
}

}  // namespace
}  // namespace neurocloth

namespace neurocloth {
namespace {

// A trade's run is checked in full at its last sample, as `simulate` checks
// its result: a run that ends blown up, with no periodic check before (40
// steps, fewer than check_interval), is a diverged row, not an "ok" one with
// a large error. (The last sample was once told by the address of a copy, so
// the check never ran.)
TEST(SampledRun, TheLastSampleIsCheckedInFull) {
  Scene scene = test::asset_scene("hanging");
  SolverSettings s = scene.solver;
  s.integrator = IntegratorKind::explicit_euler;
  s.dt = 0.003;  // 24 times its stable step: the energy grows without bound
  ASSERT_LT(40, s.divergence.check_interval);
  const SampledRun run = run_sampled(scene, s, {20 * s.dt, 40 * s.dt});
  EXPECT_EQ(run.status, RunStatus::diverged);
  EXPECT_NE(run.reason.find("no source"), std::string::npos) << run.reason;
  s.dt = 1e-4;  // below it: the same check passes
  EXPECT_EQ(run_sampled(scene, s, {20 * 0.003, 40 * 0.003}).status, RunStatus::ok);
}

}  // namespace
}  // namespace neurocloth
