#pragma once
// How fast the window draws and the simulation steps while it does: medians
// over the run after a warm-up, for the report and docs/viewer.md.
#include <vector>

#include "runtime/simulation_thread.h"

namespace neurocloth {

class FrameStats {
 public:
  // Samples taken in the first `warmup` seconds (shader compiles, the first
  // fall of the cloth) are left out of the medians.
  explicit FrameStats(double warmup = 1.0) : warmup_(warmup) {}

  void frame(double elapsed, double frame_seconds);  // one drawn frame
  void skipped() { ++skipped_; }                     // not drawn: the window is minimised
  void sample(double elapsed, const SimulationStatus& status);

  long frames() const { return frames_; }
  long skipped_frames() const { return skipped_; }
  double median_fps() const;
  double median_steps_per_second() const { return median(steps_per_second_); }
  double median_realtime_ratio() const { return median(realtime_ratio_); }
  // Simulation samples past the warm-up: none means the medians say nothing.
  std::size_t simulation_samples() const { return steps_per_second_.size(); }

 private:
  static double median(std::vector<double> v);
  double warmup_;
  long frames_ = 0, skipped_ = 0;
  std::vector<double> frame_seconds_, steps_per_second_, realtime_ratio_;
};

}  // namespace neurocloth
