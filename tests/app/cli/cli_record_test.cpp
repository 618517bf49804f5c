// simulate --record and --export-pc2, run as a user would.
#include <algorithm>
#include <cstring>
#include <numeric>
#include <random>

#include <tuple>

#include "core/io/streamed_file.h"
#include "core/scene/grid_builder.h"
#include "core/scene/mesh_node_order.h"
#include "core/scene/obj_mesh_writer.h"
#include "learn/motion/read_reference.h"
#include "learn/motion/reference_motion.h"
#include "support/cli_fixture.h"
#include "support/shuffled_grid.h"

namespace neurocloth::cli_test {
namespace {

class CliRecord : public Cli {
 protected:
  std::string out(const std::string& name) const { return (out_dir() / name).string(); }

  // Frame k of `m` against RESULT.json's positions: bit for bit.
  static void expect_positions(const ReferenceFrame& frame, const json& positions) {
    ASSERT_EQ(frame.positions.size(), positions.size());
    for (std::size_t k = 0; k < positions.size(); ++k)
      for (int a = 0; a < 3; ++a)
        ASSERT_EQ(frame.positions[k][a], positions[k][a].get<double>())
            << "file vertex " << k << " axis " << a;
  }
};

// Every frame at exactly k / 60 s, frame 0 the initial state, the last one the
// state RESULT.json holds; the PC2 cache holds the same frames as float32.
TEST_F(CliRecord, RecordsEveryFrameAtExactTimesAndEndsOnTheResult) {
  const Outcome r =
      run({"simulate", scene_asset("hanging"), "--seconds", "0.5", "--out", result_path(),
           "--record", out("run.motion"), "--export-pc2", out("run.pc2")});
  ASSERT_EQ(r.code, kOk) << r.err;
  EXPECT_NE(r.out.find("31 frames at 60 per second"), std::string::npos) << r.out;
  std::vector<std::string> files = files_in_out_dir();
  std::sort(files.begin(), files.end());
  EXPECT_EQ(files, (std::vector<std::string>{"result.json", "run.motion", "run.obj", "run.pc2"}));

  const ReferenceMotion m = read_reference(out("run.motion"), 400);
  ASSERT_EQ(m.frames.size(), 31u);
  for (std::size_t k = 0; k < m.frames.size(); ++k)
    EXPECT_EQ(m.frames[k].time, static_cast<double>(k) / 60.0) << "frame " << k;
  const Scene scene = load_scene(scene_asset("hanging"));
  const ClothState initial = scene.initial_state();
  for (std::size_t k = 0; k < 400; ++k)
    ASSERT_EQ(m.frames[0].positions[k], initial.position(k)) << k;
  const json doc = read_result();
  EXPECT_EQ(doc.at("time").get<double>(), 0.5);
  expect_positions(m.frames.back(), doc.at("positions"));
  EXPECT_EQ(doc.at("motion").at("frames").get<int>(), 31);

  // The cache: 31 samples of 400 points, the last one the last frame's.
  const std::string pc2 = read_text(out("run.pc2"));
  ASSERT_EQ(pc2.size(), 32u + 31 * 400 * 12);
  const auto le32 = [&](std::size_t at) {
    return get_le32(reinterpret_cast<const unsigned char*>(&pc2[at]));
  };
  EXPECT_EQ(le32(16), 400u);
  EXPECT_EQ(le32(28), 31u);
  for (std::size_t k = 0; k < 400; k += 57)
    for (int a = 0; a < 3; ++a) {
      const std::uint32_t bits = le32(32 + (30 * 400 + k) * 12 + 4 * a);
      float v;
      std::memcpy(&v, &bits, 4);
      EXPECT_EQ(v, static_cast<float>(m.frames.back().positions[k][a])) << k;
    }
}

// Recording changes nothing of the run, even when frames fall inside steps
// (1/60 s is no whole number of 1 ms steps): they are read between two steps.
TEST_F(CliRecord, RecordingLeavesTheRunAsItWas) {
  ASSERT_EQ(
      run({"simulate", scene_asset("hanging"), "--seconds", "0.1", "--out", result_path()}).code,
      kOk);
  const json plain = read_result();
  ASSERT_EQ(run({"simulate", scene_asset("hanging"), "--seconds", "0.1", "--out", result_path(),
                 "--record", out("r.motion"), "--record-fps", "60"})
                .code,
            kOk);
  const json recorded = read_result();
  EXPECT_EQ(recorded.at("steps"), plain.at("steps"));
  EXPECT_EQ(recorded.at("positions"), plain.at("positions"));
}

// A mesh whose file scatters neighbours is renumbered at load; the recording
// and the cache's mesh are in the file's vertex order all the same.
TEST_F(CliRecord, AShuffledMeshIsRecordedInTheFilesVertexOrder) {
  const test::ShuffledGrid sg = test::shuffled_grid(10, 0.05);
  const ClothTopology& grid = sg.grid;
  const auto& order = sg.order;
  const auto& vertex_of = sg.vertex_of;
  const int n = static_cast<int>(grid.rest_positions.size());
  write_obj_mesh(sg.shuffled, (dir_ / "shuffled.obj").string());
  const json scene = {
      {"cloth",
       {{"mesh", {{"obj", "shuffled.obj"}}},
        {"springs", {"structural", "bend"}},
        {"pins", {vertex_of[0], vertex_of[9]}}}},
      {"material",
       {{"spring_constant", 200.0}, {"node_mass", 0.01}, {"viscosity", 0.05}, {"friction", 0}}},
      {"gravity", {0, -9.81, 0}},
      {"solver", {{"integrator", "network"}, {"dt", 0.001}, {"adaptive", false}}}};
  const std::string path = write("shuffled.json", scene.dump());
  ASSERT_FALSE(load_scene(path).topology.numbering.identity()) << "the test needs a renumbering";

  const Outcome r = run({"simulate", path, "--seconds", "0.2", "--out", result_path(), "--record",
                         out("m.motion"), "--record-fps", "30", "--export-pc2", out("m.pc2")});
  ASSERT_EQ(r.code, kOk) << r.err;
  const ReferenceMotion m = read_reference(out("m.motion"), n);
  ASSERT_EQ(m.frames.size(), 7u);
  // Frame 0: vertex k of the file where the file put it (to the OBJ reader's
  // rounding; tinyobjloader's decimal parser is not strtod).
  for (int k = 0; k < n; ++k)
    ASSERT_LT((m.frames[0].positions[k] - grid.rest_positions[order[k]]).norm(), 1e-15)
        << "file vertex " << k;
  expect_positions(m.frames.back(), read_result().at("positions"));
  // The pinned vertices stayed, by file index.
  for (int pin : {vertex_of[0], vertex_of[9]})
    EXPECT_EQ(m.frames.back().positions[pin], m.frames[0].positions[pin]);
  // The cache's mesh is the input file's vertex order.
  const std::string obj = read_text(out("m.obj"));
  std::size_t at = 0;
  for (int k = 0; k < n; ++k) {
    double x, y, z;
    ASSERT_EQ(std::sscanf(obj.c_str() + at, "v %lf %lf %lf", &x, &y, &z), 3);
    EXPECT_LT((Vec3(x, y, z) - grid.rest_positions[order[k]]).norm(), 1e-15) << "vertex " << k;
    at = obj.find('\n', at) + 1;
  }
}

TEST_F(CliRecord, ADivergedRunRecordsUpToTheLastGoodStateAndSaysSo) {
  const Outcome r =
      run({"simulate", scene_asset("hanging"), "--integrator", "explicit_euler", "--dt", "0.004",
           "--seconds", "2", "--out", result_path(), "--record", out("d.motion")});
  ASSERT_EQ(r.code, kDiverged) << r.err;
  EXPECT_NE(r.out.find("the frames stop at the last good state"), std::string::npos) << r.out;
  const json doc = read_result();
  const ReferenceMotion m = read_reference(out("d.motion"), 400);
  ASSERT_FALSE(m.frames.empty());
  EXPECT_LE(m.frames.back().time, doc.at("time").get<double>());
  EXPECT_EQ(doc.at("motion").at("frames").get<std::size_t>(), m.frames.size());
}

TEST_F(CliRecord, BadOptionsWriteNothing) {
  const std::vector<std::string> base = {
      "simulate", scene_asset("hanging"), "--seconds", "0.1",
      "--out",    result_path(),          "--record",  out("r.motion")};
  for (const char* fps : {"0", "-1", "nan", "inf", "10001"}) {
    std::vector<std::string> args = base;
    args.insert(args.end(), {"--record-fps", fps});
    expect_input_error(args, {"--record-fps"});
  }
  expect_input_error({"simulate", scene_asset("hanging"), "--seconds", "0.1", "--out",
                      result_path(), "--record-fps", "30"},
                     {"--record-fps"});
  expect_input_error({"simulate", scene_asset("hanging"), "--seconds", "0.1", "--out",
                      result_path(), "--record", (dir_ / "no/such/dir/r.motion").string()},
                     {"no/such/dir/r.motion"});
  expect_input_error({"simulate", scene_asset("hanging"), "--seconds", "0.1", "--out",
                      result_path(), "--export-pc2", out("run.mdd")},
                     {"--export-pc2", ".pc2"});
  expect_input_error({"simulate", scene_asset("hanging"), "--seconds", "0.1", "--out",
                      result_path(), "--record", result_path()},
                     {"two outputs"});
  // More frames than a recording may hold: refused before the run.
  expect_input_error({"simulate", scene_asset("hanging"), "--seconds", "1e6", "--out",
                      result_path(), "--record", out("r.motion"), "--record-fps", "10000"},
                     {"--record", "node positions"});
}

// An output over an input, or onto a folder: refused before the run. The scene
// itself used to be replaced by the recording (and a folder failed only once
// the whole run was done).
TEST_F(CliRecord, AnOutputOverTheSceneOrOntoAFolderIsRefused) {
  const std::string scene = write("scene.json", read_text(scene_asset("chain")));
  const std::string folder = out("folder.pc2");
  for (const auto& [option, path, mention] :
       std::vector<std::tuple<std::string, std::string, std::string>>{
           {"--record", scene, "reads"},
           {"--record", (dir_ / "." / "scene.json").string(), "reads"},
           {"--record", folder, "folder"},
           {"--export-pc2", folder, "folder"}}) {
    fs::create_directories(folder);
    const Outcome r =
        run({"simulate", scene, "--seconds", "0.05", "--out", result_path(), option, path});
    EXPECT_EQ(r.code, kInputError) << option << " " << path << ": " << r.err;
    EXPECT_NE(r.err.find(option), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(mention), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(result_path()));
    EXPECT_EQ(read_text(scene), read_text(scene_asset("chain")));
    fs::remove_all(folder);
    EXPECT_TRUE(files_in_out_dir().empty());
  }
}

// RESULT.json over the scene (simulate, relax) used to replace the scene; two
// outputs spelled differently for one file used to pass.
TEST_F(CliRecord, AResultOverTheSceneOrTwoSpellingsOfOneOutputAreRefused) {
  const std::string scene = write("scene.json", read_text(scene_asset("chain")));
  for (const char* command : {"simulate", "relax"}) {
    std::vector<std::string> args = {command, scene, "--out", (dir_ / "." / "scene.json").string()};
    if (std::string(command) == "simulate") args.insert(args.end(), {"--seconds", "0.05"});
    const Outcome r = run(args);
    EXPECT_EQ(r.code, kInputError) << command << ": " << r.err;
    EXPECT_NE(r.err.find("--out"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("reads"), std::string::npos) << r.err;
    EXPECT_EQ(read_text(scene), read_text(scene_asset("chain")));
  }
  const Outcome r = run({"simulate", scene, "--seconds", "0.05", "--out", result_path(), "--record",
                         out("a.pc2"), "--export-pc2", (out_dir() / "." / "a.pc2").string()});
  EXPECT_EQ(r.code, kInputError) << r.err;
  EXPECT_NE(r.err.find("two outputs"), std::string::npos) << r.err;
  EXPECT_TRUE(files_in_out_dir().empty());
}

}  // namespace
}  // namespace neurocloth::cli_test
