#include "tradeoff/converged_reference.h"

#include <cstdio>
#include <iterator>
#include <stdexcept>

#include "core/io/physical_limits.h"

namespace neurocloth {
namespace {

std::string describe_run(const SampledRun& run) {
  char s[160];
  std::snprintf(s, sizeof s, "reference rk4 dt=%.4g s: %s, %.3g s %s", run.settings.dt,
                run.status == RunStatus::ok ? "ok" : "diverged", run.cost_seconds,
                to_string(run_clock(run.settings)));
  return s;
}

}  // namespace

ConvergedReference converge_reference(const Scene& scene, const std::vector<double>& times,
                                      const ErrorScale& scale, double first_dt,
                                      const ReferencePlan& plan,
                                      const std::function<void(const std::string&)>& log) {
  ConvergedReference out;
  ReferenceReport& r = out.report;
  r.target = plan.target;
  SolverSettings s = scene.solver;
  s.integrator = IntegratorKind::rk4;
  s.adaptive = false;
  s.dt = first_dt;
  const double seconds = times.back();

  std::vector<SampledRun> runs;    // every run, coarsest first
  int halvings_since_stable = -1;  // counts from the first complete run
  for (;;) {
    runs.push_back(run_sampled_timed(scene, s, times));
    const SampledRun& run = runs.back();
    ++r.runs;
    r.wall_seconds += run.cost_seconds;
    const bool complete = run.complete(times.size());
    std::string line = describe_run(run);
    if (complete && halvings_since_stable < 0) halvings_since_stable = 0;

    if (!complete && halvings_since_stable >= 0) {
      // Finer and yet diverged: something other than the step is wrong; keep the last good run.
      r.stopped_by = "diverged";
      if (log) log(line);
      out.coarser.push_back(std::move(runs.back()));  // it stays visible in the trade
      runs.pop_back();
      break;
    }
    if (complete && runs.size() >= 2 && runs[runs.size() - 2].complete(times.size())) {
      const RunError c = compare_runs(runs[runs.size() - 2], run, scale);
      r.change = c.position_max;
      r.rms_change = c.position_rms;
      r.change_by_sample = c.position_max_by_sample;
      char tail[96];
      std::snprintf(tail, sizeof tail, ", change from dt=%.4g s: %.3g of the size",
                    2 * run.settings.dt, r.change);
      line += tail;
      if (r.change < plan.target) {
        r.met = true;
        r.stopped_by = "target";
        if (log) log(line);
        break;
      }
    }
    if (log) log(line);
    if (halvings_since_stable >= plan.max_halvings) {
      r.stopped_by = "halvings";
      break;
    }
    // The next run takes twice the steps: would it still fit in the budget?
    const double reached = run.simulated_seconds > 0 ? run.simulated_seconds : seconds;
    const double predicted = 2 * run.cost_seconds * seconds / reached;
    if (r.wall_seconds + predicted > plan.budget_seconds) {
      r.stopped_by = "budget";
      break;
    }
    if (s.dt / 2 < limits::kTimeStep.low) {  // no run may ask for a step below the floor
      r.stopped_by = "step floor";
      break;
    }
    s.dt /= 2;
    if (halvings_since_stable >= 0) ++halvings_since_stable;
  }
  if (runs.empty() || !runs.back().complete(times.size()))
    throw std::runtime_error("the RK4 reference diverged at every step down to dt = " +
                             std::to_string(s.dt) + " s within its budget");
  out.run = std::move(runs.back());
  r.dt = out.run.settings.dt;
  runs.pop_back();
  out.coarser.insert(out.coarser.begin(), std::make_move_iterator(runs.begin()),
                     std::make_move_iterator(runs.end()));
  return out;
}

}  // namespace neurocloth
