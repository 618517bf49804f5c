// Runs neurocloth-cli as a user would: a real process, real files, exit codes.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "scene.h"

namespace neurocloth {
namespace {
namespace fs = std::filesystem;
using nlohmann::json;

// The exit codes documented in src/app/commands.h.
constexpr int kOk = 0, kInputError = 1, kUsage = 2, kDiverged = 3;

struct Outcome {
  int code = -1;  // -1: did not exit normally; 124: killed by the timeout
  std::string out, err;
};

std::string quote(const std::string& s) {
  std::string q = "'";
  for (char c : s)
    q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string scene_asset(const std::string& name) {
  return assets_directory() + "/scenes/" + name + ".json";
}

// `text` with the first occurrence of `from` replaced by `to`.
std::string with(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << "test bug: '" << from << "' not found";
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

// Every number in `v` is finite (NaN and infinity would be written as null).
void expect_all_finite(const json& v, const std::string& where) {
  if (v.is_null()) {
    ADD_FAILURE() << where << " is null (a NaN or infinity was written)";
  }
  if (v.is_number()) {
    EXPECT_TRUE(std::isfinite(v.get<double>())) << where;
  }
  if (v.is_object())
    for (const auto& item : v.items())
      expect_all_finite(item.value(), where + "." + item.key());
  if (v.is_array())
    for (std::size_t i = 0; i < v.size(); ++i)
      expect_all_finite(v[i], where + "[" + std::to_string(i) + "]");
}

// Each test gets its own folder: inputs in it, results in its out/ subfolder,
// which must hold nothing but the result (no temporary files left behind).
class Cli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::path(NEUROCLOTH_TEST_TMP) / "cli_test" /
           ::testing::UnitTest::GetInstance()->current_test_info()->name();
    fs::remove_all(dir_);
    fs::create_directories(out_dir());
  }

  fs::path out_dir() const { return dir_ / "out"; }
  std::string result_path() const { return (out_dir() / "result.json").string(); }

  std::string write(const std::string& name, const std::string& text) const {
    const fs::path path = dir_ / name;
    std::ofstream(path, std::ios::binary | std::ios::trunc) << text;
    return path.string();
  }

  // A run that outlives `timeout_seconds` is killed and reported as exit code 124,
  // so a hang fails the test instead of stalling the suite. `prelude` runs in the
  // same shell first (e.g. a ulimit).
  Outcome run(const std::vector<std::string>& args, int timeout_seconds = 120,
              const std::string& prelude = "") const {
    std::string cmd =
        prelude + "timeout -k 5 " + std::to_string(timeout_seconds) + " " + quote(NEUROCLOTH_CLI);
    for (const auto& a : args)
      cmd += " " + quote(a);
    const fs::path out = dir_ / "stdout.txt", err = dir_ / "stderr.txt";
    cmd += " >" + quote(out.string()) + " 2>" + quote(err.string());
    const int status = std::system(cmd.c_str());
    Outcome r;
    if (status != -1 && WIFEXITED(status)) r.code = WEXITSTATUS(status);
    r.out = read_text(out);
    r.err = read_text(err);
    return r;
  }

  json read_result() const {
    std::ifstream in(result_path());
    EXPECT_TRUE(in) << result_path();
    return json::parse(in);
  }

  std::vector<std::string> files_in_out_dir() const {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(out_dir()))
      names.push_back(e.path().filename().string());
    return names;
  }

  // A bad input: exit 1, an error on stderr that mentions every string in
  // `mentions`, and nothing at all in the output folder.
  void expect_input_error(const std::vector<std::string>& args,
                          const std::vector<std::string>& mentions, int timeout_seconds = 120,
                          const std::string& prelude = "") const {
    const Outcome r = run(args, timeout_seconds, prelude);
    EXPECT_NE(r.code, kOk);
    EXPECT_NE(r.code, kDiverged);
    EXPECT_EQ(r.code, kInputError) << r.err;
    EXPECT_NE(r.err.find("error"), std::string::npos) << r.err;
    for (const auto& m : mentions)
      EXPECT_NE(r.err.find(m), std::string::npos) << m << " not in: " << r.err;
    EXPECT_FALSE(fs::exists(result_path()));
    EXPECT_TRUE(files_in_out_dir().empty()) << "left behind: " << files_in_out_dir().front();
  }

  // simulate on a scene derived from hanging.json by one text replacement.
  void expect_bad_hanging(const std::string& from, const std::string& to,
                          const std::vector<std::string>& mentions) const {
    const std::string path = write("bad.json", with(read_text(scene_asset("hanging")), from, to));
    std::vector<std::string> all = {path};
    all.insert(all.end(), mentions.begin(), mentions.end());
    expect_input_error({"simulate", path, "--seconds", "0.01", "--out", result_path()}, all);
  }

  fs::path dir_;
};

// hanging.json: 20 x 20, origin [0, 1, 0], spacing 0.05, rows along z, columns along x.
constexpr int kSide = 20;
constexpr double kSpacing = 0.05;

TEST_F(Cli, SimulateWritesTheResult) {
  const Outcome r =
      run({"simulate", scene_asset("hanging"), "--seconds", "0.05", "--out", result_path()});
  ASSERT_EQ(r.code, kOk) << r.err;
  EXPECT_NE(r.out.find(result_path()), std::string::npos) << r.out;
  EXPECT_EQ(files_in_out_dir(), std::vector<std::string>{"result.json"});

  const json doc = read_result();
  EXPECT_EQ(doc.at("status"), "ok");
  EXPECT_NEAR(doc.at("time").get<double>(), 0.05, 1e-12);
  EXPECT_EQ(doc.at("steps").get<long>(), 50);  // fixed dt 0.001 from the scene
  EXPECT_EQ(doc.at("rejected_steps").get<long>(), 0);
  EXPECT_GE(doc.at("wall_seconds").get<double>(), 0.0);
  EXPECT_EQ(doc.at("nodes").get<int>(), kSide * kSide);
  // structural 2*20*19, shear 2*19*19, bend 2*20*18.
  EXPECT_EQ(doc.at("springs").get<int>(), 760 + 722 + 720);
  const json& e = doc.at("energy");
  const double kinetic = e.at("kinetic"), potential = e.at("potential"), total = e.at("total");
  EXPECT_GT(kinetic, 0.0);  // it has started to fall
  EXPECT_NEAR(total, kinetic + potential, 1e-12 * std::abs(total));
  expect_all_finite(doc, "result");

  const json& x = doc.at("positions");
  const json& v = doc.at("velocities");
  ASSERT_EQ(x.size(), 400u);
  ASSERT_EQ(v.size(), 400u);
  for (std::size_t i = 0; i < x.size(); ++i) {
    ASSERT_EQ(x[i].size(), 3u) << i;
    ASSERT_EQ(v[i].size(), 3u) << i;
  }
  // Pinned corners (0, 0) and (0, 19) stay exactly where they started.
  EXPECT_EQ(x[0], json({0.0, 1.0, 0.0}));
  EXPECT_EQ(x[19].at(1).get<double>(), 1.0);
  EXPECT_EQ(v[0], json({0.0, 0.0, 0.0}));
  EXPECT_EQ(v[19], json({0.0, 0.0, 0.0}));
  // The free far corner falls.
  EXPECT_LT(x[399].at(1).get<double>(), 1.0);
  EXPECT_LT(v[399].at(1).get<double>(), 0.0);
}

TEST_F(Cli, ZeroSecondsWritesTheInitialState) {
  const Outcome r =
      run({"simulate", scene_asset("hanging"), "--seconds", "0", "--out", result_path()});
  ASSERT_EQ(r.code, kOk) << r.err;
  const json doc = read_result();
  EXPECT_EQ(doc.at("status"), "ok");
  EXPECT_EQ(doc.at("time").get<double>(), 0.0);
  EXPECT_EQ(doc.at("steps").get<long>(), 0);
  const json& x = doc.at("positions");
  const json& v = doc.at("velocities");
  ASSERT_EQ(x.size(), 400u);
  ASSERT_EQ(v.size(), 400u);
  for (int row = 0; row < kSide; ++row)
    for (int col = 0; col < kSide; ++col) {
      const int i = row * kSide + col;
      SCOPED_TRACE("node " + std::to_string(i));
      EXPECT_DOUBLE_EQ(x[i].at(0).get<double>(), col * kSpacing);
      EXPECT_DOUBLE_EQ(x[i].at(1).get<double>(), 1.0);
      EXPECT_DOUBLE_EQ(x[i].at(2).get<double>(), row * kSpacing);
      EXPECT_EQ(v[i], json({0.0, 0.0, 0.0}));
    }
  EXPECT_EQ(doc.at("energy").at("kinetic").get<double>(), 0.0);
}

TEST_F(Cli, OptionsOverrideTheScene) {
  const Outcome r = run({"simulate", scene_asset("hanging"), "--seconds", "0.01", "--integrator",
                         "rk4", "--dt", "0.002", "--out", result_path()});
  ASSERT_EQ(r.code, kOk) << r.err;
  const json doc = read_result();
  EXPECT_EQ(doc.at("integrator"), "rk4");
  EXPECT_EQ(doc.at("dt").get<double>(), 0.002);
  EXPECT_EQ(doc.at("steps").get<long>(), 5);
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

TEST_F(Cli, AdaptiveWithFixedStepIsAUsageError) {
  const Outcome r = run({"simulate", scene_asset("hanging"), "--seconds", "0.01", "--adaptive",
                         "--fixed-step", "--out", result_path()});
  EXPECT_EQ(r.code, kUsage);
  EXPECT_NE(r.err.find("--fixed-step"), std::string::npos) << r.err;
  EXPECT_TRUE(files_in_out_dir().empty());
}

TEST_F(Cli, MissingRequiredOptionIsAUsageError) {
  const Outcome r = run({"simulate", scene_asset("hanging"), "--out", result_path()});
  EXPECT_EQ(r.code, kUsage);
  EXPECT_NE(r.err.find("--seconds"), std::string::npos) << r.err;
  EXPECT_TRUE(files_in_out_dir().empty());
}

TEST_F(Cli, MalformedJson) {
  // Line 3 of hanging.json follows "name" without its comma.
  const std::string path =
      write("bad.json", with(read_text(scene_asset("hanging")), R"("hanging",)", R"("hanging")"));
  expect_input_error({"simulate", path, "--seconds", "0.01", "--out", result_path()},
                     {path + ":3:", "malformed JSON"});
}

TEST_F(Cli, MissingKey) {
  expect_bad_hanging(R"("node_mass": 0.01, )", "", {"material.node_mass"});
}

TEST_F(Cli, MistypedKey) {
  expect_bad_hanging(R"("viscosity")", R"("viscocity")", {"material.viscocity"});
}

TEST_F(Cli, UnknownIntegratorOption) {
  expect_input_error({"simulate", scene_asset("hanging"), "--seconds", "0.01", "--integrator",
                      "bogus", "--out", result_path()},
                     {"--integrator", "bogus", "explicit_euler"});
}

TEST_F(Cli, ZeroTimeStepOption) {
  expect_input_error({"simulate", scene_asset("hanging"), "--seconds", "0.01", "--dt", "0", "--out",
                      result_path()},
                     {"--dt"});
}

TEST_F(Cli, NegativeTimeStepOption) {
  expect_input_error({"simulate", scene_asset("hanging"), "--seconds", "0.01", "--dt", "-1",
                      "--out", result_path()},
                     {"--dt"});
}

TEST_F(Cli, NegativeSecondsOption) {
  expect_input_error(
      {"simulate", scene_asset("hanging"), "--seconds", "-1", "--out", result_path()},
      {"--seconds"});
}

// No simulation reaches infinity: this must be refused, not run until killed.
TEST_F(Cli, InfiniteSecondsOption) {
  expect_input_error(
      {"simulate", scene_asset("hanging"), "--seconds", "inf", "--out", result_path()},
      {"--seconds"}, /*timeout_seconds=*/10);
}

// A scene's dt must be a finite number; the option that overrides it must be too.
TEST_F(Cli, InfiniteTimeStepOption) {
  expect_input_error({"simulate", scene_asset("hanging"), "--seconds", "0.01", "--dt", "inf",
                      "--out", result_path()},
                     {"--dt"});
}

TEST_F(Cli, PinOutsideTheGrid) {
  expect_bad_hanging("[0, 19]", "[0, 20]", {"cloth.pins[1]"});
}

TEST_F(Cli, ZeroMass) {
  expect_bad_hanging(R"("node_mass": 0.01)", R"("node_mass": 0)", {"material.node_mass"});
}

TEST_F(Cli, NegativeMass) {
  expect_bad_hanging(R"("node_mass": 0.01)", R"("node_mass": -0.01)", {"material.node_mass"});
}

TEST_F(Cli, NegativeStiffness) {
  expect_bad_hanging(R"("spring_constant": 200.0)", R"("spring_constant": -200.0)",
                     {"material.spring_constant"});
}

TEST_F(Cli, BadTimeStepInScene) {
  expect_bad_hanging(R"("dt": 0.001)", R"("dt": 0)", {"solver.dt"});
}

// Valid JSON syntax, but too large for a double.
TEST_F(Cli, NumberOverflow) {
  expect_bad_hanging(R"("node_mass": 0.01)", R"("node_mass": 1e400)", {});
}

// JSON nested 20000 deep is valid and the JSON parser takes it without recursion;
// reading the scene must then fail with an input error ("name" is not a string),
// not run out of stack. The 1 MiB stack limit makes a per-level recursion crash
// here quickly and cheaply; every ordinary run fits in it many times over.
TEST_F(Cli, DeeplyNestedJson) {
  const std::string deep = std::string(20000, '[') + std::string(20000, ']');
  const std::string path = write("deep.json", with(read_text(scene_asset("hanging")),
                                                   R"("name": "hanging")", R"("name": )" + deep));
  // Refused before parsing, so the message names the place (file:line:column),
  // not a field.
  expect_input_error({"simulate", path, "--seconds", "0", "--out", result_path()},
                     {path + ":2:", "nested deeper than"},
                     /*timeout_seconds=*/60, "ulimit -s 1024; ");
}

// The same stack limit, on a valid scene: the limit alone is no reason to fail.
TEST_F(Cli, OrdinaryRunFitsInASmallStack) {
  const Outcome r =
      run({"simulate", scene_asset("hanging"), "--seconds", "0.01", "--out", result_path()},
          /*timeout_seconds=*/60, "ulimit -s 1024; ");
  EXPECT_EQ(r.code, kOk) << r.err;
}

TEST_F(Cli, BrokenObj) {
  const std::string obj = write("broken.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99\n");
  const std::string scene =
      write("mesh.json", with(read_text(scene_asset("mesh_square")), "../meshes/square.obj", obj));
  expect_input_error({"simulate", scene, "--seconds", "0.01", "--out", result_path()},
                     {obj, "'f'", "99"});
}

TEST_F(Cli, MissingObj) {
  const std::string obj = (dir_ / "missing.obj").string();
  const std::string scene =
      write("mesh.json", with(read_text(scene_asset("mesh_square")), "../meshes/square.obj", obj));
  expect_input_error({"simulate", scene, "--seconds", "0.01", "--out", result_path()}, {obj});
}

TEST_F(Cli, SceneFileDoesNotExist) {
  const std::string path = (dir_ / "no_such_scene.json").string();
  expect_input_error({"simulate", path, "--seconds", "0.01", "--out", result_path()}, {path});
}

TEST_F(Cli, RelaxWithBadSceneWritesNothing) {
  const std::string path = write("bad.json", with(read_text(scene_asset("chain")),
                                                  R"("node_mass": 0.02)", R"("node_mass": 0)"));
  expect_input_error({"relax", path, "--out", result_path()}, {path, "material.node_mass"});
}

TEST_F(Cli, UnwritableOutputNamesThePath) {
  const std::string out = (dir_ / "no_such_dir" / "result.json").string();
  const Outcome r = run({"simulate", scene_asset("hanging"), "--seconds", "0", "--out", out});
  EXPECT_EQ(r.code, kInputError);
  EXPECT_NE(r.err.find(out), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "no_such_dir"));
}

TEST_F(Cli, RelaxChainReachesTheAnalyticEquilibrium) {
  const Outcome r = run({"relax", scene_asset("chain"), "--out", result_path()});
  ASSERT_EQ(r.code, kOk) << r.err;
  EXPECT_EQ(files_in_out_dir(), std::vector<std::string>{"result.json"});
  const json doc = read_result();
  EXPECT_EQ(doc.at("status"), "ok");
  expect_all_finite(doc, "result");
  const json& x = doc.at("positions");
  ASSERT_EQ(x.size(), 10u);
  // chain.json: 10 nodes 0.1 m apart hanging from node 0 at y = 2; k = 50, m = 0.02.
  // Spring i carries the 9 - i nodes below it, so it stretches by (9 - i) m g / k.
  double y = 2.0;
  for (int i = 0; i < 10; ++i) {
    SCOPED_TRACE("node " + std::to_string(i));
    EXPECT_NEAR(x[i].at(0).get<double>(), 0.0, 1e-9);
    EXPECT_NEAR(x[i].at(1).get<double>(), y, 1e-7);
    EXPECT_NEAR(x[i].at(2).get<double>(), 0.0, 1e-9);
    y -= 0.1 + (9 - i) * 0.02 * 9.81 / 50.0;
  }
  for (const auto& v : doc.at("velocities"))
    EXPECT_EQ(v, json({0.0, 0.0, 0.0}));
}

TEST_F(Cli, BenchPrintsJson) {
  const Outcome r = run({"bench", "--size", "8", "--steps", "5", "--repeat", "1", "--json"});
  ASSERT_EQ(r.code, kOk) << r.err;
  json doc;
  ASSERT_NO_THROW(doc = json::parse(r.out)) << r.out;
  EXPECT_EQ(doc.at("nodes").get<int>(), 64);
  // structural 2*8*7, shear 2*7*7, bend 2*8*6.
  EXPECT_EQ(doc.at("springs").get<int>(), 112 + 98 + 96);
  EXPECT_EQ(doc.at("steps").get<int>(), 5);
  const double sps = doc.at("steps_per_second"), ns = doc.at("ns_per_spring_update");
  EXPECT_GT(sps, 0.0);
  EXPECT_GT(ns, 0.0);
  EXPECT_TRUE(std::isfinite(sps));
  EXPECT_TRUE(std::isfinite(ns));
  // The two rates describe the same timing.
  EXPECT_NEAR(ns, 1e9 / (sps * 306), 1e-6 * ns);
}

TEST_F(Cli, BenchRejectsTinySize) {
  const Outcome r = run({"bench", "--size", "1", "--steps", "5", "--repeat", "1", "--json"});
  EXPECT_EQ(r.code, kInputError);
  EXPECT_NE(r.err.find("--size"), std::string::npos) << r.err;
}

// material: a rule base and linguistic inputs -> every output and rule activation.
TEST_F(Cli, MaterialFromRulesAndInputs) {
  const std::string fcl = assets_directory() + "/materials/cloth.fcl";
  const Outcome r = run({"material", "--rules", fcl, "--input", "mass=0.2", "--input",
                         "elasticity=0.3", "--input", "force=3", "--json"});
  ASSERT_EQ(r.code, kOk) << r.err;
  const json doc = json::parse(r.out);
  for (const char* out : {"spring_constant", "node_mass", "viscosity", "friction"})
    EXPECT_TRUE(doc.at("outputs").contains(out)) << out;
  // Sugeno node mass: density x 0.0025 m^2.
  EXPECT_NEAR(doc.at("outputs").at("node_mass").get<double>(), 0.2 * 0.0025, 1e-12);
  EXPECT_EQ(doc.at("rule_activations").size(), 17u);
  EXPECT_EQ(doc.at("rule_activations")[0].at("rule"), "1");
  // The preset with the same inputs gives the same outputs.
  const Outcome p = run({"material", "--preset", "cotton", "--json"});
  ASSERT_EQ(p.code, kOk) << p.err;
  EXPECT_EQ(json::parse(p.out).at("outputs"), doc.at("outputs"));
  // Text output names every output and rule.
  const Outcome t = run({"material", "--preset", "silk"});
  ASSERT_EQ(t.code, kOk);
  EXPECT_NE(t.out.find("spring_constant"), std::string::npos);
  EXPECT_NE(t.out.find("RULE 17"), std::string::npos);
}

TEST_F(Cli, MaterialReportsClampedInputs) {
  const Outcome r =
      run({"material", "--rules", assets_directory() + "/materials/cloth.fcl", "--input", "mass=7",
           "--input", "elasticity=0.3", "--input", "force=3", "--json"});
  ASSERT_EQ(r.code, kOk) << r.err;
  const json doc = json::parse(r.out);
  EXPECT_EQ(doc.at("clamped")[0], "mass");
  EXPECT_NE(doc.at("notes")[0].get<std::string>().find("clamped"), std::string::npos);
}

TEST_F(Cli, MaterialBadInputs) {
  const std::string fcl = assets_directory() + "/materials/cloth.fcl";
  auto expect_error = [&](const std::vector<std::string>& args,
                          const std::vector<std::string>& mentions) {
    const Outcome r = run(args);
    EXPECT_EQ(r.code, kInputError) << r.err;
    for (const auto& m : mentions)
      EXPECT_NE(r.err.find(m), std::string::npos) << m << " not in: " << r.err;
  };
  expect_error({"material", "--rules", fcl, "--input", "mass=0.2", "--input", "elasticity=0.3"},
               {"force", "missing"});
  expect_error({"material", "--rules", fcl, "--input", "mass=0.2", "--input", "elasticity=0.3",
                "--input", "force=3", "--input", "colour=1"},
               {"colour"});
  expect_error({"material", "--rules", fcl, "--input", "mass=heavy", "--input", "elasticity=0.3",
                "--input", "force=3"},
               {"mass", "heavy"});
  expect_error({"material", "--rules", fcl, "--input", "mass"}, {"NAME=VALUE"});
  expect_error({"material", "--preset", "velvet"}, {"velvet", "silk"});
  expect_error({"material", "--rules", (dir_ / "missing.fcl").string(), "--input", "x=1"},
               {"missing.fcl"});
  const std::string broken = write("broken.fcl",
                                   "FUNCTION_BLOCK b\nVAR_INPUT\n  x : REAL;\nEND_VAR\nFUZZIFY x\n "
                                   " RANGE := (0 .. 1);\n  TERM t := trian 0 oops 1;\n");
  expect_error({"material", "--rules", broken, "--input", "x=0.5"}, {broken + ":7:"});
  EXPECT_EQ(run({"material", "--preset", "silk", "--rules", fcl}).code, kUsage);
}

}  // namespace
}  // namespace neurocloth
