#include "sampled_run.h"

#include <algorithm>
#include <chrono>

namespace neurocloth {

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
  using Clock = std::chrono::steady_clock;
  for (double t : times) {
    const auto start = Clock::now();
    sim.advance(t - sim.time());
    // The last sample is checked in full, as `simulate` checks its result.
    if (&t == &times.back()) sim.check_now();
    run.wall_seconds += std::chrono::duration<double>(Clock::now() - start).count();
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
  if (!run.complete(times.size()) || run.wall_seconds >= short_seconds) return run;
  std::vector<double> walls = {run.wall_seconds};
  while (static_cast<int>(walls.size()) < repeats)
    walls.push_back(run_sampled(scene, settings, times).wall_seconds);
  std::sort(walls.begin(), walls.end());
  const std::size_t n = walls.size();
  run.wall_seconds = n % 2 ? walls[n / 2] : 0.5 * (walls[n / 2 - 1] + walls[n / 2]);
  run.timing_runs = static_cast<int>(n);
  return run;
}

}  // namespace neurocloth
