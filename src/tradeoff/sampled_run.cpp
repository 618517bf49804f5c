#include "tradeoff/sampled_run.h"

#include <time.h>

#include <algorithm>
#include <chrono>
#include <stdexcept>

namespace neurocloth {

RunClock run_clock(const SolverSettings& settings) {
  return settings.threads > 1 ? RunClock::wall : RunClock::thread_cpu;
}

const char* to_string(RunClock clock) {
  return clock == RunClock::wall ? "wall" : "thread CPU";
}

double now_seconds(RunClock clock) {
  if (clock == RunClock::wall)
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
        .count();
  timespec t{};
  if (clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t) != 0)
    throw std::runtime_error("clock_gettime(CLOCK_THREAD_CPUTIME_ID) failed");
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

std::vector<double> sample_times(double seconds, int samples) {
  std::vector<double> t;
  for (int j = 1; j <= samples; ++j)
    t.push_back(j == samples ? seconds : seconds * j / samples);
  return t;
}

SampledRun run_sampled(const Scene& scene, const SolverSettings& settings,
                       const std::vector<double>& times) {
  Scene s = scene;
  s.solver = settings;
  Simulation sim = s.make_simulation();
  SampledRun run;
  run.settings = settings;
  const RunClock clock = run_clock(settings);
  for (std::size_t k = 0; k < times.size(); ++k) {
    const double t = times[k];
    const double start = now_seconds(clock);
    sim.advance(t - sim.time());
    // The last sample is checked in full, as `simulate` checks its result.
    if (k + 1 == times.size()) sim.check_result();
    run.cost_seconds += now_seconds(clock) - start;
    if (sim.status() != RunStatus::ok) break;
    // A healthy run that did not get there ran out of its step budget (solver_settings.h).
    if (sim.time() < t - 1e-9 * t) {
      run.stopped = true;
      run.reason = "stopped at t = " + std::to_string(sim.time()) + " s: out of step budget";
      break;
    }
    const ClothState& x = sim.state();
    std::vector<double> p(3 * x.size());
    for (std::size_t i = 0; i < x.size(); ++i) {
      p[3 * i] = x.x[i];
      p[3 * i + 1] = x.y[i];
      p[3 * i + 2] = x.z[i];
    }
    run.times.push_back(t);
    run.positions.push_back(std::move(p));
    run.energy.push_back(sim.energy().total());
  }
  run.status = sim.status();
  if (run.status != RunStatus::ok) run.reason = sim.divergence_reason();
  run.simulated_seconds = sim.time();
  run.steps = sim.steps();
  run.rejected_steps = sim.rejected_steps();
  run.force_evaluations = sim.force_evaluations();
  run.cg_iterations = sim.cg_iterations();
  return run;
}

SampledRun run_sampled_timed(const Scene& scene, const SolverSettings& settings,
                             const std::vector<double>& times, int repeats, double short_seconds) {
  SampledRun run = run_sampled(scene, settings, times);
  if (!run.complete(times.size()) || run.cost_seconds >= short_seconds) return run;
  std::vector<double> costs = {run.cost_seconds};
  while (static_cast<int>(costs.size()) < repeats)
    costs.push_back(run_sampled(scene, settings, times).cost_seconds);
  std::sort(costs.begin(), costs.end());
  const std::size_t n = costs.size();
  run.cost_seconds = n % 2 ? costs[n / 2] : 0.5 * (costs[n / 2 - 1] + costs[n / 2]);
  run.timing_runs = static_cast<int>(n);
  return run;
}

}  // namespace neurocloth
