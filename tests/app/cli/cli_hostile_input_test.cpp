// The hostile inputs of the mutation campaign against neurocloth-cli, one test
// per root cause, run as the campaign ran them: a real process, real files.
// Each guards against a crash, a hang, a NaN or null written, or an error
// naming no file; docs/robustness.md lists them.
#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <unistd.h>

#include <chrono>
#include <thread>

#include "support/cli_fixture.h"
#include "support/line_of.h"

namespace neurocloth::cli_test {
namespace {

const std::string kRules = assets_directory() + "/materials/cloth.fcl";

std::string repeat(const std::string& s, int n) {
  std::string out;
  out.reserve(s.size() * static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i)
    out += s;
  return out;
}

using test::line_of;

std::vector<std::string> cloth_inputs() {
  return {"--input", "mass=0.2", "--input", "elasticity=0.3", "--input", "force=3"};
}

class HostileInput : public Cli {
 protected:
  // cloth.fcl with rule 1's condition replaced by `condition`.
  std::string rules_with_condition(const std::string& name, const std::string& condition) const {
    return write(name, with(read_text(kRules), "IF mass IS big AND elasticity IS big THEN",
                            "IF " + condition + " THEN"));
  }

  // A copy of hanging_fuzzy.json (the hanging cloth described in words) whose
  // rule base is `rules`.
  std::string fuzzy_scene_with_rules(const std::string& rules) const {
    return write("fuzzy.json", with(read_text(scene_asset("hanging_fuzzy")),
                                    "\"../materials/cloth.fcl\"", "\"" + rules + "\""));
  }

  // Both ways a rule base is loaded: `material --rules` and a scene's material.rules.
  void expect_rules_refused(const std::string& rules, const std::vector<std::string>& mentions) {
    std::vector<std::string> args = {"material", "--rules", rules};
    for (const auto& a : cloth_inputs())
      args.push_back(a);
    expect_input_error(args, mentions);
    expect_input_error(
        {"simulate", fuzzy_scene_with_rules(rules), "--seconds", "0.01", "--out", result_path()},
        mentions);
  }
};

// 1. The rule-condition parser recurses once per '(' and NOT: without a limit
// on the depth these would overflow the stack.
TEST_F(HostileInput, DeeplyNestedRuleConditionsAreRefusedWithTheirLine) {
  const std::string nested =
      rules_with_condition("nested.fcl", repeat("(", 10000) + "mass IS big" + repeat(")", 10000));
  const int line = line_of(read_text(nested), "RULE 1 ");
  expect_rules_refused(nested, {nested + ":" + std::to_string(line) + ":", "nests", "32"});

  const std::string unclosed = rules_with_condition("unclosed.fcl", repeat("(", 10000));
  expect_rules_refused(unclosed, {unclosed + ":" + std::to_string(line) + ":", "nests"});

  const std::string nots = rules_with_condition("nots.fcl", repeat("NOT ", 50000) + "mass IS big");
  expect_rules_refused(nots, {nots + ":" + std::to_string(line) + ":", "nests"});
}

// A condition as deep as the limit still reads and infers.
TEST_F(HostileInput, ARuleConditionAtTheDepthLimitIsRead) {
  const std::string deep = rules_with_condition(
      "deep.fcl", repeat("(", 32) + "mass IS big" + repeat(")", 32) + " AND elasticity IS big");
  std::vector<std::string> args = {"material", "--rules", deep};
  for (const auto& a : cloth_inputs())
    args.push_back(a);
  const Outcome r = run(args);
  EXPECT_EQ(r.code, kOk) << r.err;
}

// 2. Finite but huge values are refused at the boundary, not left to make the
// run "diverge at t = 0" with null where RESULT.json's energies belong.
TEST_F(HostileInput, HugeFiniteValuesAreRefusedWithTheirMeaning) {
  expect_bad_hanging("\"spacing\": 0.05", "\"spacing\": 1e308",
                     {"cloth.grid.spacing", ":5:", "100 m"});
  expect_bad_hanging("\"origin\": [0, 1, 0]", "\"origin\": [0, 1e308, 0]",
                     {"cloth.grid.origin[1]", "10 km"});
  expect_bad_hanging("\"gravity\": [0, -9.81, 0]", "\"gravity\": [0, -1e308, 0]",
                     {"gravity[1]", "100 g"});
  // Each value in range, together out of it: 10,000 nodes 100 m apart.
  expect_bad_hanging("\"rows\": 20, \"cols\": 20, \"spacing\": 0.05",
                     "\"rows\": 20, \"cols\": 200, \"spacing\": 99", {"cloth.grid", "10 km"});
  expect_bad_hanging("\"node_mass\": 0.01", "\"node_mass\": 5e-324",
                     {"material.node_mass", ":10:", "microgram"});
  expect_bad_hanging("\"spring_constant\": 200.0", "\"spring_constant\": 1e300",
                     {"material.spring_constant"});
}

TEST_F(HostileInput, HugeMeshValuesAreRefused) {
  const std::string square = read_text(assets_directory() + "/meshes/square.obj");
  const std::string huge = write("huge.obj", with(square, "v 1 0 1", "v 1e308 0 1"));
  const std::string scene = read_text(scene_asset("mesh_square"));
  const auto mesh_scene = [&](const std::string& name, const std::string& obj,
                              const std::string& scale) {
    return write(name, with(with(scene, "\"../meshes/square.obj\"", "\"" + obj + "\""),
                            "\"scale\": 0.5", "\"scale\": " + scale));
  };
  const std::string a = mesh_scene("a.json", huge, "0.5");
  expect_input_error({"simulate", a, "--seconds", "0.01", "--out", result_path()},
                     {huge + ":10:", "vertex 9", "1e10", a, "cloth.mesh.obj"});
  // Each vertex in range, scaled and moved out of it.
  const std::string far = write("far.obj", with(square, "v 1 0 1", "v 1e5 0 1"));
  const std::string d = mesh_scene("d.json", far, "0.5");
  expect_input_error({"simulate", d, "--seconds", "0.01", "--out", result_path()},
                     {d, "cloth.mesh", "10 km"});
  const std::string b = mesh_scene("b.json", assets_directory() + "/meshes/square.obj", "1e308");
  expect_input_error({"simulate", b, "--seconds", "0.01", "--out", result_path()},
                     {b, "cloth.mesh.scale"});
  // A NaN vertex names the OBJ file and its vertex, not "the initial state".
  const std::string nan = write("nan.obj", with(square, "v 1 0 1", "v nan 0 1"));
  const std::string c = mesh_scene("c.json", nan, "0.5");
  expect_input_error({"simulate", c, "--seconds", "0.01", "--out", result_path()}, {nan});
}

// 3. relax with every node pinned is converged, not "did NOT converge ... last
// step inf" with "last_step": null.
TEST_F(HostileInput, RelaxingAClothWithNoFreeNodeIsConvergedAsItIs) {
  std::string pins = "\"pins\": [";
  for (int r = 0; r < 20; ++r)
    for (int c = 0; c < 20; ++c)
      pins += (r || c ? ", [" : "[") + std::to_string(r) + ", " + std::to_string(c) + "]";
  const std::string path = write("pinned.json", with(read_text(scene_asset("hanging")),
                                                     "\"pins\": [[0, 0], [0, 19]]", pins + "]"));
  const Outcome r = run({"relax", path, "--out", result_path()});
  EXPECT_EQ(r.code, kOk) << r.out << r.err;
  EXPECT_NE(r.out.find("every node is pinned"), std::string::npos) << r.out;
  const json doc = read_result();
  EXPECT_EQ(doc.at("status"), "ok");
  EXPECT_EQ(doc.at("free_nodes"), 0);
  EXPECT_EQ(doc.at("last_step"), 0.0);
  expect_all_finite(doc, "relax");
}

// 4. A time step has a floor: a run takes T/dt steps, beyond any budget below it.
TEST_F(HostileInput, TimeStepsBelowTheFloorAreRefused) {
  expect_bad_hanging("\"dt\": 0.001", "\"dt\": 5e-324", {"solver.dt", ":12:", "microsecond"});
  expect_bad_hanging("\"dt\": 0.001", "\"dt\": 1e-12", {"solver.dt"});
  const Outcome r = run({"simulate", scene_asset("hanging"), "--seconds", "1", "--dt", "1e-12",
                         "--out", result_path()});
  EXPECT_EQ(r.code, kInputError) << r.err;
  EXPECT_NE(r.err.find("dt"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(result_path()));
  // A trade row that --accuracy would pick.
  const std::string trade = read_text(assets_directory() + "/tradeoff/hanging.csv");
  const auto header = trade.find("\nmethod,");
  const auto row = trade.find('\n', header + 1);
  const std::string bad =
      write("trade.csv", trade.substr(0, row + 1) +
                             "network,dt,1e-12,1e-12,,,1,1e-09,1e-09,1e-09,1,1,0,ok\n" +
                             trade.substr(row + 1));
  const int line = line_of(read_text(bad), "network,dt,1e-12");
  expect_input_error({"simulate", scene_asset("hanging"), "--seconds", "1", "--accuracy", "0.5",
                      "--trade", bad, "--out", result_path()},
                     {bad + ":" + std::to_string(line) + ":", "dt"});
}

// 5. strain_limit.iterations is capped: 2147483647 with tolerance 0 would hang.
TEST_F(HostileInput, StrainLimitIterationsAreCapped) {
  const std::string curtain = read_text(scene_asset("curtain"));
  ASSERT_NE(curtain.find("\"strain_limit\""), std::string::npos);
  const std::string path =
      write("curtain.json", with(curtain, "\"type\": \"strain_limit\"",
                                 "\"type\": \"strain_limit\", \"iterations\": 2147483647, "
                                 "\"tolerance\": 0"));
  expect_input_error({"simulate", path, "--seconds", "1", "--out", result_path()},
                     {path, "iterations", "1000"});
}

// 6. A face of 60,000 corners (some 15 s of quadratic triangulation) is
// refused, with its line, before it is triangulated.
TEST_F(HostileInput, AFaceWithTooManyCornersIsRefusedWithItsLine) {
  const std::string square = read_text(assets_directory() + "/meshes/square.obj");
  const std::string obj = write("long.obj", square + "f" + repeat(" 1", 60000) + "\n");
  const int line = line_of(read_text(obj), "f 1 1 1");
  const std::string scene = write("long.json", with(read_text(scene_asset("mesh_square")),
                                                    "\"../meshes/square.obj\"", "\"" + obj + "\""));
  expect_input_error({"simulate", scene, "--seconds", "0.01", "--out", result_path()},
                     {obj + ":" + std::to_string(line) + ":", "256 corners"});
}

// 7. --seconds 1e300 is a run that never ends: it says how long it will take,
// prints its progress, and Ctrl-C ends it with the state reached written.
// The signal is sent only once the run has said it is running, so the outcome
// does not depend on how fast this machine is.
TEST_F(HostileInput, AnEndlessRunReportsProgressAndCtrlCKeepsTheStateReached) {
  const fs::path err = dir_ / "stderr.txt", out = dir_ / "stdout.txt";
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    if (!freopen(err.c_str(), "w", stderr) || !freopen(out.c_str(), "w", stdout)) _exit(127);
    execl(NEUROCLOTH_CLI, NEUROCLOTH_CLI, "simulate", scene_asset("hanging").c_str(), "--seconds",
          "1e300", "--progress", "0.05", "--out", result_path().c_str(),
          static_cast<char*>(nullptr));
    _exit(127);
  }
  // Wait (at most 5 minutes: a guard against a hang, not a speed test) for
  // the second progress line.
  bool running = false, exited = false;
  int status = 0;
  for (int i = 0; i < 3000 && !running && !exited; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    const std::string e = read_text(err);
    running = e.find("progress:") != e.rfind("progress:");
    exited = waitpid(pid, &status, WNOHANG) == pid;
  }
  if (!exited) {
    kill(pid, SIGINT);
    ASSERT_EQ(waitpid(pid, &status, 0), pid);
  }
  ASSERT_TRUE(running) << read_text(err);
  ASSERT_TRUE(WIFEXITED(status)) << "killed by signal " << WTERMSIG(status);
  EXPECT_EQ(WEXITSTATUS(status), 130) << read_text(err);
  const std::string e = read_text(err);
  EXPECT_NE(e.find("this run takes about"), std::string::npos) << e;
  EXPECT_NE(e.find("years"), std::string::npos) << e;
  EXPECT_NE(read_text(out).find("interrupted"), std::string::npos) << read_text(out);
  const json doc = read_result();
  EXPECT_EQ(doc.at("status"), "ok");
  EXPECT_EQ(doc.at("interrupted"), true);
  EXPECT_GT(doc.at("time").get<double>(), 0.0);
  EXPECT_GT(doc.at("steps").get<long>(), 0);
  expect_all_finite(doc, "result");
  EXPECT_EQ(files_in_out_dir().size(), 1u);
}

// Endless input: /dev/zero as a rule base, a trade or a mesh would be read
// until memory ran out. A device is named as one; a pipe that never ends, or
// a file too large, by its size.
TEST_F(HostileInput, EndlessFilesAreRefusedBySize) {
  expect_rules_refused("/dev/zero", {"/dev/zero", "is a device"});
  expect_input_error({"simulate", scene_asset("hanging"), "--seconds", "1", "--accuracy", "0.5",
                      "--trade", "/dev/zero", "--out", result_path()},
                     {"/dev/zero", "is a device"});
  const std::string scene = write("zero.json", with(read_text(scene_asset("mesh_square")),
                                                    "\"../meshes/square.obj\"", "\"/dev/zero\""));
  expect_input_error({"simulate", scene, "--seconds", "0.01", "--out", result_path()},
                     {"/dev/zero", "is a device"});
  expect_input_error({"simulate", "/dev/zero", "--seconds", "0.01", "--out", result_path()},
                     {"/dev/zero", "is a device"});

  // `yes` writes into a named pipe for as long as anyone reads it.
  const std::string pipe = (dir_ / "endless.fcl").string();
  ASSERT_EQ(mkfifo(pipe.c_str(), 0600), 0);
  std::vector<std::string> args = {"material", "--rules", pipe};
  for (const auto& a : cloth_inputs())
    args.push_back(a);
  expect_input_error(args, {pipe, "larger than 4 MiB"}, 120, "(yes >" + quote(pipe) + " &); ");

  // A file one byte past the limit is refused by its size, before it is read.
  const std::string big = (dir_ / "big.fcl").string();
  fs::copy_file(kRules, big);
  fs::resize_file(big, (4u << 20) + 1);
  args[2] = big;
  expect_input_error(args, {big, "larger than 4 MiB"});
  // Should the pipe not have been read, `yes` would wait on it for ever.
  const int fd = open(pipe.c_str(), O_RDONLY | O_NONBLOCK);
  if (fd >= 0) close(fd);
}

// A key written twice is an error, not silently resolved (the last winning).
TEST_F(HostileInput, ADuplicateKeyIsNamedWithItsLine) {
  expect_bad_hanging("\"viscosity\": 0.05,", "\"viscosity\": 0.05, \"viscosity\": 50,",
                     {"material.viscosity", ":10:", "twice"});
}

// A folder or a rule base given as the scene is named as such, not "malformed JSON".
TEST_F(HostileInput, AFolderOrARuleBaseGivenAsASceneIsNamedAsSuch) {
  expect_input_error({"simulate", dir_.string(), "--seconds", "1", "--out", result_path()},
                     {dir_.string(), "is a directory"});
  expect_input_error({"simulate", kRules, "--seconds", "1", "--out", result_path()},
                     {kRules, "FCL rule base", "material.rules"});
}

// The output is renamed over its path: over a FIFO or a device (/dev/null) it
// would replace the special file itself with a regular one.
TEST_F(HostileInput, AnOutputThatIsNotARegularFileIsRefused) {
  const std::string fifo = (dir_ / "pipe").string();
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  expect_input_error({"simulate", scene_asset("hanging"), "--seconds", "0.01", "--out", fifo},
                     {"--out", fifo, "not a regular file"});
  struct stat st {};
  ASSERT_EQ(lstat(fifo.c_str(), &st), 0);
  EXPECT_TRUE(S_ISFIFO(st.st_mode)) << fifo << " was replaced";
}

}  // namespace
}  // namespace neurocloth::cli_test
