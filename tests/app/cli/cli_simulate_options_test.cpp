// `simulate`'s options as a user gives them: overrides of the scene's solver
// (integrator, step, size, precision, damping, step bound, safety) and what a run says when its
// step is too large, when it diverges and when its step budget runs out.
#include "support/cli_fixture.h"
#include "support/test_support.h"

namespace neurocloth::cli_test {
namespace {

TEST_F(Cli, OptionsOverrideTheScene) {
  const Outcome r = run({"simulate", scene_asset("hanging"), "--seconds", "0.01", "--integrator",
                         "rk4", "--dt", "0.002", "--out", result_path()});
  ASSERT_EQ(r.code, kOk) << r.err;
  const json doc = read_result();
  EXPECT_EQ(doc.at("integrator"), "rk4");
  EXPECT_EQ(doc.at("dt").get<double>(), 0.002);
  EXPECT_EQ(doc.at("steps").get<long>(), 5);
}

// --size N: the cloth resized as the window's --size does (same width, same
// mass; docs/scenes.md "Resizing a grid"): what bench/peers/run compares with
// Blender's cloth at 32², 64² and 128².
TEST_F(Cli, SizeResizesTheClothAndIsRangeChecked) {
  const Outcome r = run({"simulate", scene_asset("table_drape"), "--seconds", "0", "--size", "6",
                         "--out", result_path()});
  ASSERT_EQ(r.code, kOk) << r.err;
  const json doc = read_result();
  EXPECT_EQ(doc.at("nodes").get<int>(), 36);
  // table_drape's corners: origin (-0.6, 1, -0.6), 31 x 0.0387 m a side.
  const json& x = doc.at("positions");
  EXPECT_DOUBLE_EQ(x[0].at(0).get<double>(), -0.6);
  EXPECT_NEAR(x[35].at(0).get<double>(), -0.6 + 31 * 0.0387, 1e-12);
  EXPECT_NEAR(x[35].at(2).get<double>(), -0.6 + 31 * 0.0387, 1e-12);
  fs::remove(result_path());
  expect_input_error({"simulate", scene_asset("table_drape"), "--seconds", "0", "--size", "1",
                      "--out", result_path()},
                     {"--size", "must be in [2, 1024]"});
}

TEST_F(Cli, PrecisionOverridesTheSceneAndIsRefusedByNameWhereItCannotGo) {
  const Outcome r = run({"simulate", scene_asset("hanging"), "--seconds", "0.01", "--precision",
                         "float", "--out", result_path()});
  ASSERT_EQ(r.code, kOk) << r.err;
  EXPECT_EQ(read_result().at("precision"), "float");
  fs::remove(result_path());
  expect_input_error({"simulate", scene_asset("hanging"), "--seconds", "0.01", "--precision",
                      "half", "--out", result_path()},
                     {"--precision", "half", "double, float"});
  expect_input_error({"simulate", scene_asset("hanging"), "--seconds", "0.01", "--precision",
                      "float", "--integrator", "implicit_euler", "--out", result_path()},
                     {"--precision", "implicit_euler"});
}

TEST_F(Cli, DampingOverridesTheSceneAndIsRefusedByNameWhereItCannotGo) {
  const Outcome r = run({"simulate", scene_asset("hanging"), "--seconds", "0.01", "--damping",
                         "implicit", "--out", result_path()});
  ASSERT_EQ(r.code, kOk) << r.err;
  EXPECT_EQ(read_result().at("damping"), "implicit");
  fs::remove(result_path());
  expect_input_error({"simulate", scene_asset("hanging"), "--seconds", "0.01", "--damping",
                      "viscous", "--out", result_path()},
                     {"--damping", "viscous", "explicit, implicit"});
  expect_input_error({"simulate", scene_asset("hanging"), "--seconds", "0.01", "--damping",
                      "implicit", "--integrator", "rk4", "--out", result_path()},
                     {"--damping", "rk4"});
}

TEST_F(Cli, StepBoundOverridesTheSceneAndAWrongOneIsRefusedByName) {
  const Outcome r = run({"simulate", scene_asset("hanging"), "--seconds", "0.01", "--step-bound",
                         "gershgorin", "--out", result_path()});
  ASSERT_EQ(r.code, kOk) << r.err;
  EXPECT_EQ(read_result().at("step_bound"), "gershgorin");
  fs::remove(result_path());
  expect_input_error({"simulate", scene_asset("hanging"), "--seconds", "0.01", "--step-bound",
                      "tight", "--out", result_path()},
                     {"--step-bound", "tight", "spectral, gershgorin"});
}

// --safety: the adaptive cap's fraction of the stability bound. The drape's
// steps sit at the cap, so twice the fraction takes at most about half the
// steps (measured: 300 against 599 over 0.1 s); out of (0, 1] it is refused.
TEST_F(Cli, SafetyOverridesTheSceneAndIsRangeChecked) {
  const auto steps = [&](std::vector<std::string> extra) {
    std::vector<std::string> args = {
        "simulate", scene_asset("table_drape"), "--seconds", "0.1", "--out", result_path()};
    args.insert(args.end(), extra.begin(), extra.end());
    const Outcome r = run(args);
    EXPECT_EQ(r.code, kOk) << r.err;
    const json doc = read_result();
    fs::remove(result_path());
    return std::make_pair(doc.at("safety").get<double>(), doc.at("steps").get<long>());
  };
  const auto [default_safety, default_steps] = steps({});
  const auto [safety, fewer] = steps({"--safety", "1"});
  EXPECT_EQ(default_safety, 0.5);
  EXPECT_EQ(safety, 1.0);
  EXPECT_LE(2 * fewer, default_steps + 2);
  EXPECT_GE(2 * fewer, default_steps - 2);
  for (const char* bad : {"0", "1.5", "nan", "-1"})
    expect_input_error({"simulate", scene_asset("table_drape"), "--seconds", "0.01", "--safety",
                        bad, "--out", result_path()},
                       {"--safety", "(0, 1]"});
}

TEST_F(Cli, AdaptiveRunIsMarkedAdaptive) {
  const Outcome r = run({"simulate", scene_asset("hanging"), "--seconds", "0.02", "--adaptive",
                         "--out", result_path()});
  ASSERT_EQ(r.code, kOk) << r.err;
  const json doc = read_result();
  EXPECT_EQ(doc.at("adaptive"), true);
  EXPECT_NEAR(doc.at("time").get<double>(), 0.02, 1e-12);
}

TEST_F(Cli, DivergedRunExitsThreeWithTheLastGoodState) {
  // Explicit Euler at 20 ms is far beyond its stability bound on this cloth.
  const Outcome r = run({"simulate", scene_asset("hanging"), "--integrator", "explicit_euler",
                         "--dt", "0.02", "--seconds", "2", "--out", result_path()});
  ASSERT_EQ(r.code, kDiverged) << r.err;
  EXPECT_EQ(files_in_out_dir(), std::vector<std::string>{"result.json"});
  const json doc = read_result();
  EXPECT_EQ(doc.at("status"), "diverged");
  EXPECT_FALSE(doc.at("reason").get<std::string>().empty());
  EXPECT_LT(doc.at("time").get<double>(), 2.0);
  EXPECT_EQ(doc.at("positions").size(), 400u);
  EXPECT_EQ(doc.at("velocities").size(), 400u);
  expect_all_finite(doc, "result");
}

// A fixed step above the stable step is said before the run; the same step
// within it is not. (20 ms is far above explicit Euler's on the hanging cloth.)
TEST_F(Cli, AFixedStepAboveTheStableStepIsSaidBeforeTheRun) {
  const Outcome r = run({"simulate", scene_asset("hanging"), "--integrator", "explicit_euler",
                         "--dt", "0.02", "--seconds", "0.1", "--out", result_path()});
  EXPECT_TRUE(test::contains(r.out, "note: dt = 0.02 s is above the stable step of explicit_euler"))
      << r.out;
  const Outcome fine =
      run({"simulate", scene_asset("hanging"), "--seconds", "0.01", "--out", result_path()});
  ASSERT_EQ(fine.code, kOk) << fine.err;
  EXPECT_FALSE(test::contains(fine.out, "above the stable step")) << fine.out;
}

// 1e7 N/m on 1e-5 kg nodes: the adaptive step's cap is ~2e-7 s, so 0.5 s would
// take millions of steps. The budget stops it; the command says so and exits 5.
TEST_F(Cli, ARunTheStepBudgetStopsSaysSoAndExitsFive) {
  const std::string scene =
      write("stiff.json", with(with(read_text(scene_asset("hanging")),
                                    R"("spring_constant": 200.0)", R"("spring_constant": 1e7)"),
                               R"("node_mass": 0.01)", R"("node_mass": 1e-5)"));
  const Outcome r = run(
      {"simulate", scene, "--adaptive", "--dt", "0.1", "--seconds", "0.5", "--out", result_path()});
  ASSERT_EQ(r.code, kStoppedEarly) << r.out << r.err;
  EXPECT_NE(r.out.find("stopped early"), std::string::npos) << r.out;
  const json doc = read_result();
  EXPECT_EQ(doc.at("status"), "ok");
  EXPECT_EQ(doc.at("step_budget_exhausted"), true);
  EXPECT_LT(doc.at("time").get<double>(), 0.5);
  expect_all_finite(doc, "result");
}

}  // namespace
}  // namespace neurocloth::cli_test
