#include "runtime/realtime_pacer.h"

#include <algorithm>
#include <cmath>

namespace neurocloth {

namespace {
constexpr double kShortest = 0.05;  // s of wall time: below this a rate is noise
}

void RealtimePacer::sync(double wall, double sim_time) {
  sync_wall_ = wall;
  sync_sim_ = sim_time;
}

double RealtimePacer::owed(double wall, double sim_time) const {
  return sync_sim_ + (wall - sync_wall_) - sim_time;
}

int RealtimePacer::plan(double wall, double sim_time, double dt, int max_steps) {
  const double slice = max_steps * dt;
  if (owed(wall, sim_time) > max_lag_) {
    sync(wall - slice, sim_time);  // as if in step one slice ago: run that slice now
    ++resyncs_;
    last_resync_ = wall;
  }
  // A step owed to within round-off is owed: wall time is not a multiple of dt.
  const double steps = std::floor(owed(wall, sim_time) / dt + 1e-9);
  return static_cast<int>(std::clamp(steps, 0.0, static_cast<double>(max_steps)));
}

void RateWindow::add(double wall, double sim_time, long steps) {
  // A time going back (a reset) starts a new window.
  if (!samples_.empty() && sim_time < samples_.back().sim_time) samples_.clear();
  samples_.push_back({wall, sim_time, steps});
  // Keep one sample at least `span_` old, so the window always covers the span.
  while (samples_.size() > 2 && samples_[1].wall <= wall - span_)
    samples_.pop_front();
}

double RateWindow::covered() const {
  return samples_.size() < 2 ? 0.0 : samples_.back().wall - samples_.front().wall;
}

double RateWindow::realtime_ratio() const {
  const double wall = covered();
  if (wall < kShortest) return 1.0;
  return (samples_.back().sim_time - samples_.front().sim_time) / wall;
}

double RateWindow::steps_per_second() const {
  const double wall = covered();
  if (wall < kShortest) return 0.0;
  return (samples_.back().steps - samples_.front().steps) / wall;
}

}  // namespace neurocloth
