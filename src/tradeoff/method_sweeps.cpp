#include "tradeoff/method_sweeps.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "core/integrators/stability.h"

namespace neurocloth {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

TradeRow row_from(const SampledRun& run, const SampledRun& reference, const ErrorScale& scale,
                  std::size_t samples) {
  TradeRow row;
  row.dt = run.settings.dt;
  if (run.settings.integrator == IntegratorKind::implicit_euler)
    row.linear_tolerance = run.settings.linear_tolerance;
  row.steps = run.steps;
  row.force_evaluations = run.force_evaluations;
  row.rejected_steps = run.rejected_steps;
  row.wall_per_simulated_second =
      run.simulated_seconds > 0 ? run.cost_seconds / run.simulated_seconds : kNaN;
  if (run.complete(samples)) {
    const RunError e = compare_runs(run, reference, scale);
    row.position_error_max = e.position_max;
    row.position_error_rms = e.position_rms;
    row.energy_error = e.energy;
  } else {
    row.position_error_max = row.position_error_rms = row.energy_error = kNaN;
    row.status = run.status != RunStatus::ok ? "diverged" : "stopped";
  }
  return row;
}

std::string describe_row(const TradeRow& row) {
  char s[320];
  int n = std::snprintf(s, sizeof s, "%s: %s, max error %.3g, rms %.3g, %.3g s per simulated s",
                        describe_setting(row).c_str(), row.status.c_str(), row.position_error_max,
                        row.position_error_rms, row.wall_per_simulated_second);
  const double surface = row.ensemble[slot(Metric::surface_mean)];
  if (std::isfinite(surface) && n > 0 && static_cast<std::size_t>(n) < sizeof s)
    std::snprintf(s + n, sizeof s - static_cast<std::size_t>(n),
                  "; to the ensemble: node max %.3g, surface mean %.3g",
                  row.ensemble[slot(Metric::node_max)], surface);
  return s;
}

// Why a line stops after `row`, its `levels`-th setting, on its accuracy alone
// (empty: go on).
std::string accuracy_stop(const TradeoffPlan& plan, const ReferenceReport& ref, const TradeRow& row,
                          int levels) {
  if (row.ok() && row.position_error_max <= plan.error_floor) return "error floor";
  // At least a few settings even then, so that the chart shows the line's slope
  // (and where it flattens on the reference's own error).
  if (row.ok() && !ref.met && ref.change >= 0 && row.position_error_max <= 2 * ref.change &&
      levels >= plan.min_levels)
    return "reference resolution";
  if (levels >= plan.max_levels) return "levels";
  return "";
}

// The cost the next halving of a run is predicted to have: twice this one's.
// A run that did not finish says little about what the next one costs: only the
// time already spent counts against the budget then.
double next_cost(const TradeRow& row, const SampledRun& run) {
  return row.ok() ? 2 * run.cost_seconds : 0;
}

}  // namespace

void MethodSweep::say(const std::string& s) const {
  if (!live)
    out.log.push_back(s);
  else if (*live)
    (*live)(s);
}

// A finished run's distance to the ensemble, in every metric.
void MethodSweep::to_ensemble(TradeRow& row, const SampledRun& run) const {
  if (ensemble && run.complete(times.size()))
    row.ensemble = distance_to_ensemble(trajectory(run, metrics), *ensemble, metrics);
}

// Runs one setting and adds its row.
TradeRow MethodSweep::run_row(const SolverSettings& s, const std::string& method,
                              const char* parameter, double value, SampledRun& run) {
  run = run_sampled_timed(scene, s, times);
  TradeRow row = row_from(run, ref.run, scale, times.size());
  to_ensemble(row, run);
  row.method = method;
  row.parameter = parameter;
  row.value = value;
  if (iterates_per_step(s.integrator)) row.iterations = s.iterations;
  say(describe_row(row));
  out.rows.push_back(row);
  return row;
}

void MethodSweep::stopped(const std::string& line, const std::string& why) {
  say("  " + line + " stops: " + why);
  out.stops.push_back(line + ": " + why);
}

// Runs one setting of a line and adds its row; false when the line stops here.
bool MethodSweep::measure(const SolverSettings& s, const std::string& method, const char* parameter,
                          double value, int level, double& line_cost) {
  SampledRun run;
  const TradeRow row = run_row(s, method, parameter, value, run);
  line_cost += run.cost_seconds;
  std::string why = accuracy_stop(plan, ref.report, row, level);
  if (why.empty() && line_cost + next_cost(row, run) > plan.method_budget_seconds) why = "budget";
  if (why.empty()) return true;
  stopped(line_name(row), why);
  return false;
}

void MethodSweep::rk4() {
  for (const SampledRun& run : ref.coarser) {
    TradeRow row = row_from(run, ref.run, scale, times.size());
    to_ensemble(row, run);
    row.method = to_string(IntegratorKind::rk4);
    row.parameter = "dt";
    row.value = row.dt;
    say(describe_row(row));
    out.rows.push_back(row);
  }
}

void MethodSweep::fixed_step(IntegratorKind kind) {
  SolverSettings s = scene.solver;
  s.integrator = kind;
  s.adaptive = false;
  if (!plan.steps.empty()) {
    for (double dt : plan.steps) {
      s.dt = dt;
      SampledRun run;
      run_row(s, to_string(kind), "dt", dt, run);
    }
    return;
  }
  s.dt = first_step(scene, kind, plan.seconds / plan.samples);
  double line_cost = 0;
  for (int level = 1; measure(s, to_string(kind), "dt", s.dt, level, line_cost); ++level) {
    if (at_step_floor(s.dt, to_string(kind))) break;
    s.dt /= 2;
  }
}

// No run may ask for a step below the floor: true (and the line stopped) when
// halving `dt` would.
bool MethodSweep::at_step_floor(double dt, const std::string& line) {
  if (dt / 2 >= limits::kTimeStep.low) return false;
  say("  " + line + " stops: the step floor (1e-6 s)");
  out.stops.push_back(line + ": step floor");
  return true;
}

void MethodSweep::iterating(IntegratorKind kind, const std::vector<int>& counts) {
  std::vector<SolverSettings> lines;
  for (int iterations : counts) {
    lines.push_back(scene.solver);
    lines.back().iterations = iterations;
  }
  two_knobs(kind, lines);
}

void MethodSweep::implicit() {
  std::vector<SolverSettings> lines;
  for (double tolerance : plan.implicit_tolerances) {
    lines.push_back(scene.solver);
    lines.back().linear_tolerance = tolerance;
  }
  two_knobs(IntegratorKind::implicit_euler, lines);
}

// A method with a second knob: one line per setting of it (`lines`, the
// scene's solver with that knob set). At each step it tries (halved as for the
// others), every line still going runs. The lines stop on their accuracy one
// by one, and on the method's one budget together: the next step's runs,
// predicted at twice this step's, must fit.
void MethodSweep::two_knobs(IntegratorKind kind, std::vector<SolverSettings> going) {
  const std::string method = to_string(kind);
  for (SolverSettings& s : going) {
    s.integrator = kind;
    s.adaptive = false;
  }
  if (!plan.steps.empty()) {
    for (double dt : plan.steps)
      for (SolverSettings s : going) {
        s.dt = dt;
        SampledRun run;
        run_row(s, method, "dt", dt, run);
      }
    return;
  }
  double dt = first_step(scene, kind, plan.seconds / plan.samples);
  double method_cost = 0;
  for (int level = 1; !going.empty(); ++level) {
    double next = 0;
    std::vector<SolverSettings> still;
    std::vector<std::string> names;  // of the lines still going
    for (SolverSettings& s : going) {
      s.dt = dt;
      SampledRun run;
      const TradeRow row = run_row(s, method, "dt", dt, run);
      method_cost += run.cost_seconds;
      const std::string why = accuracy_stop(plan, ref.report, row, level);
      if (!why.empty()) {
        stopped(line_name(row), why);
        continue;
      }
      next += next_cost(row, run);
      still.push_back(s);
      names.push_back(line_name(row));
    }
    going = std::move(still);
    if (!going.empty() && method_cost + next > plan.method_budget_seconds) {
      for (const std::string& name : names)
        stopped(name, "budget");
      return;
    }
    if (!going.empty() && at_step_floor(dt, method)) return;
    dt /= 2;
  }
}

// The paper's propagation at the scene's refresh interval, halving the
// safety factor: the cap on t_c is min(t_delta, safety * stability bound), so
// values giving the same cap as the one before are skipped. With the damping
// taken implicitly the bound is the springs' stiffness alone.
void MethodSweep::adaptive(DampingMode damping) {
  SolverSettings s = scene.solver;
  s.integrator = IntegratorKind::network;
  s.adaptive = true;
  s.damping = damping;
  const ClothNetwork net = scene.build_network();
  const double bound = integrator_step_bound(net, *make_integrator(s, net), s.step_bound);
  const char* method =
      damping == DampingMode::explicit_force ? kAdaptiveMethod : kAdaptiveImplicitMethod;
  double line_cost = 0, last_cap = -1;
  int level = 0;
  for (double safety = 1; safety > 1e-6; safety /= 2) {
    const double cap = std::min(s.dt, safety * bound);
    if (cap == last_cap) continue;
    last_cap = cap;
    s.adaptive_settings.safety = safety;
    if (!measure(s, method, "safety", safety, ++level, line_cost)) return;
  }
}

}  // namespace neurocloth
