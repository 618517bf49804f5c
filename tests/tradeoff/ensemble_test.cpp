// The scene's own spread (ensemble.h) and what it does to a trade: members
// shifted as documented, a floor that grows with the shift, rows measured
// against the members, picks never tighter than the floor.
#include <gtest/gtest.h>

#include <cmath>

#include "core/io/input_error.h"
#include "support/short_trade_plan.h"
#include "support/test_support.h"
#include "tradeoff/accuracy_choice.h"
#include "tradeoff/trade_csv.h"
#include "tradeoff/tradeoff_sweep.h"

namespace neurocloth {
namespace {

TEST(Ensemble, EachMemberIsTheClothShiftedAcrossGravityBySeed) {
  const Scene scene = test::asset_scene("table_drape");
  EnsemblePlan plan;
  plan.members = 8;
  plan.shift = 0.001;
  Vec3 sum = Vec3::Zero();
  for (int k = 0; k < plan.members; ++k) {
    const Vec3 s = member_shift(scene, plan, k);
    EXPECT_NEAR(s.norm(), 0.001, 1e-15) << k;
    EXPECT_EQ(s.y(), 0) << k;  // gravity is -y
    EXPECT_EQ(s, member_shift(scene, plan, k)) << "deterministic";
    sum += s;
    for (int other = 0; other < k; ++other)
      EXPECT_GT((s - member_shift(scene, plan, other)).norm(), 0.7e-3) << k << " " << other;
  }
  plan.seed = 2;
  EXPECT_NE(member_shift(scene, plan, 0), member_shift(scene, EnsemblePlan{8, 0.001, 1}, 0));
  const Scene moved = shifted_scene(scene, Vec3(0.001, 0, 0));
  EXPECT_EQ(moved.topology.rest_positions[5].x(), scene.topology.rest_positions[5].x() + 0.001);
  EXPECT_EQ(moved.modules.size(), scene.modules.size());
}

TEST(Ensemble, RefusesSizesAndShiftsOutOfRange) {
  EXPECT_EQ(ensemble_refusal({8, 0.001, 1}), "");
  EXPECT_NE(ensemble_refusal({1, 0.001, 1}).find("[2, 64]"), std::string::npos);
  EXPECT_NE(ensemble_refusal({65, 0.001, 1}).find("[2, 64]"), std::string::npos);
  EXPECT_NE(ensemble_refusal({8, 0, 1}).find("shift"), std::string::npos);
  EXPECT_NE(ensemble_refusal({8, 0.06, 1}).find("shift"), std::string::npos);
  EXPECT_NE(ensemble_refusal({8, NAN, 1}).find("shift"), std::string::npos);
}

TEST(Ensemble, QuantilesInterpolateBetweenOrderStatistics) {
  EXPECT_EQ(quantile({3, 1, 2}, 0.5), 2);
  EXPECT_DOUBLE_EQ(quantile({1, 2, 3, 4}, 0.5), 2.5);
  EXPECT_DOUBLE_EQ(quantile({0, 10}, 0.9), 9);
  EXPECT_TRUE(std::isnan(quantile({}, 0.5)));
  EXPECT_TRUE(std::isnan(quantile({1, NAN}, 0.5)));
}

// The table drape on an 8 x 8 cloth, 0.3 s (it reaches the table): the
// spread a micrometre makes is far below a millimetre's, and a trade with
// an ensemble measures its rows against the members.
Scene small_drape() {
  return resized_grid(test::asset_scene("table_drape"), 8);
}

// The reference stops at a change of 1e-7 (or 8 halvings), its coarser runs
// are the rk4 line.
TradeoffPlan drape_plan(int members, double shift) {
  TradeoffPlan plan = test::short_trade_plan("network");
  plan.methods.push_back("rk4");
  plan.reference.target = 1e-7;
  plan.reference.max_halvings = 8;
  plan.seconds = 0.3;
  plan.samples = 2;
  plan.ensemble.members = members;
  plan.ensemble.shift = shift;
  plan.workers = 1;
  return plan;
}

// Measured once for the tests below.
const TradeTable& millimetre_trade() {
  static const TradeTable t = measure_tradeoff(small_drape(), "small", drape_plan(3, 1e-3));
  return t;
}

TEST(Ensemble, TheFloorGrowsWithTheShiftAndRowsAreMeasuredAgainstIt) {
  const TradeTable fine = measure_tradeoff(small_drape(), "small", drape_plan(3, 1e-6));
  const TradeTable& coarse = millimetre_trade();
  ASSERT_TRUE(fine.floor && coarse.floor);
  EXPECT_EQ(coarse.floor->members, 3);
  EXPECT_EQ(coarse.floor->median_by_sample.size(), 2u);
  for (Metric m : {Metric::node_max, Metric::node_rms, Metric::surface_mean, Metric::drape}) {
    EXPECT_GT(coarse.floor->p90[slot(m)], 10 * fine.floor->p90[slot(m)]) << to_string(m);
    EXPECT_GE(coarse.floor->p90[slot(m)], coarse.floor->median[slot(m)]) << to_string(m);
  }
  // A 1 mm shift on a 0.59 m cloth's diagonal moves its nodes at least that.
  EXPECT_GT(coarse.floor->median[slot(Metric::node_max)], 0.001 / coarse.cloth_size);
  for (const TradeRow& r : coarse.rows) {
    if (!r.ok()) continue;
    for (Metric m : kAllMetrics)
      EXPECT_TRUE(std::isfinite(r.ensemble[slot(m)])) << describe_setting(r) << to_string(m);
    // At least the shift from every member, at most its node error plus the members'.
    EXPECT_GE(r.ensemble[slot(Metric::node_max)], 0.9 * 0.001 / coarse.cloth_size);
  }
  // The floor and the rows' distances survive the CSV.
  const TradeTable back = parse_trade_csv(trade_csv(coarse), "e.csv");
  ASSERT_TRUE(back.floor);
  EXPECT_EQ(back.floor->members, 3);
  EXPECT_EQ(back.floor->shift, 1e-3);
  EXPECT_NEAR(back.floor->p90[slot(Metric::surface_mean)],
              coarse.floor->p90[slot(Metric::surface_mean)],
              1e-5 * coarse.floor->p90[slot(Metric::surface_mean)]);
  EXPECT_EQ(back.floor->p90_by_sample.size(), 2u);
  EXPECT_EQ(trade_csv(back), trade_csv(parse_trade_csv(trade_csv(back), "again.csv")));
}

// E below the floor is picked against the floor, and the choice says so.
TEST(Ensemble, APickIsNeverAskedTighterThanTheScenesOwnSpread) {
  const TradeTable& t = millimetre_trade();
  ASSERT_TRUE(t.floor);
  const double floor = t.floor->p90[slot(kDefaultMetric)];
  EXPECT_EQ(default_metric(t), kDefaultMetric);
  const AccuracyChoice c = choose_for_accuracy(t, "t.csv", floor / 100, SolverSettings{});
  EXPECT_EQ(c.metric, kDefaultMetric);
  EXPECT_EQ(c.target, floor);
  EXPECT_LE(c.error, floor);
  EXPECT_NE(c.floor_note.find("this scene's own spread"), std::string::npos) << c.floor_note;
  const AccuracyChoice loose = choose_for_accuracy(t, "t.csv", 0.5, SolverSettings{});
  EXPECT_EQ(loose.target, 0.5);
  EXPECT_TRUE(loose.floor_note.empty());
  // Without an ensemble only node_max was measured: another metric is refused by name.
  TradeTable old = t;
  old.floor.reset();
  for (TradeRow& r : old.rows)
    r.ensemble = unmeasured_metrics();
  EXPECT_EQ(default_metric(old), Metric::node_max);
  try {
    choose_for_accuracy(old, "old.csv", 0.1, SolverSettings{}, "--accuracy", Metric::surface_mean);
    FAIL() << "no surface_mean in a trade without an ensemble";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "--metric");
    EXPECT_NE(std::string(e.what()).find("tradeoff --ensemble"), std::string::npos) << e.what();
  }
}

TEST(Ensemble, APlanOutOfRangeIsRefusedBeforeAnyRun) {
  EXPECT_THROW(measure_tradeoff(small_drape(), "small", drape_plan(1, 1e-3)),
               std::invalid_argument);
  EXPECT_THROW(measure_tradeoff(small_drape(), "small", drape_plan(3, 1.0)), std::invalid_argument);
}

}  // namespace
}  // namespace neurocloth
