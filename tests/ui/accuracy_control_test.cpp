// The Solver panel's accuracy slider, without a window: the scene's committed
// trade is found, a request becomes the command the measured pick stands for,
// and a request the trade cannot vouch for is refused naming the file.
#include "ui/accuracy_control.h"

#include <gtest/gtest.h>

#include <cmath>
#include <variant>
#include <vector>

#include "core/io/asset_paths.h"
#include "core/io/input_error.h"
#include "core/scene/scene.h"
#include "tradeoff/accuracy_choice.h"
#include "ui/ui_requests.h"

namespace neurocloth {
namespace {

std::string hanging() {
  return assets_directory() + "/scenes/hanging.json";
}

TEST(AccuracyControl, TheCommittedTradeIsFoundWithItsRange) {
  const AccuracyTrade t = load_accuracy_trade(hanging());
  ASSERT_TRUE(t.table.has_value()) << t.note;
  EXPECT_GT(t.finest, 0);
  EXPECT_LT(t.finest, 0.01) << "the hanging trade reaches below 1%";
  EXPECT_EQ(t.loosest, 0.1);
}

TEST(AccuracyControl, ARequestBecomesThePickedSettingAsOneCommand) {
  const Scene scene = load_scene(hanging());
  const AccuracyTrade t = load_accuracy_trade(hanging());
  ASSERT_TRUE(t.table.has_value()) << t.note;
  for (double e : {0.1, 0.01, 0.001}) {
    const AccuracyPick p = pick_for_accuracy(t, e, scene.solver);
    const AccuracyChoice c = choose_for_accuracy(*t.table, t.path, e, scene.solver);
    EXPECT_LE(c.row.position_error_max, e);
    EXPECT_EQ(p.command.integrator, c.settings.integrator) << e;
    EXPECT_EQ(p.command.dt, c.settings.dt) << e;
    EXPECT_EQ(p.command.adaptive, c.settings.adaptive) << e;
    EXPECT_EQ(p.command.safety, c.settings.adaptive_settings.safety) << e;
    EXPECT_EQ(p.command.iterations, c.settings.iterations) << e;
    EXPECT_EQ(p.command.linear_tolerance, c.settings.linear_tolerance) << e;
    EXPECT_NE(p.description.find(describe_setting(c.row)), std::string::npos) << p.description;
  }
  // Tighter costs more: the 0.1% pick takes a smaller step than the 10% one.
  EXPECT_LT(pick_for_accuracy(t, 0.001, scene.solver).command.dt,
            pick_for_accuracy(t, 0.1, scene.solver).command.dt);
}

// A projective pick sends its iterations per step with the rest; a projective
// row from a file without the column leaves the scene's own.
TEST(AccuracyControl, AProjectivePickSendsItsIterations) {
  SolverSettings scene_solver;
  scene_solver.iterations = 7;
  AccuracyTrade t;
  t.path = "projective.csv";
  t.table = TradeTable{};
  t.table->scene = "hand";
  t.table->reference.change = 1e-6;
  TradeRow row;
  row.method = "projective";
  row.parameter = "dt";
  row.value = row.dt = 1.0 / 64;
  row.iterations = 4;
  row.position_error_max = 0.02;
  row.wall_per_simulated_second = 0.1;
  t.table->rows = {row};
  const AccuracyPick p = pick_for_accuracy(t, 0.05, scene_solver);
  EXPECT_EQ(p.command.integrator, IntegratorKind::projective);
  EXPECT_EQ(p.command.dt, 1.0 / 64);
  EXPECT_FALSE(p.command.adaptive);
  EXPECT_EQ(p.command.iterations, 4);
  EXPECT_NE(p.description.find("projective 4 it., dt 0.01562 s"), std::string::npos)
      << p.description;
  t.table->rows[0].iterations = 0;
  EXPECT_EQ(pick_for_accuracy(t, 0.05, scene_solver).command.iterations, 7);
}

// An implicit pick sends its CG tolerance with the rest; an implicit row from a
// file without the column leaves the scene's own.
TEST(AccuracyControl, AnImplicitPickSendsItsLinearTolerance) {
  SolverSettings scene_solver;
  scene_solver.linear_tolerance = 1e-8;
  AccuracyTrade t;
  t.path = "implicit.csv";
  t.table = TradeTable{};
  t.table->scene = "hand";
  t.table->reference.change = 1e-6;
  TradeRow row;
  row.method = "implicit_euler";
  row.parameter = "dt";
  row.value = row.dt = 1.0 / 256;
  row.linear_tolerance = 1e-6;
  row.position_error_max = 0.02;
  row.wall_per_simulated_second = 0.1;
  t.table->rows = {row};
  const AccuracyPick p = pick_for_accuracy(t, 0.05, scene_solver);
  EXPECT_EQ(p.command.integrator, IntegratorKind::implicit_euler);
  EXPECT_EQ(p.command.linear_tolerance, 1e-6);
  EXPECT_NE(p.description.find("implicit_euler tol 1e-6, dt 0.003906 s"), std::string::npos)
      << p.description;
  t.table->rows[0].linear_tolerance = 0;
  EXPECT_EQ(pick_for_accuracy(t, 0.05, scene_solver).command.linear_tolerance, 1e-8);
}

TEST(AccuracyControl, BeyondWhatTheTradeVouchesForIsRefusedNamingTheFile) {
  const Scene scene = load_scene(hanging());
  const AccuracyTrade t = load_accuracy_trade(hanging());
  ASSERT_TRUE(t.table.has_value()) << t.note;
  try {
    pick_for_accuracy(t, t.finest / 100, scene.solver);
    FAIL() << "an accuracy finer than the trade's was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("hanging.csv"), std::string::npos) << e.what();
  }
}

TEST(AccuracyControl, ASceneWithoutATradeSaysHowToMakeOne) {
  const AccuracyTrade t = load_accuracy_trade("/nowhere/no_such_scene.json");
  EXPECT_FALSE(t.table.has_value());
  EXPECT_NE(t.note.find("tradeoff"), std::string::npos) << t.note;
}

// A resized cloth is another cloth: the scene's own trade (hanging.csv, at
// 20 x 20) is not offered for it, only one measured at its size.
TEST(AccuracyControl, AResizedClothGetsOnlyATradeMeasuredAtItsSize) {
  const AccuracyTrade own = load_accuracy_trade(hanging());
  ASSERT_TRUE(own.table.has_value()) << own.note;
  const AccuracyTrade t = load_accuracy_trade(hanging(), 128);
  EXPECT_FALSE(t.table.has_value());
  EXPECT_NE(t.path.find("hanging.128.csv"), std::string::npos) << t.path;
  EXPECT_NE(t.note.find("no trade measured at 128 x 128"), std::string::npos) << t.note;
  EXPECT_NE(t.note.find("--size 128"), std::string::npos) << t.note;
  const SceneInfo resized(resized_grid(load_scene(hanging()), 24));
  EXPECT_FALSE(resized.trade().table.has_value()) << resized.trade().path;
  EXPECT_NE(resized.trade().path.find("hanging.24.csv"), std::string::npos);
}

// The slider's request, as the panel and a script's "set accuracy" make it:
// one SetSolver with the pick, mirrored in the panel's values.
TEST(AccuracyControl, ARequestPostsThePickAsOneSetSolverAndMirrorsIt) {
  const SceneInfo scene(load_scene(hanging()));
  UiValues values;
  std::vector<SimCommand> posted;
  const CommandSink sink = [&](SimCommand c) { posted.push_back(std::move(c)); };
  EXPECT_EQ(request_accuracy(scene, values, sink, 0.01), "");
  ASSERT_EQ(posted.size(), 1u);
  const SetSolver& sent = std::get<SetSolver>(posted[0]);
  const AccuracyPick pick = pick_for_accuracy(scene.trade(), 0.01, scene.solver());
  EXPECT_EQ(sent.integrator, pick.command.integrator);
  EXPECT_EQ(sent.dt, pick.command.dt);
  EXPECT_EQ(sent.adaptive, pick.command.adaptive);
  EXPECT_EQ(sent.safety, pick.command.safety);
  EXPECT_EQ(kAllIntegrators[values.integrator], sent.integrator);
  EXPECT_EQ(values.dt, sent.dt);
  EXPECT_EQ(values.adaptive, sent.adaptive);
  EXPECT_FLOAT_EQ(values.accuracy, 0.01f);
  EXPECT_EQ(values.accuracy_pick, pick.description);
}

TEST(AccuracyControl, ARequestTheTradeCannotMeetIsRefusedAndNothingPosted) {
  const SceneInfo scene(load_scene(hanging()));
  UiValues values;
  const UiValues before = values;
  std::vector<SimCommand> posted;
  const CommandSink sink = [&](SimCommand c) { posted.push_back(std::move(c)); };
  std::string refusal = request_accuracy(scene, values, sink, scene.trade().finest / 100);
  EXPECT_NE(refusal.find("hanging.csv"), std::string::npos) << refusal;
  refusal = request_accuracy(scene, values, sink, std::nan(""));
  EXPECT_NE(refusal.find("accuracy = nan refused"), std::string::npos) << refusal;
  EXPECT_NE(request_accuracy(scene, values, sink, -0.1), "");

  const SceneInfo untraded(load_scene(assets_directory() + "/scenes/chain.json"));
  refusal = request_accuracy(untraded, values, sink, 0.01);
  EXPECT_NE(refusal.find("tradeoff"), std::string::npos) << refusal;
  EXPECT_TRUE(posted.empty());
  EXPECT_EQ(values.dt, before.dt);
  EXPECT_EQ(values.accuracy, before.accuracy);
}

}  // namespace
}  // namespace neurocloth
