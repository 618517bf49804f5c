// `neurocloth-cli fit` run as a user would. The option checks run before
// anything is read; the rest needs the real FitProblem and reference reader.
#include "cli_fixture.h"

namespace neurocloth::cli_test {
namespace {

class CliFit : public Cli {
 protected:
  std::string fitted() const { return (out_dir() / "FITTED.json").string(); }

  // A marker reference for `scene` run with spring_constant `k`: every node at
  // a few times, from RESULT.json.
  std::string reference_from(const std::string& scene, double k) const {
    const std::string stiff =
        write("truth.json", with(read_text(scene_asset(scene)), "\"spring_constant\": 50.0",
                                 "\"spring_constant\": " + std::to_string(k)));
    std::string csv = "time,node,x,y,z\n";
    for (double t : {0.05, 0.1, 0.15, 0.2}) {
      const std::string result = (dir_ / "truth_result.json").string();
      const Outcome r = run({"simulate", stiff, "--seconds", std::to_string(t), "--out", result});
      EXPECT_EQ(r.code, kOk) << r.err;
      const json doc = json::parse(read_text(result));
      for (std::size_t n = 0; n < doc["positions"].size(); ++n) {
        const json& p = doc["positions"][n];
        csv += std::to_string(t) + "," + std::to_string(n) + "," + p[0].dump() + "," + p[1].dump() +
               "," + p[2].dump() + "\n";
      }
    }
    return write("reference.csv", csv);
  }
};

// Needs nothing but the command line.
TEST_F(CliFit, AnIterationBudgetBelowOneIsRefused) {
  const std::string ref = write("reference.csv", "time,node,x,y,z\n0.1,0,0,0,0\n");
  for (const char* n : {"0", "-3"})
    expect_input_error(
        {"fit", scene_asset("chain"), "--reference", ref, "--max-iterations", n, "--out", fitted()},
        {"--max-iterations"});
}

TEST_F(CliFit, AnUnknownOptimizerIsRefused) {
  const std::string ref = write("reference.csv", "time,node,x,y,z\n0.1,0,0,0,0\n");
  expect_input_error(
      {"fit", scene_asset("chain"), "--reference", ref, "--optimizer", "adam", "--out", fitted()},
      {"--optimizer", "adam"});
}

TEST_F(CliFit, AMissingReferenceIsAUsageError) {
  const Outcome r = run({"fit", scene_asset("chain"), "--out", fitted()});
  EXPECT_EQ(r.code, kUsage) << r.err;
  EXPECT_NE(r.err.find("--reference"), std::string::npos) << r.err;
  EXPECT_TRUE(files_in_out_dir().empty());
}

// Need the real FitProblem (fit_problem.cpp) and reference reader.
TEST_F(CliFit, AParameterFitCannotChangeIsRefused) {
  const std::string ref = reference_from("chain", 50.0);
  expect_input_error({"fit", scene_asset("chain"), "--reference", ref, "--params",
                      "spring_constant,warp_speed", "--out", fitted()},
                     {"--params", "warp_speed"});
}

TEST_F(CliFit, ABadReferenceIsRefusedNamingItsFile) {
  const std::string ref = write("broken.csv", "time,node,x,y,z\n0.1,0,0,zero,0\n");
  expect_input_error({"fit", scene_asset("chain"), "--reference", ref, "--out", fitted()},
                     {"broken.csv"});
}

TEST_F(CliFit, RecoversTheSpringConstantAndWritesALoadableScene) {
  const std::string ref = reference_from("chain", 65.0);
  const Outcome r = run({"fit", scene_asset("chain"), "--reference", ref, "--params",
                         "spring_constant", "--max-iterations", "40", "--out", fitted()});
  ASSERT_EQ(r.code, kOk) << r.out << r.err;
  EXPECT_NE(r.out.find("iteration 0/40"), std::string::npos) << r.out;  // plain lines: no tty
  EXPECT_EQ(r.out.find('\r'), std::string::npos);
  EXPECT_NE(r.out.find("uncertainty"), std::string::npos) << r.out;
  const Scene fitted_scene = load_scene(fitted());
  EXPECT_NEAR(fitted_scene.material.spring_constant, 65.0, 65.0 * 0.02);
  EXPECT_TRUE(fs::exists(out_dir() / "FITTED.loss.csv"));
  EXPECT_TRUE(fs::exists(out_dir() / "FITTED.loss.png"));
  const Outcome sim = run({"simulate", fitted(), "--seconds", "0.05", "--out", result_path()});
  EXPECT_EQ(sim.code, kOk) << sim.err;
}

// Every bad reference the issue lists: exit 1, one line naming the file, the
// line and the field, nothing written.
TEST_F(CliFit, EveryBadMarkerFileIsRefusedNamingFileLineAndField) {
  struct Bad {
    const char* text;
    std::vector<std::string> mentions;
  };
  const std::vector<Bad> cases = {
      {"time,node,x,y,z\n0.1,0,0,0,0\n0.1,10,0,0,0\n", {":3", "node", "10"}},
      {"time,node,x,y,z\n0.1,0,0,nan,0\n", {":2", "y"}},
      {"time,node,x,y,z\n0.1,0,0,0,inf\n", {":2", "z"}},
      {"time,node,x,y,z\n0.1,0,0,0,0\n0.05,1,0,0,0\n", {":3", "time"}},
      {"time,node,x,y,z\n0.1,3,0,0,0\n0.1,3,0,0,1\n", {":3", "node", "3"}},
      {"time,node,x,y,z\n", {"marker"}},
      {"time,node,x,y,z\n1e300,0,0,0,0\n", {"time", "1e7"}},
  };
  for (const Bad& b : cases) {
    const std::string ref = write("markers.csv", b.text);
    std::vector<std::string> mentions = {"markers.csv"};
    mentions.insert(mentions.end(), b.mentions.begin(), b.mentions.end());
    expect_input_error({"fit", scene_asset("chain"), "--reference", ref, "--out", fitted()},
                       mentions);
  }
}

TEST_F(CliFit, ARecordingOfAnotherSceneIsRefused) {
  const std::string rec = (dir_ / "hanging.motion").string();
  ASSERT_EQ(run({"simulate", scene_asset("hanging"), "--seconds", "0.02", "--record", rec, "--out",
                 result_path()})
                .code,
            kOk);
  fs::remove(result_path());
  fs::rename(rec, dir_ / "moved.motion");  // out of the output folder the check looks at
  expect_input_error({"fit", scene_asset("chain"), "--reference", (dir_ / "moved.motion").string(),
                      "--out", fitted()},
                     {"moved.motion", "node_count", "400"});
}

// Parameters, integrators and modules fit cannot differentiate: one line
// naming them, nothing written.
TEST_F(CliFit, WhatFitCannotChangeIsRefusedByName) {
  const std::string ref = reference_from("chain", 50.0);
  for (const auto& [params, mention] : std::vector<std::pair<std::string, std::string>>{
           {"friction", "collider"}, {"wind.drag", "wind.drag"}, {"", "unknown parameter ''"}}) {
    expect_input_error(
        {"fit", scene_asset("chain"), "--reference", ref, "--params", params, "--out", fitted()},
        {"--params", mention});
  }
  const std::string rk4 =
      write("rk4.json", with(read_text(scene_asset("chain")), "\"integrator\": \"network\"",
                             "\"integrator\": \"rk4\""));
  expect_input_error({"fit", rk4, "--reference", ref, "--out", fitted()}, {"rk4", "adjoint"});
}

}  // namespace
}  // namespace neurocloth::cli_test
