#include "tradeoff/tradeoff_sweep.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <stdexcept>
#include <thread>

#include "core/integrators/stability.h"
#include "tradeoff/ordered_jobs.h"

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

// The members' step: the coarsest reference run within kMemberTolerance of the finest.
SolverSettings member_settings(const ConvergedReference& ref, const ErrorScale& scale,
                               std::size_t samples) {
  for (const SampledRun& run : ref.coarser)  // coarsest first
    if (run.complete(samples) && compare_runs(run, ref.run, scale).position_max <= kMemberTolerance)
      return run.settings;
  return ref.run.settings;
}

bool named(const TradeoffPlan& plan, const std::string& method) {
  return std::find(plan.methods.begin(), plan.methods.end(), method) != plan.methods.end();
}

bool wanted(const TradeoffPlan& plan, const std::string& method) {
  return plan.methods.empty() || named(plan, method);
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

double first_step(const Scene& scene, IntegratorKind kind, double interval) {
  const ClothNetwork net = scene.build_network();
  const auto integrator = make_integrator(kind, net);
  if (std::isinf(integrator->stability_limit()))
    return interval / 4;  // implicit_euler, projective: no bound to meet
  // Gershgorin's bound whatever the scene's setting: the sweep starts at twice
  // it, near the stability edge (Gershgorin's lies 1.2-2.6 times under it,
  // docs/stability.md); twice the spectral bound can be 1.8 times past the
  // edge, where a level is nothing but its blow-up.
  const double bound = integrator_step_bound(net, *integrator, StepBound::gershgorin);
  double h = interval;
  while (h > 2 * bound && h > interval * 1e-12)
    h /= 2;
  return h;
}

int tradeoff_workers(int workers, std::size_t lines) {
  const int wanted =
      workers > 0 ? workers : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  return std::max(1, static_cast<int>(std::min<std::size_t>(static_cast<std::size_t>(wanted),
                                                            std::max<std::size_t>(lines, 1))));
}

std::string step_refusal(double dt, double interval) {
  if (!limits::kTimeStep.contains(dt)) return limits::kTimeStep.refusal(dt);
  // A part step at each sample time would be a run of another step (and, for
  // projective, another factorisation): not the setting asked for.
  const double steps = interval / dt;
  if (std::abs(steps - std::round(steps)) > 1e-9 * steps) {
    char s[160];
    std::snprintf(s, sizeof s,
                  "%.6g s does not divide the sample interval %.6g s (seconds / samples) into "
                  "whole steps",
                  dt, interval);
    return s;
  }
  return "";
}

namespace {

// What one method's line adds to the table, kept apart until it is merged in
// method order.
struct Line {
  std::vector<TradeRow> rows;
  std::vector<std::string> stops;
  std::vector<std::string> log;  // when not told live
};

// One method's sweep: reads what every line shares, writes only its own line.
struct Sweep {
  const Scene& scene;  // the line's own copy
  const TradeoffPlan& plan;
  const std::vector<double>& times;
  const ErrorScale& scale;
  const ConvergedReference& ref;
  const MetricContext& metrics;
  const Ensemble* ensemble;                             // null: none asked for
  const std::function<void(const std::string&)>* live;  // null: say() keeps it in the line
  Line& out;

  void say(const std::string& s) const {
    if (!live)
      out.log.push_back(s);
    else if (*live)
      (*live)(s);
  }

  // A finished run's distance to the ensemble, in every metric.
  void to_ensemble(TradeRow& row, const SampledRun& run) const {
    if (ensemble && run.complete(times.size()))
      row.ensemble = distance_to_ensemble(trajectory(run, metrics), *ensemble, metrics);
  }

  // Runs one setting and adds its row.
  TradeRow run_row(const SolverSettings& s, const std::string& method, const char* parameter,
                   double value, SampledRun& run) {
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

  void stopped(const std::string& line, const std::string& why) {
    say("  " + line + " stops: " + why);
    out.stops.push_back(line + ": " + why);
  }

  // Runs one setting of a line and adds its row; false when the line stops here.
  bool measure(const SolverSettings& s, const std::string& method, const char* parameter,
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

  // RK4's line: the reference's own coarser runs.
  void rk4() {
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

  void fixed_step(IntegratorKind kind) {
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
  bool at_step_floor(double dt, const std::string& line) {
    if (dt / 2 >= limits::kTimeStep.low) return false;
    say("  " + line + " stops: the step floor (1e-6 s)");
    out.stops.push_back(line + ": step floor");
    return true;
  }

  // Projective and vbd have two knobs: the step and the iterations per step.
  void iterating(IntegratorKind kind, const std::vector<int>& counts) {
    std::vector<SolverSettings> lines;
    for (int iterations : counts) {
      lines.push_back(scene.solver);
      lines.back().iterations = iterations;
    }
    two_knobs(kind, lines);
  }

  // So has the implicit step: its step and its conjugate-gradient tolerance.
  void implicit() {
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
  void two_knobs(IntegratorKind kind, std::vector<SolverSettings> going) {
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
  void adaptive(DampingMode damping) {
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
};

}  // namespace

TradeTable measure_tradeoff(const Scene& scene_as_given, const std::string& scene_file,
                            const TradeoffPlan& plan,
                            const std::function<void(const std::string&)>& log) {
  // The trade is measured in double, every method alike: the implicit ones
  // have no float path, and a float scene's own error against double is
  // measured apart (docs/network.md, "Float springs").
  Scene scene = scene_as_given;
  if (scene.solver.precision != SpringPrecision::float64) {
    scene.solver.precision = SpringPrecision::float64;
    if (log) log("the scene's solver.precision is float; the trade is measured in double");
  }
  if (!(plan.seconds > 0) || !std::isfinite(plan.seconds))
    throw std::invalid_argument("seconds must be a finite number > 0");
  if (plan.samples < 1) throw std::invalid_argument("samples must be >= 1");
  for (const auto& [kind, counts] :
       {std::pair{IntegratorKind::projective, &plan.projective_iterations},
        std::pair{IntegratorKind::vbd, &plan.vbd_iterations}}) {
    const std::string name = to_string(kind);
    if (!wanted(plan, name)) continue;
    if (counts->empty())
      throw std::invalid_argument(name + " needs at least one iterations count to sweep");
    for (int i : *counts)
      if (!limits::kIterations.contains(i))
        throw std::invalid_argument(name + " iterations must be in [1, 1000], got " +
                                    std::to_string(i));
  }
  if (wanted(plan, to_string(IntegratorKind::implicit_euler))) {
    if (plan.implicit_tolerances.empty())
      throw std::invalid_argument("implicit_euler needs at least one linear tolerance to sweep");
    for (double t : plan.implicit_tolerances)
      if (!limits::kLinearTolerance.contains(t))
        throw std::invalid_argument("implicit_euler linear tolerance: " +
                                    limits::kLinearTolerance.refusal(t));
  }
  for (double dt : plan.steps)
    if (const std::string why = step_refusal(dt, plan.seconds / plan.samples); !why.empty())
      throw std::invalid_argument("step: " + why);
  if (plan.ensemble.members != 0)
    if (const std::string why = ensemble_refusal(plan.ensemble); !why.empty())
      throw std::invalid_argument("ensemble: " + why);
  if (plan.workers < 0 || plan.workers > kMaxTradeoffWorkers)
    throw std::invalid_argument("workers must be in [0, " + std::to_string(kMaxTradeoffWorkers) +
                                "] (0: one per core), got " + std::to_string(plan.workers));
  for (const std::string& m : plan.methods)
    if (!is_trade_method(m))
      throw std::invalid_argument("unknown method '" + m +
                                  "' (expected one of: " + trade_method_names() + ")");
  const auto start = std::chrono::steady_clock::now();

  TradeTable table;
  table.scene = scene.name;
  table.scene_file = scene_file;
  table.seconds = plan.seconds;
  table.samples = plan.samples;
  if (scene.grid) {
    table.grid_rows = scene.grid->rows;
    table.grid_cols = scene.grid->cols;
  }
  const ErrorScale scale = error_scale(scene);
  table.cloth_size = scale.size;
  table.energy_scale = scale.energy;
  const std::vector<double> times = sample_times(plan.seconds, plan.samples);
  const double interval = plan.seconds / plan.samples;
  const ConvergedReference ref = converge_reference(
      scene, times, scale, first_step(scene, IntegratorKind::rk4, interval), plan.reference, log);
  table.reference = ref.report;
  // The metrics' context (triangles, support, the flat cloth's shadow) only
  // serves the ensemble: without one no row is measured in them.
  MetricContext metrics;
  std::optional<Ensemble> ensemble;
  if (plan.ensemble.members != 0) {
    metrics = metric_context(scene);
    const SolverSettings member = member_settings(ref, scale, times.size());
    ensemble = run_ensemble(
        scene, times, member, plan.ensemble, metrics,
        tradeoff_workers(plan.workers, static_cast<std::size_t>(plan.ensemble.members)), log);
    table.floor = ensemble->floor;
  }

  // Each line's stopping rules read only its own rows, so the lines can be
  // measured side by side; they are merged in method order whatever finishes first.
  std::vector<std::function<void(Sweep&)>> sweeps;
  for (IntegratorKind kind : kAllIntegrators) {
    if (!wanted(plan, to_string(kind))) continue;
    if (kind == IntegratorKind::rk4)
      sweeps.emplace_back([](Sweep& s) { s.rk4(); });
    else if (kind == IntegratorKind::projective)
      sweeps.emplace_back(
          [](Sweep& s) { s.iterating(IntegratorKind::projective, s.plan.projective_iterations); });
    else if (kind == IntegratorKind::vbd)
      sweeps.emplace_back(
          [](Sweep& s) { s.iterating(IntegratorKind::vbd, s.plan.vbd_iterations); });
    else if (kind == IntegratorKind::implicit_euler)
      sweeps.emplace_back([](Sweep& s) { s.implicit(); });
    else
      sweeps.emplace_back([kind](Sweep& s) { s.fixed_step(kind); });
  }
  if (wanted(plan, kAdaptiveMethod))
    sweeps.emplace_back([](Sweep& s) { s.adaptive(DampingMode::explicit_force); });
  // Not among the defaults: a trade of its own on the scenes it was made for.
  if (named(plan, kAdaptiveImplicitMethod))
    sweeps.emplace_back([](Sweep& s) { s.adaptive(DampingMode::implicit_springwise); });
  const int workers = tradeoff_workers(plan.workers, sweeps.size());
  // Two cores go to two lines or to one step, not both at once.
  Scene line_scene = scene;
  if (workers > 1) line_scene.solver.threads = 1;
  std::vector<Line> lines(sweeps.size());
  run_jobs_in_order(
      sweeps.size(), workers,
      [&](std::size_t i) {
        const Scene own = line_scene;
        Sweep sweep{own,
                    plan,
                    times,
                    scale,
                    ref,
                    metrics,
                    ensemble ? &*ensemble : nullptr,
                    workers > 1 ? nullptr : &log,
                    lines[i]};
        sweeps[i](sweep);
      },
      [&](std::size_t i) {
        Line& line = lines[i];
        table.rows.insert(table.rows.end(), line.rows.begin(), line.rows.end());
        table.sweep_stops.insert(table.sweep_stops.end(), line.stops.begin(), line.stops.end());
        if (log)
          for (const std::string& s : line.log)
            log(s);
        line = Line{};
      });
  table.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return table;
}

}  // namespace neurocloth
