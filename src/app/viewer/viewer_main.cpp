// neurocloth: the cloth in a window. Reads the scene (and script) first, so
// bad input is reported even where no window can open; then opens the window
// and runs the simulation on its own thread (docs/viewer.md).
#include <cstdio>
#include <exception>
#include <optional>
#include <string>

#include "app/viewer/viewer_app.h"
#include "app/viewer/viewer_options.h"
#include "app/viewer/viewer_priority.h"
#include "app/viewer/viewer_script.h"
#include "app/viewer/viewer_sim_only.h"
#include "app/viewer/viewer_window.h"
#include "core/base/cpu_features.h"
#include "core/io/input_error.h"
#include "core/scene/scene.h"
#include "render/orbit_camera.h"
#include "runtime/realtime_pick.h"
#include "runtime/simulation_thread.h"

namespace {

using namespace neurocloth;

// One line, naming what to run instead.
int no_display(const std::string& why, const std::string& scene) {
  std::fprintf(stderr,
               "neurocloth: no display to open a window on (%s); for a picture without one run: "
               "neurocloth-cli snapshot %s --out FILE.png\n",
               why.c_str(), scene.c_str());
  return kViewerNoDisplay;
}

int run(const ViewerOptions& options) {
  Scene scene = load_scene(options.scene);
  if (options.size) scene = resized_grid(scene, *options.size);
  std::optional<Script> script;
  if (options.script) script = load_script(*options.script);
  OrbitCamera camera;
  if (options.camera) camera = parse_camera(*options.camera);
  // A resized cloth may be too fine for the scene's solver to keep real time:
  // then the window (and --sim-only, its speed reference) runs one that can.
  // Not in lockstep: a deterministic run must not depend on this machine.
  RealtimePick pick;
  if (options.size && !options.lockstep) {
    std::fprintf(stderr, "neurocloth: timing the scene's solver at %d x %d nodes...\n",
                 *options.size, *options.size);
    // What the picked settings' error is at this size, if it was measured.
    const SizedTrade trade = find_sized_trade(options.scene, *options.size);
    if (!trade.problem.empty())
      std::fprintf(stderr, "neurocloth: %s (not quoted)\n", trade.problem.c_str());
    // And that it runs through the cloth's first second (a large step can land
    // a fine cloth on the table and stretch it over the edge into a divergence).
    pick = pick_for_real_time(
        scene, [](const Scene& s) { return measure_cost(s, 0.4); }, trade,
        [](const Scene& s) { return runs_sound(s, kSoundSeconds); });
    if (pick.switched) {
      scene.solver = pick.picked;
      std::fprintf(stderr, "neurocloth: %s\n", pick.note.c_str());
    }
  }
  if (options.sim_only) return run_sim_only(scene, options);

  try {
    ViewerWindow::connect();
  } catch (const NoDisplay& e) {
    return no_display(e.what(), options.scene);
  }
  // The simulation's thread first, then this one steps back: the window and the
  // threads the GL driver starts for it (llvmpipe's, without a GPU) then never
  // take a core the simulation wants.
  SimulationThread::Options run;
  run.start_paused = options.paused;
  run.lockstep = options.lockstep;
  SimulationThread sim(scene, run);
  yield_to_simulation();
  ViewerWindow window(options.width, options.height, "neurocloth - " + scene.name, options.vsync);
  ViewerApp app(window, sim, scene, options, camera, std::move(script));
  if (pick.switched) app.set_realtime_pick(pick);
  return app.run();
}

}  // namespace

int main(int argc, char** argv) {
  ViewerOptions options;
  if (const auto code = parse_viewer_options(argc, argv, options)) return *code;
  // A mask of CPU features that cannot be read runs nothing (cpu_features.h).
  if (const std::string cpu = disabled_cpu_features_error(); !cpu.empty()) {
    std::fprintf(stderr, "neurocloth: %s\n", cpu.c_str());
    return kViewerUsage;
  }
  try {
    return run(options);
  } catch (const InputError& e) {
    std::fprintf(stderr, "neurocloth: %s\n", e.what());
    return kViewerInputError;
  } catch (const std::invalid_argument& e) {  // --size on a scene without a grid, --camera
    std::fprintf(stderr, "neurocloth: %s\n", e.what());
    return kViewerUsage;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "neurocloth: %s\n", e.what());
    return kViewerInputError;
  }
}
