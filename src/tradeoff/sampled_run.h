#pragma once
// One run of a scene under given solver settings, with where every node was and
// the total energy at fixed sample times, and what the run cost: the raw
// material of the speed-against-accuracy trade (docs/tradeoff.md).
#include <string>
#include <vector>

#include "core/scene/scene.h"

namespace neurocloth {

struct SampledRun {
  SolverSettings settings;
  // One entry per sample time reached: all of them unless the run diverged.
  std::vector<double> times;
  std::vector<std::vector<double>> positions;  // per sample: x0 y0 z0 x1 y1 z1 ...
  std::vector<double> energy;                  // per sample: total energy, J
  RunStatus status = RunStatus::ok;
  std::string reason;    // why it diverged
  bool stopped = false;  // healthy but behind: it ran out of step budget
  // Inside advance() only, on run_clock (below): what the run costs.
  double cost_seconds = 0;
  int timing_runs = 1;           // cost_seconds is the median of this many identical runs
  double simulated_seconds = 0;  // how far it got
  long steps = 0, rejected_steps = 0, force_evaluations = 0, cg_iterations = 0;

  bool complete(std::size_t samples) const {
    return status == RunStatus::ok && !stopped && times.size() == samples;
  }
};

// The clock a run's cost is read on. With one thread in the step, the running
// thread's CPU time: runs measured side by side (the tradeoff's workers) or
// next to other work on a shared machine are not charged for each other's
// time. With threads inside the step the caller's CPU time would miss its
// helpers' share, so wall time (steady_clock) then.
enum class RunClock { thread_cpu, wall };
RunClock run_clock(const SolverSettings& settings);
const char* to_string(RunClock clock);  // "thread CPU" or "wall"
double now_seconds(RunClock clock);

// `samples` times evenly spaced over (0, seconds], the last one at `seconds`.
std::vector<double> sample_times(double seconds, int samples);

// Runs `scene` with `settings` from its initial state through every time in
// `times` (increasing), recording each; stops at a divergence.
SampledRun run_sampled(const Scene& scene, const SolverSettings& settings,
                       const std::vector<double>& times);

// The same, but a finished run shorter than `short_seconds` of wall time (where
// timer noise and cold caches weigh most) is run again, up to `repeats` runs in
// all, and its wall time is their median. The runs are identical bit for bit
// (same input, same bits), so only the timing changes.
inline constexpr int kTimingRepeats = 5;
inline constexpr double kShortRunSeconds = 0.1;
SampledRun run_sampled_timed(const Scene& scene, const SolverSettings& settings,
                             const std::vector<double>& times, int repeats = kTimingRepeats,
                             double short_seconds = kShortRunSeconds);

}  // namespace neurocloth
