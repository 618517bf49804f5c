#include "app/viewer/viewer_sim_only.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <thread>

#include "app/viewer/viewer_frame_stats.h"
#include "app/viewer/viewer_report.h"
#include "runtime/simulation_thread.h"

namespace neurocloth {

int run_sim_only(const Scene& shipped, const ViewerOptions& options) {
  using Clock = std::chrono::steady_clock;
  // No window draws beside it: the step may have both cores.
  Scene scene = shipped;
  scene.solver.threads = batch_step_threads(scene.topology.rest_positions.size());
  SimulationThread sim(scene);
  // A run shorter than the window's warm-up still gets its last three quarters measured.
  FrameStats stats(std::min(1.0, 0.25 * *options.sim_only));
  const Clock::time_point start = Clock::now();
  for (;;) {
    // Sampled at about the rate a window would read the status.
    std::this_thread::sleep_for(std::chrono::milliseconds(16));
    const double elapsed = std::chrono::duration<double>(Clock::now() - start).count();
    if (elapsed >= *options.sim_only) break;
    stats.sample(elapsed, sim.status());
  }
  const SimulationStatus status = sim.status();
  if (stats.simulation_samples() == 0)
    std::printf("%s: too short to measure (no status sample after the warm-up), t = %.2f s\n",
                status.scene_name.c_str(), status.time);
  else
    std::printf("%s: %.0f steps/s (median), %.2fx real time, t = %.2f s\n",
                status.scene_name.c_str(), stats.median_steps_per_second(),
                stats.median_realtime_ratio(), status.time);
  if (options.report) {
    try {
      ViewerReport().write(*options.report, status, stats);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "neurocloth: %s\n", e.what());
      return kViewerInputError;
    }
  }
  return kViewerOk;
}

}  // namespace neurocloth
