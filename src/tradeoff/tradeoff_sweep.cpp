#include "tradeoff/tradeoff_sweep.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>
#include <stdexcept>
#include <thread>

#include "core/integrators/stability.h"
#include "tradeoff/method_sweeps.h"
#include "tradeoff/ordered_jobs.h"

namespace neurocloth {
namespace {

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
  std::vector<std::function<void(MethodSweep&)>> sweeps;
  for (IntegratorKind kind : kAllIntegrators) {
    if (!wanted(plan, to_string(kind))) continue;
    if (kind == IntegratorKind::rk4)
      sweeps.emplace_back([](MethodSweep& s) { s.rk4(); });
    else if (kind == IntegratorKind::projective)
      sweeps.emplace_back([](MethodSweep& s) {
        s.iterating(IntegratorKind::projective, s.plan.projective_iterations);
      });
    else if (kind == IntegratorKind::vbd)
      sweeps.emplace_back(
          [](MethodSweep& s) { s.iterating(IntegratorKind::vbd, s.plan.vbd_iterations); });
    else if (kind == IntegratorKind::implicit_euler)
      sweeps.emplace_back([](MethodSweep& s) { s.implicit(); });
    else
      sweeps.emplace_back([kind](MethodSweep& s) { s.fixed_step(kind); });
  }
  if (wanted(plan, kAdaptiveMethod))
    sweeps.emplace_back([](MethodSweep& s) { s.adaptive(DampingMode::explicit_force); });
  // Not among the defaults: a trade of its own on the scenes it was made for.
  if (named(plan, kAdaptiveImplicitMethod))
    sweeps.emplace_back([](MethodSweep& s) { s.adaptive(DampingMode::implicit_springwise); });
  const int workers = tradeoff_workers(plan.workers, sweeps.size());
  // Two cores go to two lines or to one step, not both at once.
  Scene line_scene = scene;
  if (workers > 1) line_scene.solver.threads = 1;
  std::vector<MethodLine> lines(sweeps.size());
  run_jobs_in_order(
      sweeps.size(), workers,
      [&](std::size_t i) {
        const Scene own = line_scene;
        MethodSweep sweep{own,
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
        MethodLine& line = lines[i];
        table.rows.insert(table.rows.end(), line.rows.begin(), line.rows.end());
        table.sweep_stops.insert(table.sweep_stops.end(), line.stops.begin(), line.stops.end());
        if (log)
          for (const std::string& s : line.log)
            log(s);
        line = MethodLine{};
      });
  table.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return table;
}

}  // namespace neurocloth
