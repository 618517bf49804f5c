// `neurocloth-cli compare` and the ensemble's options of `tradeoff` and
// `simulate --accuracy`, run as a user would: real processes, real files.
#include "support/cli_fixture.h"
#include "support/hand_made_trade.h"
#include "tradeoff/trade_csv.h"

namespace neurocloth::cli_test {
namespace {

// Two short drapes of the table scene's cloth at 8 x 8, the scene's own step
// and projective at 1/60 s: they land apart.
TEST_F(Cli, CompareGivesEveryMetricAsOneJsonObject) {
  const std::string a = (dir_ / "a.json").string(), b = (dir_ / "b.json").string();
  ASSERT_EQ(
      run({"simulate", scene_asset("table_drape"), "--size", "8", "--seconds", "0.5", "--out", a})
          .code,
      kOk);
  ASSERT_EQ(run({"simulate", scene_asset("table_drape"), "--size", "8", "--seconds", "0.5",
                 "--integrator", "projective", "--dt", "0.0166666666666667", "--out", b})
                .code,
            kOk);
  const Outcome r = run({"compare", a, b});
  ASSERT_EQ(r.code, kOk) << r.err;
  const json v = json::parse(r.out);
  EXPECT_EQ(v.at("nodes").get<int>(), 64) << "the scene resized to the results' 8 x 8";
  EXPECT_NEAR(v.at("cloth_size_m").get<double>(), 1.2 * std::sqrt(2.0), 0.01);
  for (const char* key :
       {"node_max", "node_rms", "surface_mean", "surface_max", "drape_coefficient_a",
        "drape_coefficient_b", "folds_a", "folds_b", "strain_max_a", "strain_mean_b", "energy"})
    EXPECT_TRUE(v.contains(key)) << key << " not in " << r.out;
  // A node's distance to the other surface is at most its distance to its own
  // node there: the surfaces are never further apart than the nodes.
  EXPECT_GT(v.at("node_max").get<double>(), 0);
  EXPECT_LE(v.at("surface_max").get<double>(), v.at("node_max").get<double>());
  EXPECT_LE(v.at("surface_mean").get<double>(), v.at("node_rms").get<double>());
  EXPECT_GT(v.at("drape_coefficient_a").get<double>(), 0);
  EXPECT_LT(v.at("drape_coefficient_a").get<double>(), 1) << "it hangs over the edge";
  const json same = json::parse(run({"compare", a, a}).out);
  for (const char* key : {"node_max", "node_rms", "surface_mean", "surface_max", "energy"})
    EXPECT_EQ(same.at(key).get<double>(), 0) << key;
  EXPECT_EQ(same.at("drape_coefficient_a"), same.at("drape_coefficient_b"));
}

TEST_F(Cli, CompareRefusesResultsOfDifferentClothsAndASceneWithoutASupport) {
  const std::string a = (dir_ / "a.json").string(), b = (dir_ / "b.json").string();
  ASSERT_EQ(
      run({"simulate", scene_asset("table_drape"), "--size", "8", "--seconds", "0", "--out", a})
          .code,
      kOk);
  ASSERT_EQ(
      run({"simulate", scene_asset("table_drape"), "--size", "6", "--seconds", "0", "--out", b})
          .code,
      kOk);
  expect_input_error({"compare", a, b}, {a, b, "different node counts", "64", "36"});
  // The support is the point of --scene: a scene without one is refused.
  const std::string bare = write(
      "bare.json",
      with(
          read_text(scene_asset("table_drape")),
          R"({ "type": "box", "center": [0, 0.375, 0], "size": [0.8, 0.75, 0.8], "thickness": 0.005 })",
          R"({ "type": "air_drag", "rate": 0.1 })"));
  expect_input_error({"compare", a, a, "--scene", bare}, {bare, "modules", "drape"});
  expect_input_error({"compare", a, (dir_ / "missing.json").string()}, {"missing.json"});
  const std::string broken = write("broken.json", R"({"positions": [[0, 0, "x"]]})");
  expect_input_error({"compare", broken, broken}, {"broken.json", "positions[0]"});
}

TEST_F(Cli, TradeoffRefusesAnEnsembleOrMetricOutOfRangeWritingNothing) {
  const std::string report = (out_dir() / "r").string();
  const std::vector<std::string> base = {
      "tradeoff", scene_asset("hanging"), "--seconds", "0.05", "--samples", "1", "--out", report};
  auto with_option = [&](const std::string& option, const std::string& value) {
    std::vector<std::string> args = base;
    args.insert(args.end(), {option, value});
    return args;
  };
  expect_input_error(with_option("--metric", "surface"), {"--metric", "surface", "surface_mean"});
  expect_input_error(with_option("--ensemble", "1"), {"--ensemble", "[2, 64]"});
  expect_input_error(with_option("--ensemble", "65"), {"--ensemble", "[2, 64]"});
  expect_input_error(with_option("--perturbation", "1m"), {"--perturbation", "[1e-09, 0.05]"});
  expect_input_error(with_option("--perturbation", "0"), {"--perturbation"});
  expect_input_error(with_option("--perturbation", "a lot"), {"--perturbation", "not a length"});
}

// A trade with an ensemble: a hand-made hanging trade whose floor in every
// metric is 2%; verlet is at 1.5%, rk4 at 0.1%, both within it.
std::string trade_with_floor() {
  TradeTable t = test::hanging_trade();
  EnsembleFloor f;
  f.members = 4;
  f.shift = 0.001;
  f.member_dt = 1e-4;
  f.median.fill(0.01);
  f.p90.fill(0.02);
  t.floor = f;
  auto row = [](const char* method, double dt, double cost, double surface) {
    TradeRow r;
    r.method = method;
    r.parameter = "dt";
    r.value = r.dt = dt;
    r.steps = 10;
    r.position_error_max = r.position_error_rms = r.energy_error = 2 * surface;
    r.ensemble.fill(surface);
    r.wall_per_simulated_second = cost;
    return r;
  };
  t.rows = {row("network", 0.002, 0.02, 0.05), row("verlet", 0.002, 0.04, 0.015),
            row("rk4", 0.001, 0.1, 0.001)};
  return trade_csv(t);
}

TEST_F(Cli, AccuracyBelowTheScenesSpreadIsPickedAgainstTheSpreadAndSaysSo) {
  const std::string trade = write("trade.csv", trade_with_floor());
  const Outcome r = run({"simulate", scene_asset("hanging"), "--seconds", "0.01", "--accuracy",
                         "0.001", "--trade", trade, "--out", result_path()});
  ASSERT_EQ(r.code, kOk) << r.err;
  EXPECT_NE(r.out.find("asked 0.1%: this scene's own spread is 2% (energy, 4 references "
                       "shifted 1 mm); picked against 2%"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("picked verlet, dt 0.002 s"), std::string::npos) << r.out;
  const json a = read_result().at("accuracy");
  EXPECT_EQ(a.at("metric"), "energy");
  EXPECT_EQ(a.at("floor").get<double>(), 0.02);
  EXPECT_EQ(a.at("picked_against").get<double>(), 0.02);
  EXPECT_TRUE(a.at("within_floor").get<bool>());
  // Asked in node_max the same floor holds (every metric's is 2% here).
  const Outcome node =
      run({"simulate", scene_asset("hanging"), "--seconds", "0.01", "--accuracy", "0.5", "--metric",
           "node_max", "--trade", trade, "--out", result_path()});
  ASSERT_EQ(node.code, kOk) << node.err;
  EXPECT_NE(node.out.find("picked network"), std::string::npos) << node.out;
  EXPECT_EQ(read_result().at("accuracy").at("metric"), "node_max");
}

TEST_F(Cli, AccuracyRefusesAMetricTheTradeDidNotMeasure) {
  const std::string trade = write("trade.csv", with(trade_with_floor(), "# ensemble: 4\n", ""));
  expect_input_error({"simulate", scene_asset("hanging"), "--seconds", "0.01", "--accuracy", "0.1",
                      "--trade", trade, "--out", result_path()},
                     {"trade.csv", "# ensemble"});
  TradeTable old = read_trade_csv(write("old.csv", trade_with_floor()));
  old.floor.reset();
  for (TradeRow& r : old.rows)
    r.ensemble = unmeasured_metrics();
  const std::string plain = write("plain.csv", trade_csv(old));
  expect_input_error({"simulate", scene_asset("hanging"), "--seconds", "0.01", "--accuracy", "0.1",
                      "--metric", "surface_mean", "--trade", plain, "--out", result_path()},
                     {"plain.csv", "--metric", "no ensemble"});
  expect_input_error({"simulate", scene_asset("hanging"), "--seconds", "0.01", "--accuracy", "0.1",
                      "--metric", "bogus", "--trade", plain, "--out", result_path()},
                     {"--metric", "bogus"});
}

// A measured trade drawn again in another metric, nothing measured.
TEST_F(Cli, TradeoffReplotsATradeInAnotherMetric) {
  const std::string trade = write("trade.csv", trade_with_floor());
  const std::string report = (out_dir() / "again").string();
  const Outcome r = run({"tradeoff", scene_asset("hanging"), "--replot", trade, "--metric",
                         "node_rms", "--out", report});
  ASSERT_EQ(r.code, kOk) << r.err;
  const std::string md = read_text(report + ".md");
  EXPECT_NE(md.find("Budgets in **node_rms**"), std::string::npos) << md;
  EXPECT_NE(md.find("| 1% and below: the floor, 2% | verlet"), std::string::npos) << md;
  EXPECT_EQ(read_text(report + ".png").substr(1, 3), "PNG");
  EXPECT_FALSE(fs::exists(report + ".csv")) << "nothing measured, no table written";
  fs::remove(report + ".md");
  fs::remove(report + ".png");
  expect_input_error({"tradeoff", scene_asset("table_drape"), "--replot", trade, "--out", report},
                     {"trade.csv", "# scene", "hanging"});
}

// A resized cloth picks from a trade measured at its size, never another's.
TEST_F(Cli, AccuracyAtASizeReadsTheTradeOfThatSize) {
  TradeTable t = read_trade_csv(write("t.csv", trade_with_floor()));
  t.scene = "table_drape";
  t.grid_rows = t.grid_cols = 8;
  const std::string trade = write("at8.csv", trade_csv(t));
  expect_input_error({"simulate", scene_asset("table_drape"), "--size", "6", "--seconds", "0.01",
                      "--accuracy", "0.1", "--trade", trade, "--out", result_path()},
                     {"at8.csv", "# grid", "8 x 8", "6 x 6"});
  const Outcome r = run({"simulate", scene_asset("table_drape"), "--size", "8", "--seconds", "0.01",
                         "--accuracy", "0.1", "--trade", trade, "--out", result_path()});
  ASSERT_EQ(r.code, kOk) << r.err;
  EXPECT_EQ(read_result().at("nodes").get<int>(), 64);
}

}  // namespace
}  // namespace neurocloth::cli_test
