// Runs neurocloth-cli as a user would: a real process, real files, exit codes.
#include <algorithm>
#include <cstdint>
#include <numeric>
#include <random>
#include <vector>

#include "core/network/spring_kernel.h"
#include "core/scene/grid_builder.h"
#include "core/scene/mesh_node_order.h"
#include "core/scene/obj_mesh_writer.h"
#include "support/cli_fixture.h"
#include "support/shuffled_grid.h"
#include "support/test_support.h"

namespace neurocloth::cli_test {
namespace {

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

TEST_F(Cli, SimulateReportsTheActiveModulesAndTheirTime) {
  const Outcome r =
      run({"simulate", scene_asset("curtain"), "--seconds", "0.2", "--out", result_path()});
  ASSERT_EQ(r.code, kOk) << r.err;
  const json doc = read_result();
  const json& modules = doc.at("modules");
  ASSERT_EQ(modules.size(), 3u);
  std::vector<std::string> types;
  double sum = 0;
  for (const json& m : modules) {
    types.push_back(m.at("type"));
    EXPECT_GT(m.at("calls").get<long>(), 0) << m.dump();
    EXPECT_GE(m.at("seconds").get<double>(), 0.0);
    EXPECT_EQ(m.at("declaration").at("type"), m.at("type"));
    sum += m.at("seconds").get<double>();
    EXPECT_NE(r.out.find("module " + types.back()), std::string::npos) << r.out;
  }
  // Force modules first, then the constraints in the order the step runs them.
  EXPECT_EQ(types, (std::vector<std::string>{"air_drag", "pin_motion", "strain_limit"}));
  EXPECT_DOUBLE_EQ(doc.at("module_seconds").get<double>(), sum);
  EXPECT_LE(sum, doc.at("wall_seconds").get<double>());

  const Outcome bare =
      run({"simulate", scene_asset("hanging"), "--seconds", "0.01", "--out", result_path()});
  ASSERT_EQ(bare.code, kOk) << bare.err;
  EXPECT_EQ(read_result().at("modules"), json::array());
}

TEST_F(Cli, SimulateWithABadModuleNamesFileAndField) {
  const std::string path =
      write("bad.json", with(read_text(scene_asset("table_drape")), R"("type": "box")",
                             R"("type": "box", "friction": -1)"));
  expect_input_error({"simulate", path, "--seconds", "1", "--out", result_path()},
                     {path, "modules[0].friction"});
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

// --kernel picks the spring kernel (spring_kernel.h); one named is timed
// beside the other where both can run. An unknown name, or avx512 on a CPU
// without AVX-512, is refused naming the option (cli_cpu_test.cpp: the same
// with AVX-512 masked, and on an emulated CPU without it).
TEST_F(Cli, BenchTimesTheNamedKernelBesideTheOther) {
  const Outcome r = run(
      {"bench", "--size", "8", "--steps", "5", "--repeat", "1", "--kernel", "portable", "--json"});
  ASSERT_EQ(r.code, kOk) << r.err;
  json doc;
  ASSERT_NO_THROW(doc = json::parse(r.out)) << r.out;
  EXPECT_EQ(doc.at("kernel"), "portable");
  if (avx512_kernel_available()) {
    EXPECT_EQ(doc.at("other_kernel"), "avx512");
    EXPECT_GT(doc.at("other_kernel_ns_per_spring_update").get<double>(), 0.0);
  } else {
    EXPECT_FALSE(doc.contains("other_kernel"));
  }
  std::vector<std::string> refused = {"avx-512"};
  if (!avx512_kernel_available()) refused.push_back("avx512");
  for (const std::string& name : refused) {
    const Outcome bad =
        run({"bench", "--size", "8", "--steps", "5", "--repeat", "1", "--kernel", name});
    EXPECT_EQ(bad.code, kInputError) << name;
    EXPECT_NE(bad.err.find("--kernel"), std::string::npos) << bad.err;
  }
}

TEST_F(Cli, BenchRejectsTinySize) {
  const Outcome r = run({"bench", "--size", "1", "--steps", "5", "--repeat", "1", "--json"});
  EXPECT_EQ(r.code, kInputError);
  EXPECT_NE(r.err.find("--size"), std::string::npos) << r.err;
}

// A size or a count that would take the machine's memory or run for ever is
// refused before anything is built (--size 100000 is 1e10 nodes).
TEST_F(Cli, BenchRejectsSizesAndCountsBeyondItsLimits) {
  for (const auto& [option, value] :
       {std::pair{"--size", "100000"}, {"--steps", "2147483647"}, {"--repeat", "2147483647"}}) {
    std::vector<std::string> args = {"bench", "--size", "8", "--steps", "5", "--repeat", "1"};
    *(std::find(args.begin(), args.end(), option) + 1) = value;
    const Outcome r = run(args, 60);
    EXPECT_EQ(r.code, kInputError) << option << ": " << r.err;
    EXPECT_NE(r.err.find(option), std::string::npos) << r.err;
  }
}

// A mesh's nodes are renumbered at load when its file scatters neighbours, and
// that must not show: the same grid written row by row and with its vertices
// shuffled, pinned and moved by file index, ends with the same positions for
// the same vertices in RESULT.json (to rounding: the sums run in other orders).
TEST_F(Cli, AShuffledMeshGivesTheSameResultByFileIndex) {
  const test::ShuffledGrid sg = test::shuffled_grid(16, 0.05);
  const ClothTopology& grid = sg.grid;
  const auto& order = sg.order;
  const auto& vertex_of = sg.vertex_of;
  const int n = static_cast<int>(grid.rest_positions.size());
  write_obj_mesh(grid, (dir_ / "rows.obj").string());
  write_obj_mesh(sg.shuffled, (dir_ / "shuffled.obj").string());

  // Hung from its two top corners, the middle of its top edge drawn aside.
  const auto scene = [&](const std::string& obj, const std::vector<int>& vertex) {
    const json doc = {
        {"cloth",
         {{"mesh", {{"obj", obj}}},
          {"springs", {"structural", "bend"}},
          {"pins", {vertex[0], vertex[15]}}}},
        {"material",
         {{"spring_constant", 200.0}, {"node_mass", 0.01}, {"viscosity", 0.05}, {"friction", 0}}},
        {"modules",
         {{{"type", "pin_motion"},
           {"nodes", {vertex[7], vertex[8]}},
           {"keyframes",
            {{{"t", 0.0}, {"offset", {0, 0, 0}}}, {{"t", 0.3}, {"offset", {0.1, 0, 0}}}}}}}},
        {"gravity", {0, -9.81, 0}},
        {"solver", {{"integrator", "network"}, {"dt", 0.001}, {"adaptive", false}}}};
    return write(obj + ".json", doc.dump());
  };
  std::vector<int> identity(n);
  std::iota(identity.begin(), identity.end(), 0);
  const auto positions = [&](const std::string& path) {
    const Outcome r = run({"simulate", path, "--seconds", "0.3", "--out", result_path()});
    EXPECT_EQ(r.code, kOk) << r.err;
    return read_result().at("positions");
  };
  const json rows = positions(scene("rows.obj", identity));
  const json shuffled = positions(scene("shuffled.obj", vertex_of));
  ASSERT_EQ(rows.size(), static_cast<std::size_t>(n));
  ASSERT_EQ(shuffled.size(), static_cast<std::size_t>(n));
  // The pinned corners stayed, the moved pins went: the pins held the same vertices.
  EXPECT_NEAR(rows[7][0].get<double>(), 0.35 + 0.1, 1e-12);
  for (int k = 0; k < n; ++k)
    for (int axis = 0; axis < 3; ++axis)
      EXPECT_NEAR(shuffled[k][axis].get<double>(), rows[order[k]][axis].get<double>(), 1e-9)
          << "file vertex " << k << " (grid node " << order[k] << "), axis " << axis;
}

}  // namespace
}  // namespace neurocloth::cli_test
