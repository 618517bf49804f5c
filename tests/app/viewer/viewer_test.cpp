// The window, run as a user would under its own Xvfb: scripted sessions drive
// the same input handlers as a mouse, and the report says what the simulation
// showed (positions from its snapshots, values from its status), not what the
// picture looked like.
#include <algorithm>
#include <array>
#include <set>
#include <string>

#include "core/io/asset_paths.h"
#include "core/scene/scene.h"
#include "core/simulation/simulation.h"
#include "render/orbit_camera.h"
#include "render/renderer.h"
#include "support/viewer_fixture.h"
#include "tradeoff/accuracy_choice.h"
#include "tradeoff/trade_csv.h"

namespace neurocloth::viewer_test {
namespace {

constexpr int kWidth = 1280, kHeight = 720;
constexpr double kControlWidth = 400;  // the ImGui controls cover the left of the window

Vec3 position(const json& at) {
  return {at.at(0).get<double>(), at.at(1).get<double>(), at.at(2).get<double>()};
}

// Where `p` appears in the window with the default camera: the same OrbitCamera
// math the window uses, so the test needs no knowledge of the picture.
std::array<double, 2> pixel_of(const Vec3& p) {
  std::array<double, 2> px{-1, -1};
  EXPECT_TRUE(OrbitCamera().project(p, kWidth, kHeight, px[0], px[1]));
  return px;
}

// The hanging cloth's node on its free edge, mid-way between the pins: it has
// the room to be pulled, and its rest pixel is clear of the controls.
struct Target {
  int node;
  std::array<double, 2> pixel;
};
Target free_edge_node(int quarter = 2) {
  const Scene scene = load_scene(scene_asset("hanging"));
  const int node =
      (scene.topology.rows - 1) * scene.topology.cols + quarter * scene.topology.cols / 4;
  const auto pixel = pixel_of(scene.topology.rest_positions.at(node));
  EXPECT_GT(pixel[0], kControlWidth + 20) << "test bug: pick a node the controls do not cover";
  EXPECT_LT(pixel[0], kWidth - 20);
  EXPECT_GT(pixel[1], 20);
  EXPECT_LT(pixel[1], kHeight - 20);
  return {node, pixel};
}

json move(double t, double x, double y, double duration = 0) {
  json e = {{"t", t}, {"type", "move"}, {"x", x}, {"y", y}};
  if (duration > 0) e["duration"] = duration;
  return e;
}
json button(double t, const char* type, const char* which) {
  return {{"t", t}, {"type", type}, {"button", which}};
}
json key(double t, const char* name) {
  return {{"t", t}, {"type", "key"}, {"key", name}};
}
json probe(double t, int node) {
  return {{"t", t}, {"type", "probe"}, {"node", node}};
}
json quit(double t) {
  return {{"t", t}, {"type", "quit"}};
}

// The default, wall-clock mode as a user starts it. How far the simulation gets
// in a wall second depends on the machine, so only what does not is checked;
// the lockstep tests below check what the simulation does.
TEST_F(Viewer, OpensTheDefaultSceneAndAScriptedRunExitsZero) {
  SKIP_WITHOUT_XVFB();
  const std::string script = write_script("script.json", {move(0.2, 800, 300), quit(1.0)});
  const Outcome r = run({"--script", script, "--report", path("report.json").string()});
  ASSERT_EQ(r.code, 0) << r.err;
  const json report = json::parse(read_text(path("report.json")));
  EXPECT_EQ(report["status"]["scene_name"], "table_drape");
  // Its material is in words: the Material panel shows their sliders.
  EXPECT_EQ(report["status"]["material_inputs"],
            json({{"elasticity", 0.35}, {"force", 1.0}, {"mass", 1.5}}));
  // The first frame, the move's and the quit's: one time stamp per frame.
  EXPECT_GE(report["frames"]["drawn"].get<long>(), 2);
  EXPECT_FALSE(report["status"]["paused"].get<bool>());
  EXPECT_TRUE(report["errors"].empty()) << report["errors"].dump();
}

// --lockstep: from Space on, the simulation runs exactly the script's time (a
// probe at script time t sees it at t - 0.2 s, to within the one step that does
// not fit yet: hanging steps 1 ms), and the same script run twice gives the
// same cloth bit for bit, drag and pin included. Started paused, so the pin
// and the press meet the nodes where the scene puts them; each press comes a
// frame after its move (the controls decide from the cursor's last frame
// whether a click is theirs).
TEST_F(Viewer, UnderLockstepScriptTimesAreSimulatedSecondsAndARunRepeatsExactly) {
  SKIP_WITHOUT_XVFB();
  const Target target = free_edge_node(), pin = free_edge_node(3);
  const double x = target.pixel[0], y = target.pixel[1];
  const double start = 0.2;  // Space
  const json events = {move(0.02, pin.pixel[0], pin.pixel[1]),
                       button(0.05, "press", "right"),
                       button(0.05, "release", "right"),
                       move(0.1, x, y),
                       button(0.15, "press", "left"),
                       key(start, "space"),
                       move(start, x - 80, y - 120, 0.25),
                       probe(0.5, target.node),
                       button(0.6, "release", "left"),
                       probe(1.0, target.node),
                       probe(1.0, pin.node),
                       quit(1.1)};
  const json first = session(scene_asset("hanging"), events, {"--paused"}, "first");
  const json second = session(scene_asset("hanging"), events, {"--paused"}, "second");
  ASSERT_EQ(first["probes"].size(), 3u) << first.dump(1);
  const double dt = 1e-3;  // hanging.json
  for (const json& p : first["probes"]) {
    const double ran = p["t"].get<double>() - start, time = p["time"].get<double>();
    EXPECT_LE(time, ran + 1e-12) << "never ahead of the script";
    EXPECT_GE(time, ran - dt - 1e-9) << "behind the script by one step at most";
  }
  ASSERT_EQ(first["drags"].size(), 1u) << first.dump(1);
  EXPECT_EQ(first["drags"][0]["node"], target.node);
  ASSERT_EQ(first["pins"].size(), 1u) << first.dump(1);
  EXPECT_EQ(first["pins"][0]["node"], pin.node);
  EXPECT_TRUE(first["probes"][2]["pinned"].get<bool>());
  EXPECT_EQ(first["probes"], second["probes"]);
  EXPECT_EQ(first["drags"], second["drags"]);
  EXPECT_EQ(first["pins"], second["pins"]);
  EXPECT_EQ(first["status"]["time"], second["status"]["time"]);
  EXPECT_EQ(first["status"]["steps"], second["status"]["steps"]);
}

// Started paused, so the node is where the scene puts it when the press comes;
// Space then lets it go with the cursor pulling on the node. Where the node
// would be without the pull comes from the core run alone to the very
// simulated time of the probe. Under --lockstep the cursor follows the cloth
// frame by frame in simulated time, so the pull is the same on any machine.
TEST_F(Viewer, DraggingANodePullsItTowardsTheCursor) {
  SKIP_WITHOUT_XVFB();
  const Target target = free_edge_node();
  const double x = target.pixel[0], y = target.pixel[1];
  const json dragged = session(scene_asset("hanging"),
                               {move(0.2, x, y), button(0.3, "press", "left"), key(0.4, "space"),
                                move(0.4, x + 100, y - 150, 0.3), probe(1.4, target.node),
                                button(1.5, "release", "left"), quit(1.6)},
                               {"--paused"}, "dragged");
  ASSERT_EQ(dragged["picks"].size(), 1u) << dragged.dump(1);
  EXPECT_EQ(dragged["picks"][0]["node"], target.node);
  ASSERT_EQ(dragged["drags"].size(), 1u);
  const json& drag = dragged["drags"][0];
  ASSERT_TRUE(drag.contains("release")) << drag.dump();
  EXPECT_EQ(dragged["status"]["commands_refused"], 0);

  const json& probe = dragged["probes"][0];
  const double t = probe["time"].get<double>();
  // Space at 0.4 s, the probe at 1.4 s: one simulated second ran (in 1 ms steps).
  ASSERT_NEAR(t, 1.0, 1e-3) << "the cloth ran from Space to the probe";
  Simulation alone = load_scene(scene_asset("hanging")).make_simulation();
  ASSERT_EQ(alone.advance(t), RunStatus::ok);
  const Vec3 free = alone.state().position(static_cast<std::size_t>(target.node));
  const Vec3 pulled = position(probe["position"]);
  const Vec3 cursor = position(drag["target"]);
  // Left alone the free edge swings down and under the pins; pulled, the node
  // ends far nearer the point the cursor pulled it towards, moved its way.
  EXPECT_LT((pulled - cursor).norm(), 0.6 * (free - cursor).norm())
      << "at t = " << t << " s: pulled " << pulled.transpose() << ", free " << free.transpose()
      << ", cursor " << cursor.transpose();
  const double cosine =
      (pulled - free).dot(cursor - free) / ((pulled - free).norm() * (cursor - free).norm());
  EXPECT_GT(cosine, 0.5) << "moved towards the cursor";
}

TEST_F(Viewer, RightClickPinsTheNodeUnderTheCursor) {
  SKIP_WITHOUT_XVFB();
  const Target target = free_edge_node();
  const double x = target.pixel[0], y = target.pixel[1];
  const json report =
      session(scene_asset("hanging"),
              {move(0.2, x, y), button(0.3, "press", "right"), button(0.35, "release", "right"),
               key(0.5, "space"), probe(1.2, target.node), quit(1.3)},
              {"--paused"});
  ASSERT_EQ(report["pins"].size(), 1u) << report.dump(1);
  EXPECT_EQ(report["pins"][0]["node"], target.node);
  EXPECT_TRUE(report["pins"][0]["pinned"].get<bool>());
  EXPECT_TRUE(report["probes"][0]["pinned"].get<bool>());
  // Pinned where it was: it did not fall with the rest of the free edge.
  const Scene scene = load_scene(scene_asset("hanging"));
  EXPECT_LT((position(report["probes"][0]["position"]) - scene.topology.rest_positions[target.node])
                .norm(),
            1e-6);
}

TEST_F(Viewer, ASetEventReachesTheSimulationAndAnOutOfRangeOneIsRefused) {
  SKIP_WITHOUT_XVFB();
  const json report = session(scene_asset("table_drape"),
                              {{{"t", 0.2}, {"type", "set"}, {"name", "viscosity"}, {"value", 0.5}},
                               {{"t", 0.3}, {"type", "set"}, {"name", "viscosity"}, {"value", -3}},
                               quit(0.8)});
  ASSERT_EQ(report["sets"].size(), 2u);
  EXPECT_TRUE(report["sets"][0]["accepted"].get<bool>());
  EXPECT_EQ(report["status"]["viscosity"], 0.5) << "the status shows the value asked for";
  EXPECT_FALSE(report["sets"][1]["accepted"].get<bool>());
  const std::string refusal = report["sets"][1]["refusal"];
  EXPECT_NE(refusal.find("valid range"), std::string::npos) << refusal;
  ASSERT_FALSE(report["errors"].empty()) << "the refusal is shown as an error line";
}

// The Solver panel's accuracy slider, driven as a script's "set": the
// simulation runs with the setting the scene's measured trade picks (read from
// its status), and an accuracy finer than the trade vouches for is refused.
TEST_F(Viewer, AnAccuracyRequestRunsThePickedSettingAndATooFineOneIsRefused) {
  SKIP_WITHOUT_XVFB();
  const Scene scene = load_scene(scene_asset("hanging"));
  const std::string trade_path = committed_trade_path(scene.path);
  const AccuracyChoice expected =
      choose_for_accuracy(read_trade_csv(trade_path), trade_path, 0.01, scene.solver);
  const json report =
      session(scene_asset("hanging"),
              {{{"t", 0.2}, {"type", "set"}, {"name", "accuracy"}, {"value", 0.01}},
               {{"t", 0.3}, {"type", "set"}, {"name", "accuracy"}, {"value", 1e-12}},
               quit(0.8)});
  ASSERT_EQ(report["sets"].size(), 2u);
  EXPECT_TRUE(report["sets"][0]["accepted"].get<bool>()) << report["sets"].dump();
  EXPECT_EQ(report["status"]["integrator"], to_string(expected.settings.integrator));
  EXPECT_EQ(report["status"]["dt"].get<double>(), expected.settings.dt);
  EXPECT_EQ(report["status"]["adaptive"].get<bool>(), expected.settings.adaptive);
  EXPECT_FALSE(report["sets"][1]["accepted"].get<bool>());
  const std::string refusal = report["sets"][1]["refusal"];
  EXPECT_NE(refusal.find("hanging.csv"), std::string::npos) << refusal;
  EXPECT_EQ(report["status"]["run"], "ok");
}

TEST_F(Viewer, ALinguisticInputReachesTheSimulation) {
  SKIP_WITHOUT_XVFB();
  const json report =
      session(scene_asset("hanging_fuzzy"),
              {{{"t", 0.2}, {"type", "set"}, {"name", "input.mass"}, {"value", 0.8}}, quit(0.6)});
  ASSERT_EQ(report["sets"].size(), 1u);
  EXPECT_TRUE(report["sets"][0]["accepted"].get<bool>()) << report["sets"].dump();
  EXPECT_EQ(report["status"]["material_inputs"]["mass"], 0.8);
}

TEST_F(Viewer, ScreenshotsAreWrittenAtTheWindowSize) {
  SKIP_WITHOUT_XVFB();
  const json report = session(
      scene_asset("table_drape"),
      {key(0.5, "F12"), {{"t", 0.7}, {"type", "screenshot"}, {"path", "shot.png"}}, quit(1.0)});
  ASSERT_EQ(report["screenshots"].size(), 2u) << report.dump(1);
  EXPECT_EQ(report["screenshots"][1]["path"], "shot.png");
  for (const json& shot : report["screenshots"]) {
    const fs::path file = path(shot["path"].get<std::string>());
    ASSERT_TRUE(fs::exists(file)) << file;
    int width = 0, height = 0;
    const std::vector<std::uint8_t> rgba = read_png(file.string(), width, height);
    EXPECT_EQ(width, kWidth);
    EXPECT_EQ(height, kHeight);
    std::set<std::uint32_t> colours;
    for (std::size_t i = 0; i + 3 < rgba.size() && colours.size() < 16; i += 4 * 97)
      colours.insert(rgba[i] | rgba[i + 1] << 8 | rgba[i + 2] << 16);
    EXPECT_GE(colours.size(), 4u) << file << " is (nearly) one colour";
  }
}

// A minimised window reports 0 x 0: nothing is drawn, nothing crashes, and the
// simulation goes on meanwhile.
TEST_F(Viewer, AMinimisedWindowDrawsNothingAndTheSimulationGoesOn) {
  SKIP_WITHOUT_XVFB();
  const json report =
      session(scene_asset("hanging"),
              {{{"t", 0.2}, {"type", "resize"}, {"width", 0}, {"height", 0}},
               probe(0.3, 0),
               probe(1.3, 0),
               {{"t", 1.4}, {"type", "resize"}, {"width", kWidth}, {"height", kHeight}},
               {{"t", 1.6}, {"type", "screenshot"}, {"path", "after.png"}},
               quit(1.9)});
  // Frames at 0.2, 0.2 + 1/60, ... up to the one before 1.4 s: 72 frames of 1/60 s.
  EXPECT_EQ(report["frames"]["skipped"].get<long>(), 72);
  const double minimised =
      report["probes"][1]["time"].get<double>() - report["probes"][0]["time"].get<double>();
  EXPECT_NEAR(minimised, 1.0, 1e-3) << "the simulation ran the whole second minimised";
  EXPECT_TRUE(fs::exists(path("after.png"))) << "drawing resumes";
}

TEST_F(Viewer, BadInputIsShownAndTheSceneKeepsRunning) {
  SKIP_WITHOUT_XVFB();
  write("broken_scene.json", "{ \"name\": \"broken\", \"cloth\": { \"grid\": 3 } }");
  const json report = session(scene_asset("table_drape"),
                              {{{"t", 0.2}, {"type", "load"}, {"path", "broken_scene.json"}},
                               {{"t", 0.3}, {"type", "load"}, {"path", "no_such_scene.json"}},
                               probe(0.4, 0),
                               probe(1.0, 0),
                               quit(1.1)});
  ASSERT_GE(report["errors"].size(), 2u) << report.dump(1);
  EXPECT_NE(report["errors"][0]["message"].get<std::string>().find("broken_scene.json"),
            std::string::npos);
  EXPECT_EQ(report["status"]["scene_name"], "table_drape");
  // table_drape steps in refresh intervals of 0.04 s: 0.6 s apart, to within one.
  EXPECT_NEAR(report["probes"][1]["time"].get<double>() - report["probes"][0]["time"].get<double>(),
              0.6, 0.04 + 1e-9)
      << "the scene kept running";
}

TEST_F(Viewer, ABrokenRuleBaseIsNamedAndTheMaterialKeepsRunning) {
  SKIP_WITHOUT_XVFB();
  write("broken.fcl", "FUNCTION_BLOCK broken\nVAR_INPUT\n  mass REAL;\nEND_VAR\n");
  const json report =
      session(scene_asset("hanging_fuzzy"),
              {{{"t", 0.2}, {"type", "rules"}, {"path", "broken.fcl"}}, probe(0.3, 0), quit(0.6)});
  ASSERT_EQ(report["errors"].size(), 1u) << report.dump(1);
  const std::string error = report["errors"][0]["message"];
  EXPECT_NE(error.find("broken.fcl:3"), std::string::npos) << error;
  EXPECT_EQ(report["status"]["run"], "ok");
  EXPECT_EQ(report["status"]["material_inputs"]["mass"], 0.2) << "the scene's own inputs";
}

TEST_F(Viewer, WithoutADisplayItSaysSoInOneLineNamingTheSnapshotCommand) {
  const Outcome r = run({}, /*display=*/false);
  EXPECT_NE(r.code, 0);
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find("neurocloth-cli snapshot"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--out FILE.png"), std::string::npos) << r.err;
}

// --sim-only needs no display. A run too short to sample past its warm-up
// says so rather than printing a median of nothing as "0 steps/s" (the loop
// samples every 16 ms, so 10 ms never reaches a sample however fast the machine).
TEST_F(Viewer, ASimOnlyRunTooShortToMeasureSaysSo) {
  const Outcome r = run({"--size", "8", "--sim-only", "0.01"}, /*display=*/false);
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("too short to measure"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("0 steps/s"), std::string::npos) << r.out;
}

// A script is read before any window opens, so these need no display.
TEST_F(Viewer, ABrokenScriptIsNamedWithItsFieldAndLine) {
  const std::string script = write("bad.json",
                                   "{\n"
                                   "  \"events\": [\n"
                                   "    {\"t\": 0.1, \"type\": \"press\", \"button\": \"lefty\"}\n"
                                   "  ]\n"
                                   "}\n");
  const Outcome r = run({scene_asset("table_drape"), "--script", script}, false);
  EXPECT_EQ(r.code, 1);
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find("bad.json:3"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("events[0].button"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("left, right, middle"), std::string::npos) << r.err;

  const std::string malformed = write("malformed.json", "{\"events\": [\n  {\"t\": 1,}\n]}\n");
  const Outcome m = run({scene_asset("table_drape"), "--script", malformed}, false);
  EXPECT_EQ(m.code, 1);
  EXPECT_NE(m.err.find("malformed.json:2"), std::string::npos) << m.err;

  const std::string unordered = write_script("unordered.json", {quit(1.0), move(0.5, 1, 1)});
  const Outcome u = run({scene_asset("table_drape"), "--script", unordered}, false);
  EXPECT_EQ(u.code, 1);
  EXPECT_NE(u.err.find("events[1].t"), std::string::npos) << u.err;
  EXPECT_NE(u.err.find("time order"), std::string::npos) << u.err;
}

}  // namespace
}  // namespace neurocloth::viewer_test
