// The speed-against-accuracy trade: the error metrics, the converged reference,
// the sweep, the Pareto front and the picker, and the trade's CSV.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>

#include "input_error.h"
#include "stability.h"
#include "test_support.h"
#include "tradeoff/accuracy_choice.h"
#include "tradeoff/pareto_front.h"
#include "tradeoff/trade_csv.h"
#include "tradeoff/trade_summary.h"
#include "tradeoff/tradeoff_sweep.h"

namespace neurocloth {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

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

// One mass on one spring (k = 40 N/m, m = 0.1 kg, no damping), let go at rest
// length: y(t) = y0 - (m g / k)(1 - cos(w t)).
TEST(TradeoffReference, ConvergesOnTheOscillatorAndMatchesItsClosedForm) {
  const Scene scene = test::asset_scene("spring_mass");
  const std::vector<double> times = sample_times(1.0, 4);
  const ErrorScale scale = error_scale(scene);
  const ConvergedReference ref =
      converge_reference(scene, times, scale, first_step(scene, IntegratorKind::rk4, 0.25), {});
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
  ReferencePlan plan;
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
      stable_step_bound(net, make_integrator(IntegratorKind::rk4, net)->stability_limit());
  EXPECT_LE(h, 2 * bound);
  EXPECT_GT(2 * h, 2 * bound);
  EXPECT_EQ(first_step(scene, IntegratorKind::implicit_euler, 0.25), 0.0625);
}

// ---- the sweep ----

TEST(TradeoffSweep, ErrorsShrinkAtEachIntegratorsOrder) {
  const Scene scene = test::asset_scene("hanging");
  TradeoffPlan plan;
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
  TradeoffPlan plan;
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

TradeRow row(const std::string& method, double cost, double error,
             const std::string& status = "ok") {
  TradeRow r;
  r.method = method;
  r.parameter = method == kAdaptiveMethod ? "safety" : "dt";
  r.value = r.dt = 0.001;
  r.wall_per_simulated_second = cost;
  r.position_error_max = error;
  r.position_error_rms = error / 4;
  r.status = status;
  return r;
}

std::vector<TradeRow> hand_made() {
  return {row("network", 1, 0.1),                        // 0: front
          row("verlet", 2, 0.01),                        // 1: front
          row("rk4", 3, 0.05),                           // 2: beaten by 1
          row("explicit_euler", 0.5, 0.5),               // 3: front (cheapest)
          row("explicit_euler", 0.1, kNaN, "diverged"),  // 4: not finished
          row("implicit_euler", 2, 0.01),                // 5: ties with 1: both on the front
          row("rk4", 4, 0.001),                          // 6: front
          row("adaptive", 4, 0.002)};                    // 7: beaten by 6 (same cost, larger error)
}

TEST(TradeoffPareto, FrontHoldsWhatNothingBeatsCheapestFirst) {
  EXPECT_EQ(pareto_front(hand_made()), (std::vector<std::size_t>{3, 0, 1, 5, 6}));
}

TEST(TradeoffPareto, CheapestMeetingABudget) {
  const std::vector<TradeRow> rows = hand_made();
  EXPECT_EQ(cheapest_meeting(rows, 1.0), 3u);
  EXPECT_EQ(cheapest_meeting(rows, 0.1), 0u);    // the budget itself is met
  EXPECT_EQ(cheapest_meeting(rows, 0.05), 1u);   // ties with 5: the earlier row
  EXPECT_EQ(cheapest_meeting(rows, 0.002), 6u);  // same cost as 7, smaller error
  EXPECT_EQ(cheapest_meeting(rows, 0.0005), std::nullopt);
  EXPECT_EQ(most_accurate(rows), 6u);
}

TEST(TradeoffPareto, EqualCostGoesToTheSmallerErrorWhicheverComesFirst) {
  std::vector<TradeRow> rows = {row("rk4", 2, 0.004), row("verlet", 2, 0.003)};
  EXPECT_EQ(cheapest_meeting(rows, 0.01), 1u);
  std::swap(rows[0], rows[1]);
  EXPECT_EQ(cheapest_meeting(rows, 0.01), 0u);
}

TEST(TradeoffPareto, NothingFinishedMeansNothingToPick) {
  const std::vector<TradeRow> rows = {row("rk4", 1, kNaN, "diverged"),
                                      row("verlet", 1, kNaN, "stopped")};
  EXPECT_TRUE(pareto_front(rows).empty());
  EXPECT_EQ(cheapest_meeting(rows, 1e9), std::nullopt);
  EXPECT_EQ(most_accurate(rows), std::nullopt);
}

TradeTable hand_made_trade() {
  TradeTable t;
  t.scene = "hand";
  t.seconds = 2;
  t.samples = 8;
  t.reference.change = 1e-10;
  t.reference.met = true;
  t.rows = hand_made();
  t.rows[7].value = 0.25;
  return t;
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
  const std::string md = trade_summary(t, "chart.png");
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
  const std::string unmet = trade_summary(t);
  EXPECT_NE(unmet.find("| 0.1% | not certified"), std::string::npos) << unmet;
  EXPECT_NE(unmet.find("**not met**"), std::string::npos) << unmet;
}

// ---- CSV ----

TradeTable csv_table() {
  TradeTable t = hand_made_trade();
  t.scene_file = "assets/scenes/hand.json";
  t.cloth_size = 1.3435;
  t.energy_scale = 52.45;
  ReferenceReport& r = t.reference;
  r.dt = 6.103515625e-05;
  r.change = 1.07e-10;
  r.change_by_sample = {1e-13, 1.07e-10};
  r.rms_change = 1e-11;
  r.met = true;
  r.runs = 7;
  r.wall_seconds = 0.88;
  r.stopped_by = "target";
  t.wall_seconds = 6.6;
  t.sweep_stops = {"network: levels", "adaptive: error floor"};
  t.rows[1].dt = t.rows[1].value = 0.0009765625;
  t.rows[1].steps = 2048;
  t.rows[1].force_evaluations = 4096;
  t.rows[7].rejected_steps = 12;
  return t;
}

TEST(TradeoffCsv, RoundTrips) {
  const TradeTable t = csv_table();
  const std::string text = trade_csv(t);
  const TradeTable back = parse_trade_csv(text, "x.csv");
  EXPECT_EQ(trade_csv(back), text);
  EXPECT_EQ(back.scene, "hand");
  EXPECT_EQ(back.scene_file, t.scene_file);
  EXPECT_EQ(back.seconds, 2);
  EXPECT_EQ(back.samples, 8);
  EXPECT_EQ(back.reference.dt, t.reference.dt);  // settings: exact
  EXPECT_EQ(back.reference.change, t.reference.change);
  EXPECT_EQ(back.reference.change_by_sample, t.reference.change_by_sample);
  EXPECT_TRUE(back.reference.met);
  EXPECT_EQ(back.reference.stopped_by, "target");
  EXPECT_EQ(back.sweep_stops, t.sweep_stops);
  ASSERT_EQ(back.rows.size(), t.rows.size());
  for (std::size_t i = 0; i < t.rows.size(); ++i) {
    SCOPED_TRACE(i);
    const TradeRow &a = t.rows[i], &b = back.rows[i];
    EXPECT_EQ(b.method, a.method);
    EXPECT_EQ(b.parameter, a.parameter);
    EXPECT_EQ(b.value, a.value);
    EXPECT_EQ(b.dt, a.dt);
    EXPECT_EQ(b.steps, a.steps);
    EXPECT_EQ(b.status, a.status);
    EXPECT_EQ(b.force_evaluations, a.force_evaluations);
    EXPECT_EQ(b.rejected_steps, a.rejected_steps);
    if (a.ok()) {
      EXPECT_NEAR(b.position_error_max, a.position_error_max, 1e-6 * a.position_error_max);
      EXPECT_NEAR(b.wall_per_simulated_second, a.wall_per_simulated_second,
                  1e-6 * a.wall_per_simulated_second);
    } else {
      EXPECT_TRUE(std::isnan(b.position_error_max));
    }
  }
}

// The InputError parse_trade_csv throws for `text`, or a failure.
std::optional<InputError> csv_error(const std::string& text) {
  try {
    parse_trade_csv(text, "broken.csv");
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "accepted:\n" << text;
  return std::nullopt;
}

// `text` with the first `from` on line `line` (1-based) replaced by `to`.
std::string edit_line(std::string text, int line, const std::string& from, const std::string& to) {
  std::size_t at = 0;
  for (int l = 1; l < line; ++l)
    at = text.find('\n', at) + 1;
  const std::size_t hit = text.find(from, at);
  EXPECT_LT(hit, text.find('\n', at)) << "test bug: '" << from << "' not on line " << line;
  return text.replace(hit, from.size(), to);
}

int line_of(const std::string& text, const std::string& start) {
  const std::size_t at = text.find("\n" + start);
  EXPECT_NE(at, std::string::npos) << start;
  return static_cast<int>(std::count(text.begin(), text.begin() + at + 1, '\n')) + 1;
}

struct BrokenCsv {
  const char* what;
  const char* line_start;  // the line edited
  const char* from;
  const char* to;
  const char* field;
  const char* at;  // the error's column is where this first is on the edited line ("": its end)
  const char* message;
};

TEST(TradeoffCsv, BrokenFilesNameFileLineColumnAndField) {
  const std::string good = trade_csv(csv_table());
  const BrokenCsv cases[] = {
      {"a word for a number", "verlet,", "0.01,", "0.0x1,", "position_error_max", "0.0x1",
       "not a finite number: '0.0x1'"},
      {"an unknown method", "verlet,", "verlet", "leapfrog", "method", "leapfrog",
       "unknown method"},
      {"the wrong parameter", "adaptive,", "safety", "dt", "parameter", "dt", "must be 'safety'"},
      {"a safety above 1", "adaptive,", "0.25", "1.5", "value", "1.5", "(0, 1]"},
      {"a negative step", "network,", "0.001,0.001", "0.001,-0.001", "dt", "-0.001", "must be > 0"},
      {"a fraction of a step count", "network,", ",0,", ",1.5,", "steps", "1.5", "whole number"},
      {"no error on a finished run", "rk4,dt,0.001,0.001,0,0.05", "0.05", "nan",
       "position_error_max", "nan", "not a finite number"},
      {"an unknown status", "rk4,dt,0.001,0.001,0,0.05", ",ok", ",fine", "status", "fine",
       "must be ok, diverged or stopped"},
      {"a missing field", "network,", ",0,ok", ",ok", "status", "", "expected 12 fields, found 11"},
      {"a misspelt column", "method,", "position_error_rms", "position_error_rsm", "header",
       "position_error_rsm", "column 7 must be 'position_error_rms'"},
      {"a bad metadata value", "# seconds", "2", "two", "# seconds", "two", "not a finite number"},
      {"reference_met neither yes nor no", "# reference_met", "yes", "maybe", "# reference_met",
       "maybe", "yes or no"},
  };
  for (const BrokenCsv& c : cases) {
    SCOPED_TRACE(c.what);
    const int line = line_of(good, c.line_start);
    const std::string text = edit_line(good, line, c.from, c.to);
    std::size_t start = 0;
    for (int l = 1; l < line; ++l)
      start = text.find('\n', start) + 1;
    const std::string edited = text.substr(start, text.find('\n', start) - start);
    const int column = static_cast<int>(*c.at ? edited.find(c.at) + 1 : edited.size() + 1);
    const auto e = csv_error(text);
    if (!e) continue;
    EXPECT_EQ(e->file(), "broken.csv");
    EXPECT_EQ(e->line(), line) << e->what();
    EXPECT_EQ(e->field(), c.field) << e->what();
    EXPECT_EQ(e->column(), column) << e->what();
    const std::string what = e->what();
    EXPECT_EQ(what.rfind("broken.csv:" + std::to_string(line) + ":", 0), 0u) << what;
    EXPECT_NE(what.find(c.message), std::string::npos) << what;
  }
}

TEST(TradeoffCsv, MissingPartsAreNamed) {
  const std::string good = trade_csv(csv_table());
  const std::string no_scene = edit_line(good, 2, "# scene: hand", "# nothing here");
  auto e = csv_error(no_scene);
  ASSERT_TRUE(e);
  EXPECT_EQ(e->field(), "# scene");
  EXPECT_EQ(e->line(), line_of(good, "method,"));

  e = csv_error(good.substr(0, good.find("method,")));
  ASSERT_TRUE(e);
  EXPECT_EQ(e->field(), "header");

  e = csv_error(good.substr(0, good.find("network,")));
  ASSERT_TRUE(e);
  EXPECT_EQ(e->field(), "rows");

  e = csv_error("");
  ASSERT_TRUE(e);
  EXPECT_EQ(e->field(), "header");

  try {
    read_trade_csv("/no/such/trade.csv");
    ADD_FAILURE() << "read a file that does not exist";
  } catch (const InputError& err) {
    EXPECT_EQ(err.file(), "/no/such/trade.csv");
  }
}

TEST(TradeoffCsv, BlankLinesCountTowardsLineNumbers) {
  std::string text = trade_csv(csv_table());
  const int line = line_of(text, "verlet,");
  text.insert(text.find("method,"), "\n\n");
  const auto e = csv_error(edit_line(text, line + 2, "verlet", "leapfrog"));
  ASSERT_TRUE(e);
  EXPECT_EQ(e->line(), line + 2) << e->what();
}

TEST(TradeoffCsv, AcceptsWindowsLineEndsAndPeoplesComments) {
  std::string text = trade_csv(csv_table());
  text.insert(text.find("method,"), "# measured on a quiet afternoon\n");
  std::string crlf;
  for (char c : text)
    crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
  const TradeTable t = parse_trade_csv(crlf, "x.csv");
  EXPECT_EQ(t.rows.size(), csv_table().rows.size());
  EXPECT_EQ(t.rows.back().status, "ok");
}

}  // namespace
}  // namespace neurocloth
