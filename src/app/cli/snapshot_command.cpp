// `neurocloth-cli snapshot`: a scene after some simulated time, rendered to a
// PNG through OSMesa with the window's renderer. Needs no display.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>

#include "app/cli/commands.h"
#include "app/cli/long_run.h"
#include "core/io/input_error.h"
#include "core/scene/frame_snapshot.h"
#include "core/scene/scene.h"
#include "render/orbit_camera.h"
#include "render/osmesa_context.h"
#include "render/renderer.h"
#include "render/snapshot_framing.h"

namespace neurocloth {
namespace {

// "1280x720" -> 1280, 720; anything else is an InputError naming --size and the form.
void parse_size(const std::string& text, int& width, int& height) {
  const int max = OsmesaContext::max_size();
  const std::string form =
      "expected WIDTHxHEIGHT in pixels, e.g. 1280x720, each 1 to " + std::to_string(max);
  const std::size_t x = text.find('x');
  auto number = [&](const std::string& s) {
    if (s.empty() || s.size() > 6 || s.find_first_not_of("0123456789") != std::string::npos)
      throw InputError("command line", "--size", "'" + text + "': " + form);
    return std::atoi(s.c_str());
  };
  if (x == std::string::npos) throw InputError("command line", "--size", "'" + text + "': " + form);
  width = number(text.substr(0, x));
  height = number(text.substr(x + 1));
  if (width < 1 || height < 1 || width > max || height > max)
    throw InputError("command line", "--size", "'" + text + "': " + form);
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

int run_snapshot(const SnapshotOptions& o) {
  // Everything on the command line is checked before the (possibly long) run.
  if (!(o.seconds >= 0) || !std::isfinite(o.seconds))
    throw InputError("command line", "--seconds", "must be a finite number >= 0");
  int width = 0, height = 0;
  parse_size(o.size, width, height);
  if (o.strain_max && !(*o.strain_max > 0 && std::isfinite(*o.strain_max)))
    throw InputError("command line", "--strain-max", "must be a finite number > 0, e.g. 0.1");
  if (o.camera) {
    try {
      parse_camera(*o.camera);
    } catch (const std::invalid_argument& e) {
      throw InputError("command line", "--camera", e.what());
    }
  }
  const std::filesystem::path out(o.out);
  const std::filesystem::path folder = out.has_parent_path() ? out.parent_path() : ".";
  std::error_code ec;
  if (!std::filesystem::is_directory(folder, ec))
    throw InputError("command line", "--out", "folder '" + folder.string() + "' does not exist");

  const Scene scene = load_scene(o.scene);
  Simulation sim = scene.make_simulation();
  const LongRunOutcome run = run_long(sim, o.seconds);
  sim.check_result();
  const double sim_wall = run.wall_seconds;

  FrameSnapshot snapshot;
  snapshot.geometry = make_geometry(scene);
  capture(sim, snapshot);
  const double aspect = double(width) / height;
  OrbitCamera camera = framing_camera(snapshot, aspect);
  if (o.camera) camera = parse_camera(*o.camera, camera.target);

  RenderOptions options;
  options.wireframe = o.wireframe;
  options.springs = o.springs;
  options.nodes = o.nodes;
  options.strain = o.strain;
  if (o.strain_max) options.strain_max = float(*o.strain_max);

  const auto render_start = std::chrono::steady_clock::now();
  OsmesaContext context(width, height);
  Renderer renderer;
  renderer.draw(snapshot, camera, options, width, height);
  const std::vector<std::uint8_t> rgba = renderer.read_pixels(width, height);
  const double render_wall = seconds_since(render_start);
  try {
    write_png(o.out, rgba, width, height);
  } catch (const std::runtime_error& e) {
    throw InputError(o.out, "--out", e.what());
  }

  std::printf("%s: %s at t = %.4g s, %dx%d, camera %.4g,%.4g,%.4g,%.4g,%.4g,%.4g\n",
              scene.name.c_str(), to_string(sim.status()), sim.time(), width, height, camera.yaw,
              camera.pitch, camera.distance, camera.target.x(), camera.target.y(),
              camera.target.z());
  if (o.verbose) {
    std::printf("  OpenGL: %s\n", context.renderer_string().c_str());
    std::printf("  simulation %.3g s wall, context + render + read back %.3g s wall\n", sim_wall,
                render_wall);
  }
  if (sim.status() != RunStatus::ok)
    std::printf("  diverged: %s; drew the last good state (t = %.4g s)\n",
                sim.divergence_reason().c_str(), sim.time());
  if (run.interrupted)
    std::printf("  interrupted (Ctrl-C) at t = %.6g s of %.6g s: drew the state reached\n",
                sim.time(), o.seconds);
  std::printf("  wrote %s\n", o.out.c_str());
  if (sim.status() != RunStatus::ok) return kExitDiverged;
  return run.interrupted ? kExitInterrupted : kExitOk;
}

}  // namespace neurocloth
