// The window's choice of a solver that keeps a resized cloth in real time,
// with the costs given (the probe itself is wall-clock and not tested here).
#include "realtime_pick.h"

#include <gtest/gtest.h>

#include <vector>

#include "test_support.h"

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

}  // namespace
}  // namespace neurocloth
