#include "app/viewer/viewer_frame_stats.h"

#include <algorithm>

namespace neurocloth {

void FrameStats::frame(double elapsed, double frame_seconds) {
  ++frames_;
  if (elapsed >= warmup_) frame_seconds_.push_back(frame_seconds);
}

void FrameStats::sample(double elapsed, const SimulationStatus& status) {
  if (elapsed < warmup_) return;
  steps_per_second_.push_back(status.steps_per_second);
  realtime_ratio_.push_back(status.realtime_ratio);
}

double FrameStats::median_fps() const {
  const double m = median(frame_seconds_);
  return m > 0 ? 1 / m : 0;
}

double FrameStats::median(std::vector<double> v) {
  if (v.empty()) return 0;
  const auto mid = v.begin() + v.size() / 2;
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

}  // namespace neurocloth
