// The window's choice of a solver that keeps a resized cloth in real time,
// with the costs given (the probe itself is wall-clock and not tested here).
#include "runtime/realtime_pick.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <vector>

#include "core/simulation/simulation.h"
#include "support/scratch_dir.h"
#include "support/test_support.h"
#include "tradeoff/trade_csv.h"

namespace neurocloth {
namespace {

// Costs by setting: the scene's own solver, and projective at `a + b * iterations`.
struct FakeCosts {
  double own, a, b;
  mutable std::vector<SolverSettings> asked;
  double operator()(const Scene& s) const {
    asked.push_back(s.solver);
    if (s.solver.integrator != IntegratorKind::projective) return own;
    return a + b * s.solver.iterations;
  }
};

TEST(RealtimePick, KeepsTheScenesSolverWhenItKeepsUp) {
  const Scene scene = test::asset_scene("table_drape");
  FakeCosts costs{0.5, 0.1, 0.1, {}};
  const RealtimePick pick = pick_for_real_time(scene, std::ref(costs));
  EXPECT_FALSE(pick.switched);
  EXPECT_EQ(pick.picked.integrator, scene.solver.integrator);
  EXPECT_EQ(costs.asked.size(), 1u);  // nothing else timed
}

TEST(RealtimePick, TakesTheMostIterationsThatFitTheBudget) {
  const Scene scene = test::asset_scene("table_drape");
  ASSERT_TRUE(scene.solver.adaptive);
  // 0.1 + 0.14 it: 4 iterations cost 0.66, 5 cost 0.8 (the budget is 0.7).
  FakeCosts costs{100.0, 0.1, 0.14, {}};
  const RealtimePick pick = pick_for_real_time(scene, std::ref(costs));
  ASSERT_TRUE(pick.switched);
  EXPECT_EQ(pick.picked.integrator, IntegratorKind::projective);
  EXPECT_FALSE(pick.picked.adaptive);
  EXPECT_DOUBLE_EQ(pick.picked.dt, kRealtimeStep);
  EXPECT_EQ(pick.picked.iterations, 4);
  EXPECT_NEAR(pick.picked_cost, 0.66, 1e-12);
  EXPECT_EQ(pick.own.integrator, scene.solver.integrator);  // what "back" restores
  EXPECT_TRUE(pick.own.adaptive);
  EXPECT_NE(pick.note.find("projective, 4 iterations"), std::string::npos) << pick.note;
  EXPECT_NE(pick.note.find("0.01x real time"), std::string::npos) << pick.note;
  EXPECT_NO_THROW(validate(pick.picked));
}

TEST(RealtimePick, SaysWhenEvenOneIterationDoesNotKeepUp) {
  const Scene scene = test::asset_scene("table_drape");
  FakeCosts costs{100.0, 1.0, 0.5, {}};  // one iteration: 1.5 s per simulated second
  const RealtimePick pick = pick_for_real_time(scene, std::ref(costs));
  ASSERT_TRUE(pick.switched);
  EXPECT_EQ(pick.picked.iterations, 1);
  EXPECT_NE(pick.note.find("even this runs only 0.67x"), std::string::npos) << pick.note;
}

TEST(RealtimePick, SaysWhenOneIterationKeepsUpWithLittleToSpare) {
  const Scene scene = test::asset_scene("table_drape");
  FakeCosts costs{100.0, 0.7, 0.1, {}};  // one iteration: 0.8 s per simulated second
  const RealtimePick pick = pick_for_real_time(scene, std::ref(costs));
  ASSERT_TRUE(pick.switched);
  EXPECT_EQ(pick.picked.iterations, 1);
  EXPECT_NE(pick.note.find("this runs 1.2x, with little to spare"), std::string::npos) << pick.note;
}

TEST(RealtimePick, AMachineFastEnoughForTheDefaultIterationsGetsThem) {
  const Scene scene = test::asset_scene("table_drape");
  FakeCosts costs{100.0, 0.01, 0.01, {}};
  const RealtimePick pick = pick_for_real_time(scene, std::ref(costs));
  ASSERT_TRUE(pick.switched);
  EXPECT_EQ(pick.picked.iterations, kDefaultProjectiveIterations);
}

// The table drape resized to 8 x 8 (the costs are given: nothing is run).
Scene drape_at_8() {
  return resized_grid(test::asset_scene("table_drape"), 8);
}
const char* kDrapeFile = "assets/scenes/table_drape.json";

TradeRow projective_row(double dt, int iterations, double error) {
  TradeRow r;
  r.method = "projective";
  r.parameter = "dt";
  r.dt = r.value = dt;
  r.iterations = iterations;
  r.steps = 60;
  r.position_error_max = error;
  r.position_error_rms = error / 4;
  r.energy_error = error / 10;
  r.wall_per_simulated_second = 0.1 * iterations;
  r.force_evaluations = 60;
  return r;
}

// A trade measured at `grid` x `grid` with `rows`, written where a test can read it
// (with `floor`: an ensemble whose spread is `floor` in every metric).
std::string write_trade(const std::string& name, int grid, const std::vector<TradeRow>& rows,
                        double floor = 0) {
  TradeTable t;
  t.scene = "table_drape";
  t.scene_file = kDrapeFile;
  t.seconds = 1;
  t.samples = 4;
  t.grid_rows = t.grid_cols = grid;
  t.cloth_size = 1.7;
  t.energy_scale = 36;
  t.reference.dt = 1e-5;
  t.reference.change = 1e-3;
  t.reference.stopped_by = "budget";
  t.rows = rows;
  if (floor > 0) {
    EnsembleFloor f;
    f.members = 8;
    f.shift = 0.001;
    f.member_dt = 1e-5;
    f.median.fill(floor / 2);
    f.p90.fill(floor);
    t.floor = f;
  }
  const std::string path = test::scratch_path(name);
  std::ofstream(path, std::ios::trunc) << trade_csv(t);
  return path;
}

// The pick on the drape at 8 x 8 with a trade of `rows` beside it, where up to
// 4 iterations fit the budget.
RealtimePick pick_at_8(const std::vector<TradeRow>& rows) {
  const std::string path = write_trade("drape.8.csv", 8, rows);
  FakeCosts costs{100.0, 0.1, 0.14, {}};
  return pick_for_real_time(drape_at_8(), std::ref(costs), find_sized_trade(kDrapeFile, 8, path));
}

// Errors falling with the iterations, as on a smooth cloth: 30% / iterations.
std::vector<TradeRow> falling_errors() {
  std::vector<TradeRow> rows;
  for (int it = 1; it <= 10; ++it)
    rows.push_back(projective_row(kRealtimeStep, it, 0.3 / it));
  return rows;
}

TEST(RealtimePick, QuotesThePickedSettingsErrorMeasuredAtThisSize) {
  std::vector<TradeRow> rows = falling_errors();
  // Neither is the window's setting: another step, and a run that did not finish.
  rows.push_back(projective_row(1.0 / 64, 4, 1e-6));
  TradeRow diverged = projective_row(kRealtimeStep, 4, 0);
  diverged.status = "diverged";
  rows.insert(rows.begin(), diverged);
  const std::string path = write_trade("drape.8.csv", 8, rows);
  const SizedTrade trade = find_sized_trade(kDrapeFile, 8, path);
  ASSERT_TRUE(trade.table) << trade.problem;
  FakeCosts costs{100.0, 0.1, 0.14, {}};  // 4 iterations fit, 5 do not
  const RealtimePick pick = pick_for_real_time(drape_at_8(), std::ref(costs), trade);
  ASSERT_TRUE(pick.switched);
  EXPECT_EQ(pick.picked.iterations, 4);
  ASSERT_TRUE(pick.measured);
  EXPECT_EQ(pick.measured->iterations, 4);
  EXPECT_DOUBLE_EQ(pick.measured->position_error_max, 0.075);
  EXPECT_EQ(pick.measured_in, path);
  EXPECT_NE(pick.note.find("Measured at 8 x 8: projective 4 it., dt 1/60 s: max position error "
                           "7.5% of the cloth's size over its first 1 s (rms 1.9%; the reference "
                           "is good to 0.1%), in " +
                           path),
            std::string::npos)
      << pick.note;
}

// With an ensemble the note quotes the error in the default metric and the
// scene's own spread, and counts whose errors are all within that spread are a
// tie won by the fewest iterations.
TEST(RealtimePick, QuotesTheErrorAgainstTheScenesOwnSpread) {
  std::vector<TradeRow> rows;
  for (int it = 1; it <= 4; ++it) {
    TradeRow r = projective_row(kRealtimeStep, it, 0.3 / it);
    r.ensemble.fill(0.004 / it);  // 0.4%, 0.2%, 0.13%, 0.1%
    rows.push_back(r);
  }
  const std::string path = write_trade("drape.8.csv", 8, rows, 0.0025);
  FakeCosts costs{100.0, 0.1, 0.14, {}};  // 4 iterations fit, 5 do not
  const RealtimePick pick =
      pick_for_real_time(drape_at_8(), std::ref(costs), find_sized_trade(kDrapeFile, 8, path));
  ASSERT_TRUE(pick.measured);
  EXPECT_EQ(pick.picked.iterations, 2) << "2, 3 and 4 are within the spread; 1 is not";
  EXPECT_NE(pick.note.find("Measured at 8 x 8: projective 2 it., dt 1/60 s: error 0.2% "
                           "(energy; spread 0.25%) over its first 1 s, within the scene's "
                           "own spread (8 references shifted 1 mm), in " +
                           path),
            std::string::npos)
      << pick.note;
}

TEST(RealtimePick, PrefersTheLeastMeasuredErrorAmongTheSettingsThatFit) {
  // 2 iterations land nearest the reference; 7 nearer still, but they do not fit.
  const RealtimePick pick =
      pick_at_8({projective_row(kRealtimeStep, 1, 0.2), projective_row(kRealtimeStep, 2, 0.05),
                 projective_row(kRealtimeStep, 4, 0.06), projective_row(kRealtimeStep, 7, 0.01)});
  EXPECT_EQ(pick.picked.iterations, 2);
  ASSERT_TRUE(pick.measured);
  EXPECT_DOUBLE_EQ(pick.measured->position_error_max, 0.05);
  EXPECT_NEAR(pick.picked_cost, 0.1 + 0.14 * 2, 1e-12);
}

// Errors within the reference's resolution (here 0.1% of the size) of the
// least cannot be told apart: then the fewest iterations among them, which
// leave the renderer the most of the machine. Measured from the least error,
// not from the first count looked at: 2 ties with 3 (the least), 1 does not.
TEST(RealtimePick, ErrorsTheReferenceCannotTellApartAreATieWonByTheCheapest) {
  const RealtimePick pick = pick_at_8(
      {projective_row(kRealtimeStep, 1, 0.0520), projective_row(kRealtimeStep, 2, 0.0509),
       projective_row(kRealtimeStep, 3, 0.0500), projective_row(kRealtimeStep, 4, 0.0515)});
  EXPECT_EQ(pick.picked.iterations, 2);
  ASSERT_TRUE(pick.measured);
  EXPECT_DOUBLE_EQ(pick.measured->position_error_max, 0.0509);
}

TEST(RealtimePick, SaysWhenTheErrorAtThisSizeIsNotMeasuredAndHowToMeasureIt) {
  // A name in the test's emptied folder: no file is there.
  const std::string nowhere = test::scratch_path("none.8.csv");
  const SizedTrade trade = find_sized_trade(kDrapeFile, 8, nowhere);
  EXPECT_FALSE(trade.table);
  EXPECT_TRUE(trade.problem.empty()) << trade.problem;
  FakeCosts costs{100.0, 0.1, 0.14, {}};
  const RealtimePick pick = pick_for_real_time(drape_at_8(), std::ref(costs), trade);
  EXPECT_EQ(pick.picked.iterations, 4);  // the most that fit, as without a trade
  EXPECT_FALSE(pick.measured);
  for (const std::string& part :
       {std::string("Its error at 8 x 8 is not measured; to measure it: neurocloth-cli tradeoff ") +
            kDrapeFile + " --size 8 ",
        std::string("--methods projective --dt 1/60 --projective-iterations 1,2,3,4,5,6,7,8,9,10"),
        "--out " + nowhere.substr(0, nowhere.size() - 4)})
    EXPECT_NE(pick.note.find(part), std::string::npos) << part << "\n not in: " << pick.note;
}

TEST(RealtimePick, NeverQuotesATradeMeasuredAtAnotherSize) {
  const std::string path = write_trade("drape.32.csv", 32, falling_errors());
  const SizedTrade trade = find_sized_trade(kDrapeFile, 8, path);
  EXPECT_FALSE(trade.table);
  EXPECT_NE(trade.problem.find(path), std::string::npos) << trade.problem;
  EXPECT_NE(trade.problem.find("# grid"), std::string::npos) << trade.problem;
  FakeCosts costs{100.0, 0.1, 0.14, {}};
  const RealtimePick pick = pick_for_real_time(drape_at_8(), std::ref(costs), trade);
  EXPECT_FALSE(pick.measured);
  EXPECT_NE(pick.note.find("Its error at 8 x 8 is not measured (" + path), std::string::npos)
      << pick.note;
  EXPECT_NE(pick.note.find("measured on a 32 x 32 grid, not 8 x 8"), std::string::npos)
      << pick.note;
}

}  // namespace
}  // namespace neurocloth

namespace neurocloth {
namespace {

// Soundness by setting: a step of `diverges_above` or more diverges.
struct FakeSound {
  double diverges_above;
  mutable std::vector<SolverSettings> asked;
  bool operator()(const Scene& s) const {
    asked.push_back(s.solver);
    return s.solver.dt < diverges_above;
  }
};

// A setting that diverges within the cloth's first second at 1/60 s (the
// 256 x 256 drape lands on the table a whole step's fall at once) is not
// kept: the step is halved until one runs through, its iterations chosen
// again for the doubled cost, and the note says why.
TEST(RealtimePick, HalvesTheStepUntilTheClothRunsThrough) {
  const Scene scene = test::asset_scene("table_drape");
  FakeCosts costs{100.0, 0.1, 0.14, {}};  // at 1/60 s 4 iterations fit; at 1/120 s only 1
  FakeSound sound{0.75 * kRealtimeStep, {}};
  const RealtimePick pick = pick_for_real_time(scene, std::ref(costs), {}, std::ref(sound));
  ASSERT_TRUE(pick.switched);
  EXPECT_DOUBLE_EQ(pick.picked.dt, kRealtimeStep / 2);
  EXPECT_EQ(pick.picked.iterations, 1);
  EXPECT_NEAR(pick.picked_cost, 2 * 0.24, 1e-12);
  ASSERT_EQ(sound.asked.size(), 2u);
  EXPECT_EQ(sound.asked[0].iterations, 4);
  EXPECT_DOUBLE_EQ(sound.asked[0].dt, kRealtimeStep);
  EXPECT_EQ(sound.asked[1].iterations, 1);
  EXPECT_NE(pick.note.find("projective, 1 iteration, dt 1/120 s"), std::string::npos) << pick.note;
  EXPECT_NE(pick.note.find("At dt 1/60 s it diverged within the cloth's first 1 s"),
            std::string::npos)
      << pick.note;
  EXPECT_EQ(pick.note.find("expect it to stop"), std::string::npos) << pick.note;
  EXPECT_NO_THROW(validate(pick.picked));
}

// Its note's command measures the step it took, not 1/60 s.
TEST(RealtimePick, AHalvedPickSaysHowToMeasureItsOwnStep) {
  const SizedTrade trade = find_sized_trade(kDrapeFile, 8, test::scratch_path("none.8.csv"));
  FakeCosts costs{100.0, 0.1, 0.14, {}};
  FakeSound sound{0.75 * kRealtimeStep, {}};
  const RealtimePick pick =
      pick_for_real_time(drape_at_8(), std::ref(costs), trade, std::ref(sound));
  EXPECT_NE(pick.note.find("is not measured; to measure it: neurocloth-cli tradeoff " +
                           std::string(kDrapeFile) +
                           " --size 8 --seconds 1 --samples 4 "
                           "--methods projective --dt 1/120 --projective-iterations"),
            std::string::npos)
      << pick.note;
}

TEST(RealtimePick, SaysWhenNoStepItTriesRunsThrough) {
  const Scene scene = test::asset_scene("table_drape");
  FakeCosts costs{100.0, 0.1, 0.14, {}};
  FakeSound sound{0, {}};  // every step diverges
  const RealtimePick pick = pick_for_real_time(scene, std::ref(costs), {}, std::ref(sound));
  EXPECT_EQ(sound.asked.size(), std::size_t(kMaxStepHalvings) + 1);
  EXPECT_DOUBLE_EQ(pick.picked.dt, kRealtimeStep / 8);
  EXPECT_NE(pick.note.find("At dt 1/60, 1/120, 1/240, 1/480 s it diverged"), std::string::npos)
      << pick.note;
  EXPECT_NE(pick.note.find("no step tried ran through, so expect it to stop"), std::string::npos)
      << pick.note;
}

// The probe itself, on a cloth small enough for a test: the 32 x 32 drape at
// 1/16 s diverges on the table (it has 16 steps in its first second, so only
// the result's check sees it), at 1/64 s it runs through.
TEST(RunsSound, SaysWhetherTheFirstSecondDiverges) {
  Scene scene = test::asset_scene("table_drape");
  scene.solver.integrator = IntegratorKind::projective;
  scene.solver.adaptive = false;
  scene.solver.iterations = 4;
  scene.solver.dt = 1.0 / 16;
  EXPECT_FALSE(runs_sound(scene, kSoundSeconds));
  scene.solver.dt = 1.0 / 64;
  EXPECT_TRUE(runs_sound(scene, kSoundSeconds));
}

// The probe checks after every frame, as the window does, not only the end:
// the drape at 12 x 12 under projective (4 iterations) at 1/20 s gains energy
// with no source from frame to frame as it lands (measured: 1.46 allowances,
// either kernel; above 1 is a strike, two in a row a divergence, rolled back
// to 0.25 s), then loses it on the table, so the same run checked only at its
// end, against its start, passes (measured: 0.387 allowances).
TEST(RunsSound, CatchesADivergenceBetweenFramesThatTheEndAloneWouldMiss) {
  Scene scene = resized_grid(test::asset_scene("table_drape"), 12);
  scene.solver.integrator = IntegratorKind::projective;
  scene.solver.adaptive = false;
  scene.solver.iterations = 4;
  scene.solver.dt = 1.0 / 20;
  Simulation end_only = scene.make_simulation();
  end_only.advance(kSoundSeconds);
  ASSERT_EQ(end_only.check_result(), RunStatus::ok) << end_only.divergence_reason();
  EXPECT_LT(end_only.largest_energy_growth(), 1.0);
  EXPECT_FALSE(runs_sound(scene, kSoundSeconds));
}

}  // namespace
}  // namespace neurocloth
