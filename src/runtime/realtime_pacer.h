#pragma once
// Keeping simulated time in step with the wall clock, and measuring how well
// that goes. Times are plain seconds (wall time from any steady origin) so the
// rules can be tested without a clock.
#include <deque>

namespace neurocloth {

// Simulated time against wall time from a sync point (as MuJoCo's simulate
// does): the simulation owes whatever wall time passed since the sync point that
// it has not simulated yet.
class RealtimePacer {
 public:
  // `max_lag`: how far behind the wall clock the simulation may fall (s) before
  // it stops trying to catch up.
  explicit RealtimePacer(double max_lag) : max_lag_(max_lag) {}
  // From now on `sim_time` corresponds to `wall`: nothing is owed (after a
  // pause, a reset, a new scene).
  void sync(double wall, double sim_time);
  // Simulated seconds owed at `wall` (negative when ahead).
  double owed(double wall, double sim_time) const;
  // Whole steps of `dt` to take now, at most `max_steps` (one slice). When more
  // than max_lag is owed the debt is dropped but for one slice (a re-sync): a
  // simulation that cannot keep up runs at its own pace rather than chasing a
  // clock it cannot catch, which would only make every slice longer.
  int plan(double wall, double sim_time, double dt, int max_steps);
  long resyncs() const { return resyncs_; }
  double last_resync() const { return last_resync_; }  // wall time; -inf if never

 private:
  double max_lag_;
  double sync_wall_ = 0, sync_sim_ = 0;
  long resyncs_ = 0;
  double last_resync_ = -1e300;
};

// Rates over the last `span` seconds of wall time, from samples taken as the run goes.
class RateWindow {
 public:
  explicit RateWindow(double span = 1.0) : span_(span) {}
  void add(double wall, double sim_time, long steps);
  void clear() { samples_.clear(); }
  double covered() const;  // wall seconds between the oldest and newest sample
  // Simulated seconds per wall second (1 while the window is too short to tell).
  double realtime_ratio() const;
  double steps_per_second() const;  // 0 while too short to tell

 private:
  struct Sample {
    double wall, sim_time;
    long steps;
  };
  double span_;
  std::deque<Sample> samples_;
};

}  // namespace neurocloth
