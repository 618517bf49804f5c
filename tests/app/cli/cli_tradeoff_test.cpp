// `neurocloth-cli tradeoff` and `simulate --accuracy`, run as a user would: a
// real process, real files, exit codes. Small scenes and short runs, so it is fast.
#include <algorithm>

#include "support/cli_fixture.h"
#include "support/hand_made_trade.h"
#include "tradeoff/trade_csv.h"

namespace neurocloth::cli_test {
namespace {

// A fast tradeoff on the hanging cloth: 0.05 s, two compared times, two settings a method.
// The wall-time budgets are far beyond what it takes, so the levels alone decide
// what it runs, however busy this machine is.
std::vector<std::string> quick_tradeoff(const std::string& scene, const std::string& out) {
  return {"tradeoff",           scene, "--seconds",       "0.05", "--samples", "2", "--levels", "2",
          "--reference-budget", "600", "--method-budget", "600",  "--out",     out};
}

TradeRow row(const std::string& method, double dt, double cost, double error) {
  TradeRow r;
  r.method = method;
  r.parameter = is_adaptive_method(method) ? "safety" : "dt";
  r.dt = dt;
  r.value = is_adaptive_method(method) ? 0.5 : dt;
  r.steps = 100;
  r.position_error_max = error;
  r.position_error_rms = error / 3;
  r.energy_error = error / 10;
  r.wall_per_simulated_second = cost;
  r.force_evaluations = 100;
  return r;
}

// A hand-made trade for `scene`: verlet at 2 ms is the cheapest within 1%, the
// adaptive propagation the cheapest within 20%, rk4 the most accurate (1e-5).
std::string hand_made_trade(const std::string& scene = "hanging") {
  TradeTable t = test::hanging_trade(scene);
  t.rows = {row("network", 0.002, 0.02, 0.05), row(kAdaptiveMethod, 0.004, 0.01, 0.15),
            row("verlet", 0.002, 0.04, 0.008), row("rk4", 0.002, 0.1, 1e-5)};
  return trade_csv(t);
}

TEST_F(Cli, TradeoffWritesTheTableTheChartAndTheSummary) {
  const std::string report = (out_dir() / "hanging").string();
  const Outcome r = run(quick_tradeoff(scene_asset("hanging"), report));
  ASSERT_EQ(r.code, kOk) << r.out << r.err;
  std::vector<std::string> files = files_in_out_dir();
  std::sort(files.begin(), files.end());
  EXPECT_EQ(files, (std::vector<std::string>{"hanging.csv", "hanging.md", "hanging.png"}));
  EXPECT_NE(r.out.find("reference: rk4"), std::string::npos) << r.out;

  const TradeTable t = read_trade_csv(report + ".csv");
  EXPECT_EQ(t.scene, "hanging");
  EXPECT_EQ(t.seconds, 0.05);
  EXPECT_EQ(t.samples, 2);
  EXPECT_GT(t.reference.runs, 1);
  for (const char* m :
       {"network", "explicit_euler", "verlet", "rk4", "implicit_euler", "projective", "adaptive"})
    EXPECT_TRUE(std::any_of(t.rows.begin(), t.rows.end(), [&](const TradeRow& row) {
      return row.method == m;
    })) << m;
  // Projective at every iterations count of the default grid, at each step tried.
  std::vector<int> iterations;
  for (const TradeRow& row : t.rows)
    if (row.method == "projective") iterations.push_back(row.iterations);
  EXPECT_EQ(iterations, (std::vector<int>{1, 2, 4, 10, 30, 1, 2, 4, 10, 30}));

  const std::string png = read_text(report + ".png");
  ASSERT_GT(png.size(), 8u);
  EXPECT_EQ(png.substr(1, 3), "PNG");

  const std::string md = read_text(report + ".md");
  for (const char* budget : {"| 10% |", "| 1% |", "| 0.1% |", "| 0.01% |"})
    EXPECT_NE(md.find(budget), std::string::npos) << budget << " not in:\n" << md;
  EXPECT_NE(md.find("![error against cost](hanging.png)"), std::string::npos) << md;
}

// The window's settings exactly, on the cloth resized: projective at 1/60 s and
// the counts asked, no halving, and the grid recorded in the file.
TEST_F(Cli, TradeoffAtASizeRunsTheStepsAskedAndRecordsTheGrid) {
  const std::string report = (out_dir() / "drape").string();
  const Outcome r =
      run({"tradeoff", scene_asset("table_drape"), "--size", "6", "--seconds", "0.25", "--samples",
           "1", "--methods", "projective", "--dt", "1/60", "--projective-iterations", "1,3",
           "--reference-budget", "600", "--out", report});
  ASSERT_EQ(r.code, kOk) << r.out << r.err;
  EXPECT_NE(r.out.find("table_drape at 6 x 6"), std::string::npos) << r.out;
  const TradeTable t = read_sized_trade(report + ".csv", 6);
  EXPECT_EQ(t.grid_rows, 6);
  std::vector<int> iterations;
  for (const TradeRow& row : t.rows)
    if (row.method == "projective") {
      EXPECT_EQ(row.dt, 1.0 / 60) << "exactly the window's step";
      EXPECT_EQ(row.steps, 15);
      iterations.push_back(row.iterations);
    }
  EXPECT_EQ(iterations, (std::vector<int>{1, 3}));
}

// The adaptive propagation with the springs' damping taken implicitly is a
// line of its own when named (never by default): safety halved as the
// adaptive line's, at a cap its springs alone set, so fewer steps. (What is
// checked does not read the reference: its budget is the least there is.)
TEST_F(Cli, TradeoffSweepsTheImplicitDampingLineWhenNamed) {
  const std::string report = (out_dir() / "drape").string();
  const Outcome r =
      run({"tradeoff", scene_asset("table_drape"), "--size", "8", "--seconds", "0.3", "--samples",
           "1", "--methods", "adaptive,adaptive_implicit", "--levels", "2", "--reference-budget",
           "0.001", "--method-budget", "600", "--out", report});
  ASSERT_EQ(r.code, kOk) << r.out << r.err;
  const TradeTable t = read_sized_trade(report + ".csv", 8);
  std::vector<const TradeRow*> plain, implicit;
  for (const TradeRow& row : t.rows) {
    if (row.method == kAdaptiveMethod) plain.push_back(&row);
    if (row.method == kAdaptiveImplicitMethod) implicit.push_back(&row);
  }
  ASSERT_EQ(plain.size(), 2u);
  ASSERT_EQ(implicit.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(implicit[i]->parameter, "safety");
    EXPECT_EQ(implicit[i]->value, plain[i]->value);
    EXPECT_EQ(implicit[i]->status, "ok");
    EXPECT_LT(implicit[i]->steps, plain[i]->steps);
  }
}

// A picked implicit-damping row runs with its damping, and says so.
TEST_F(Cli, AccuracyPicksAnImplicitDampingRowWithItsDamping) {
  TradeTable t = read_trade_csv(write("base.csv", hand_made_trade()));
  t.rows.push_back(row(kAdaptiveImplicitMethod, 0.004, 0.005, 0.15));
  const std::string trade = write("trade.csv", trade_csv(t));
  const Outcome r = run({"simulate", scene_asset("hanging"), "--seconds", "0.01", "--accuracy",
                         "0.2", "--trade", trade, "--out", result_path()});
  ASSERT_EQ(r.code, kOk) << r.err;
  EXPECT_NE(r.out.find("picked adaptive_implicit, safety 0.5"), std::string::npos) << r.out;
  const json doc = read_result();
  EXPECT_EQ(doc.at("integrator"), "network");
  EXPECT_TRUE(doc.at("adaptive").get<bool>());
  EXPECT_EQ(doc.at("damping"), "implicit");
  EXPECT_EQ(doc.at("accuracy").at("method"), "adaptive_implicit");
}

TEST_F(Cli, AccuracyPicksTheCheapestSettingFromAGivenTrade) {
  const std::string trade = write("trade.csv", hand_made_trade());
  Outcome r = run({"simulate", scene_asset("hanging"), "--seconds", "0.01", "--accuracy", "0.01",
                   "--trade", trade, "--out", result_path()});
  ASSERT_EQ(r.code, kOk) << r.err;
  EXPECT_NE(r.out.find("accuracy 0.01: picked verlet, dt 0.002 s from " + trade), std::string::npos)
      << r.out;
  json doc = read_result();
  EXPECT_EQ(doc.at("integrator"), "verlet");
  EXPECT_EQ(doc.at("dt").get<double>(), 0.002);
  EXPECT_FALSE(doc.at("adaptive").get<bool>());
  EXPECT_EQ(doc.at("steps").get<long>(), 5);
  const json& a = doc.at("accuracy");
  EXPECT_EQ(a.at("requested").get<double>(), 0.01);
  EXPECT_EQ(a.at("trade"), trade);
  EXPECT_EQ(a.at("method"), "verlet");
  EXPECT_EQ(a.at("measured_position_error_max").get<double>(), 0.008);
  EXPECT_EQ(a.at("measured_wall_per_simulated_second").get<double>(), 0.04);

  // A looser accuracy: the paper's adaptive propagation is cheaper and good enough.
  r = run({"simulate", scene_asset("hanging"), "--seconds", "0.01", "--accuracy", "0.2", "--trade",
           trade, "--out", result_path()});
  ASSERT_EQ(r.code, kOk) << r.err;
  doc = read_result();
  EXPECT_EQ(doc.at("integrator"), "network");
  EXPECT_TRUE(doc.at("adaptive").get<bool>());
  EXPECT_EQ(doc.at("dt").get<double>(), 0.004);
  EXPECT_EQ(doc.at("accuracy").at("parameter"), "safety");
  EXPECT_EQ(doc.at("accuracy").at("value").get<double>(), 0.5);
}

// Projective's row carries its iterations per step into the run and RESULT.json.
TEST_F(Cli, AccuracyPicksAProjectiveRowWithItsIterations) {
  TradeTable t = read_trade_csv(write("base.csv", hand_made_trade()));
  TradeRow projective = row("projective", 0.015625, 0.005, 0.03);
  projective.iterations = 4;
  t.rows.push_back(projective);
  const std::string trade = write("trade.csv", trade_csv(t));
  const Outcome r = run({"simulate", scene_asset("hanging"), "--seconds", "0.03125", "--accuracy",
                         "0.05", "--trade", trade, "--out", result_path()});
  ASSERT_EQ(r.code, kOk) << r.err;
  EXPECT_NE(r.out.find("picked projective 4 it., dt 0.01562 s"), std::string::npos) << r.out;
  const json doc = read_result();
  EXPECT_EQ(doc.at("integrator"), "projective");
  EXPECT_EQ(doc.at("dt").get<double>(), 0.015625);
  EXPECT_EQ(doc.at("steps").get<long>(), 2);
  EXPECT_EQ(doc.at("accuracy").at("iterations").get<int>(), 4);
}

// The implicit row's CG tolerance reaches the run: it solves as a scene asking
// for that tolerance does, in fewer CG iterations than at the scene's own 1e-10.
TEST_F(Cli, AccuracyPicksAnImplicitRowWithItsLinearTolerance) {
  TradeTable t = read_trade_csv(write("base.csv", hand_made_trade()));
  TradeRow implicit = row("implicit_euler", 0.015625, 0.005, 0.03);
  implicit.linear_tolerance = 1e-2;
  t.rows.push_back(implicit);
  const std::string trade = write("trade.csv", trade_csv(t));
  const std::vector<std::string> seconds = {"--seconds", "0.25"};
  Outcome r = run({"simulate", scene_asset("hanging"), seconds[0], seconds[1], "--accuracy", "0.05",
                   "--trade", trade, "--out", result_path()});
  ASSERT_EQ(r.code, kOk) << r.err;
  EXPECT_NE(r.out.find("picked implicit_euler tol 0.01, dt 0.01562 s"), std::string::npos) << r.out;
  const json picked = read_result();
  EXPECT_EQ(picked.at("integrator"), "implicit_euler");
  EXPECT_EQ(picked.at("accuracy").at("linear_tolerance").get<double>(), 1e-2);

  r = run({"simulate", scene_asset("hanging"), seconds[0], seconds[1], "--integrator",
           "implicit_euler", "--dt", "0.015625", "--out", result_path()});
  ASSERT_EQ(r.code, kOk) << r.err;
  const json own = read_result();
  const std::string loose_scene =
      write("loose.json", with(read_text(scene_asset("hanging")), "\"adaptive\": false",
                               "\"adaptive\": false, \"linear_tolerance\": 0.01"));
  r = run({"simulate", loose_scene, seconds[0], seconds[1], "--integrator", "implicit_euler",
           "--dt", "0.015625", "--out", result_path()});
  ASSERT_EQ(r.code, kOk) << r.err;
  const json loose = read_result();
  EXPECT_EQ(picked.at("cg_iterations"), loose.at("cg_iterations"));
  EXPECT_EQ(picked.at("positions"), loose.at("positions"));
  EXPECT_LT(picked.at("cg_iterations").get<long>(), own.at("cg_iterations").get<long>());
}

TEST_F(Cli, AccuracyUsesTheCommittedTradeOfAShippedScene) {
  const std::string committed = assets_directory() + "/tradeoff/hanging.csv";
  ASSERT_TRUE(fs::exists(committed)) << committed;
  const Outcome r = run({"simulate", scene_asset("hanging"), "--seconds", "0.01", "--accuracy",
                         "0.01", "--out", result_path()});
  ASSERT_EQ(r.code, kOk) << r.err;
  EXPECT_NE(r.out.find("from " + committed), std::string::npos) << r.out;
  const json doc = read_result();
  EXPECT_EQ(doc.at("accuracy").at("trade"), committed);
  EXPECT_LE(doc.at("accuracy").at("measured_position_error_max").get<double>(), 0.01);
}

TEST_F(Cli, AccuracyMeasuresATradeWhenNoneIsCommittedAndSaysSo) {
  // A scene under a name no committed trade has.
  const std::string scene = write("my_chain.json", read_text(scene_asset("chain")));
  const Outcome r =
      run({"simulate", scene, "--seconds", "0.05", "--accuracy", "0.1", "--out", result_path()});
  ASSERT_EQ(r.code, kOk) << r.err;
  EXPECT_NE(r.out.find("no measured trade"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("measuring one over 0.05 s first"), std::string::npos) << r.out;
  const json doc = read_result();
  EXPECT_EQ(doc.at("accuracy").at("trade"), "measured now");
  EXPECT_LE(doc.at("accuracy").at("measured_position_error_max").get<double>(), 0.1);
  EXPECT_EQ(files_in_out_dir(), std::vector<std::string>{"result.json"});
}

TEST_F(Cli, TradeoffBadInputNamesWhatIsWrong) {
  const std::string report = (out_dir() / "report").string();
  expect_input_error(quick_tradeoff(dir_.string() + "/missing.json", report), {"missing.json"});
  // A trade runs the scene dozens of times: 1e300 s would never end.
  for (const char* seconds : {"0", "-1", "inf", "1e300"}) {
    std::vector<std::string> args = quick_tradeoff(scene_asset("hanging"), report);
    args[3] = seconds;
    expect_input_error(args, {"--seconds", "must be in (0, 3600]"});
  }
  for (const auto& [option, value] : {std::pair{"--samples", "2147483647"}, {"--levels", "1000"}}) {
    std::vector<std::string> args = quick_tradeoff(scene_asset("hanging"), report);
    *(std::find(args.begin(), args.end(), option) + 1) = value;
    expect_input_error(args, {option, "must be in [1, "});
  }
  std::vector<std::string> args = quick_tradeoff(scene_asset("hanging"), report);
  args.insert(args.end(), {"--methods", "network,leapfrog"});
  expect_input_error(args, {"--methods", "leapfrog"});
  for (const char* option : {"--projective-iterations", "--vbd-iterations"}) {
    args = quick_tradeoff(scene_asset("hanging"), report);
    args.insert(args.end(), {option, "4,0"});
    expect_input_error(args, {option, "must be in [1, 1000]"});
    args = quick_tradeoff(scene_asset("hanging"), report);
    args.insert(args.end(), {option, "1001"});
    expect_input_error(args, {option, "must be in [1, 1000]"});
  }
  for (const char* tolerances : {"1e-6,0", "1e-6,0.5", "1e-15"}) {
    args = quick_tradeoff(scene_asset("hanging"), report);
    args.insert(args.end(), {"--implicit-tolerances", tolerances});
    expect_input_error(args, {"--implicit-tolerances", "must be in [1e-14, 0.01]"});
  }
  for (const char* workers : {"0", "-1", "65"}) {
    args = quick_tradeoff(scene_asset("hanging"), report);
    args.insert(args.end(), {"--workers", workers});
    expect_input_error(args, {"--workers", "must be in [1, 64]"});
  }
  // --size: a grid a side, on a grid scene; --dt: steps that land on every sample time.
  for (const char* size : {"1", "1025"}) {
    args = quick_tradeoff(scene_asset("hanging"), report);
    args.insert(args.end(), {"--size", size});
    expect_input_error(args, {"--size", "must be in [2, 1024]"});
  }
  args = quick_tradeoff(scene_asset("mesh_square"), report);
  args.insert(args.end(), {"--size", "8"});
  expect_input_error(args, {"--size", "not a grid scene"});
  for (const auto& [dt, why] : {std::pair{"1/60x", "not a step in s"},
                                {"1/0", "not a step in s"},
                                {"1/7", "does not divide the sample interval 0.025 s"},
                                {"1e-9", "must be in [1e-06, "}}) {
    args = quick_tradeoff(scene_asset("hanging"), report);
    args.insert(args.end(), {"--dt", dt});
    expect_input_error(args, {"--dt", why});
  }
  // A folder that does not exist: refused before measuring, naming the file.
  expect_input_error(quick_tradeoff(scene_asset("hanging"), dir_.string() + "/nowhere/report"),
                     {"--out", "nowhere/report.csv"}, 10);
  // A scene with an error in it names its file and line.
  const std::string bad = write("bad.json", with(read_text(scene_asset("hanging")),
                                                 "\"node_mass\": 0.01", "\"node_mass\": -0.01"));
  expect_input_error(quick_tradeoff(bad, report), {"bad.json:", "material.node_mass"});
}

TEST_F(Cli, AccuracyBadInputNamesWhatIsWrong) {
  const std::string hanging = scene_asset("hanging");
  const std::string trade = write("trade.csv", hand_made_trade());
  auto simulate = [&](const std::vector<std::string>& more) {
    std::vector<std::string> args = {"simulate", hanging, "--seconds",
                                     "0.01",     "--out", result_path()};
    args.insert(args.end(), more.begin(), more.end());
    return args;
  };
  for (const char* bad : {"0", "-0.01", "nan"})
    expect_input_error(simulate({"--accuracy", bad, "--trade", trade}),
                       {"--accuracy", "must be a finite number > 0"});
  expect_input_error(simulate({"--accuracy", "0.01", "--trade", dir_.string() + "/none.csv"}),
                     {"none.csv", "cannot open"});
  const std::string broken_text = with(hand_made_trade(), "verlet,dt", "verlet,safety");
  const std::string broken = write("broken.csv", broken_text);
  const auto before = broken_text.begin() + broken_text.find("verlet,safety");
  const int line = static_cast<int>(std::count(broken_text.begin(), before, '\n')) + 1;
  expect_input_error(simulate({"--accuracy", "0.01", "--trade", broken}),
                     {"broken.csv:" + std::to_string(line) + ":8: field 'parameter'"});
  expect_input_error(simulate({"--accuracy", "1e-9", "--trade", trade}),
                     {"trade.csv", "--accuracy", "best achievable is rk4, dt 0.002 s"});
  const std::string flag_trade = write("flag.csv", hand_made_trade("flag"));
  expect_input_error(simulate({"--accuracy", "0.01", "--trade", flag_trade}),
                     {"flag.csv", "# scene", "measured for scene 'flag', not for 'hanging'"});
}

TEST_F(Cli, AccuracyExcludesChoosingTheStepByHand) {
  const std::string trade = write("trade.csv", hand_made_trade());
  for (const std::vector<std::string>& by_hand : {std::vector<std::string>{"--dt", "0.001"},
                                                  {"--integrator", "rk4"},
                                                  {"--adaptive"},
                                                  {"--fixed-step"}}) {
    std::vector<std::string> args = {"simulate",   scene_asset("hanging"),
                                     "--seconds",  "0.01",
                                     "--accuracy", "0.01",
                                     "--trade",    trade,
                                     "--out",      result_path()};
    args.insert(args.end(), by_hand.begin(), by_hand.end());
    const Outcome r = run(args);
    EXPECT_EQ(r.code, kUsage) << by_hand[0] << ": " << r.err;
    EXPECT_NE(r.err.find("excludes"), std::string::npos) << r.err;
    EXPECT_TRUE(files_in_out_dir().empty());
  }
  const Outcome r = run({"simulate", scene_asset("hanging"), "--seconds", "0.01", "--trade", trade,
                         "--out", result_path()});
  EXPECT_EQ(r.code, kUsage) << "--trade without --accuracy: " << r.err;
}

}  // namespace
}  // namespace neurocloth::cli_test
