#pragma once
// The window's command line: `neurocloth [SCENE] [--script FILE] [--report FILE] ...`.
#include <optional>
#include <string>

namespace neurocloth {

// Exit codes of `neurocloth`.
inline constexpr int kViewerOk = 0;
inline constexpr int kViewerInputError = 1;  // scene, script or shader that does not read
inline constexpr int kViewerUsage = 2;
inline constexpr int kViewerNoDisplay = 3;  // no window system to open a window on

struct ViewerOptions {
  std::string scene;                  // default: assets/scenes/table_drape.json
  std::optional<std::string> script;  // replay timed input events, then exit
  std::optional<std::string> report;  // write what happened (JSON) on exit
  std::optional<int> size;            // run the scene's cloth as an N x N grid
  std::optional<std::string> camera;  // "yaw,pitch,distance[,tx,ty,tz]"
  int width = 1280, height = 720;     // window, px
  bool paused = false;                // start paused
  bool vsync = true;                  // off: do not wait for the display's refresh
  // Frames per second at most (0: no cap). Where swapping does not wait for a
  // refresh (Xvfb, some drivers) an uncapped window would take a whole core from
  // the simulation to draw frames no one can see.
  double max_fps = 60;
  // Run the simulation thread alone, without a window, for this many wall
  // seconds (for comparing its speed with and without the window).
  std::optional<double> sim_only;
  // Deterministic: every frame advances the simulation by exactly
  // kLockstepFrame simulated seconds and waits for it, and script times are
  // simulated seconds, so a script does the same on any machine at any load
  // (tests, soak runs). Off: the simulation follows the wall clock.
  bool lockstep = false;
};

// Simulated seconds per frame under --lockstep: a 60 Hz display's frame.
inline constexpr double kLockstepFrame = 1.0 / 60.0;

// Parses argv; on --help or a usage error prints the message and returns the exit code.
std::optional<int> parse_viewer_options(int argc, char** argv, ViewerOptions& options);

}  // namespace neurocloth
