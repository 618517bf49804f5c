#include "app/viewer/viewer_options.h"

#include <CLI/CLI.hpp>

#include "core/io/asset_paths.h"
#include "core/io/physical_limits.h"

namespace neurocloth {

std::optional<int> parse_viewer_options(int argc, char** argv, ViewerOptions& o) {
  CLI::App app{"neurocloth: the cloth in a window (docs/viewer.md)"};
  app.add_option("scene", o.scene, "Scene file (JSON); default: assets/scenes/table_drape.json");
  app.add_option("--script", o.script, "Replay the timed input events in FILE (JSON), then exit");
  app.add_option("--report", o.report, "Write what happened to FILE (JSON) on exit");
  app.add_option("--size", o.size, "Run the scene's cloth as an N x N grid")
      ->check(CLI::Range(static_cast<int>(limits::kGridSize.low),
                         static_cast<int>(limits::kGridSize.high)));
  app.add_option("--camera", o.camera, "Start camera: yaw,pitch,distance[,tx,ty,tz] (rad, m)");
  app.add_option("--width", o.width, "Window width, px")->check(CLI::Range(64, 16384));
  app.add_option("--height", o.height, "Window height, px")->check(CLI::Range(64, 16384));
  app.add_flag("--paused", o.paused, "Start paused");
  app.add_flag("!--no-vsync", o.vsync, "Do not wait for the display's refresh when swapping");
  app.add_option("--max-fps", o.max_fps, "Frames per second at most; 0: as many as it can draw")
      ->check(CLI::NonNegativeNumber);
  CLI::Option* sim_only =
      app.add_option("--sim-only", o.sim_only,
                     "Run the simulation without a window for SECONDS (speed reference)")
          ->check(CLI::PositiveNumber);
  app.add_flag("--lockstep", o.lockstep,
               "Deterministic: each frame advances the simulation by 1/60 s and waits for it; "
               "script times are simulated seconds (tests, soak runs)")
      ->excludes(sim_only);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? kViewerOk : kViewerUsage;
  }
  if (o.scene.empty()) o.scene = assets_directory() + "/scenes/table_drape.json";
  return std::nullopt;
}

}  // namespace neurocloth
