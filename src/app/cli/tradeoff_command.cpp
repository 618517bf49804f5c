// `neurocloth-cli tradeoff`: measures what each integrator's accuracy costs on a
// scene and writes the trade as CSV, a log-log chart and a Markdown summary.
// All three are made in memory first, so a failure to measure or draw leaves
// the old files as they were; each is then written whole or not at all.
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "app/cli/commands.h"
#include "chart/trade_chart.h"
#include "core/io/input_error.h"
#include "core/io/physical_limits.h"
#include "core/io/text_file.h"
#include "core/scene/scene.h"
#include "tradeoff/accuracy_choice.h"
#include "tradeoff/pareto_front.h"
#include "tradeoff/trade_csv.h"
#include "tradeoff/trade_summary.h"
#include "tradeoff/tradeoff_sweep.h"

namespace neurocloth {
namespace {

// Fails now, naming the file, if REPORT's folder cannot take a file: better
// than after a minute of measuring.
void check_writable(const std::string& report) {
  const std::string probe = report + ".csv.probe." + std::to_string(::getpid());
  try {
    write_file_atomically(probe, "");
  } catch (const std::runtime_error&) {
    throw InputError("command line", "--out", report + ".csv: cannot write output file");
  }
  std::remove(probe.c_str());
}

// A step as "0.015625" or as a fraction "1/60" (a display's frame is not a
// short decimal); nullopt when it is neither.
std::optional<double> parse_step(const std::string& text) {
  const auto number = [](const std::string& t) -> std::optional<double> {
    char* end = nullptr;
    const double v = std::strtod(t.c_str(), &end);
    if (t.empty() || end != t.c_str() + t.size() || !std::isfinite(v)) return std::nullopt;
    return v;
  };
  const std::size_t slash = text.find('/');
  if (slash == std::string::npos) return number(text);
  const auto top = number(text.substr(0, slash)), bottom = number(text.substr(slash + 1));
  if (!top || !bottom || !(*bottom > 0)) return std::nullopt;
  return *top / *bottom;
}

}  // namespace

std::optional<double> parse_length(const std::string& text) {
  static const std::pair<const char*, double> kUnits[] = {
      {"nm", 1e-9}, {"um", 1e-6}, {"mm", 1e-3}, {"cm", 1e-2}, {"m", 1}};
  std::string number = text;
  double unit = 1;
  for (const auto& [suffix, scale] : kUnits) {
    const std::size_t n = std::char_traits<char>::length(suffix);
    if (text.size() > n && text.compare(text.size() - n, n, suffix) == 0) {
      number = text.substr(0, text.size() - n);
      unit = scale;
      break;
    }
  }
  char* end = nullptr;
  const double v = std::strtod(number.c_str(), &end);
  if (number.empty() || end != number.c_str() + number.size() || !std::isfinite(v))
    return std::nullopt;
  return v * unit;
}

Metric metric_option(const std::string& text, const char* option) {
  if (text.empty()) return kDefaultMetric;
  const std::optional<Metric> m = parse_metric(text);
  if (!m)
    throw InputError("command line", option,
                     "unknown metric '" + text + "' (expected one of: " + metric_names() + ")");
  return *m;
}

TradeoffPlan tradeoff_plan(const TradeoffOptions& o) {
  // A trade runs the scene dozens of times over: an hour of simulated time
  // each is already days of wall time for a fine cloth.
  if (!(o.seconds > 0 && o.seconds <= 3600))
    throw InputError("command line", "--seconds", "must be in (0, 3600] (simulated seconds)");
  if (o.samples < 1 || o.samples > 1000)
    throw InputError("command line", "--samples", "must be in [1, 1000]");
  if (!(o.reference_budget > 0) || !std::isfinite(o.reference_budget))
    throw InputError("command line", "--reference-budget", "must be a finite number > 0 (seconds)");
  if (!(o.method_budget > 0) || !std::isfinite(o.method_budget))
    throw InputError("command line", "--method-budget", "must be a finite number > 0 (seconds)");
  if (o.levels < 1 || o.levels > 40)
    throw InputError("command line", "--levels", "must be in [1, 40] (each halves the step)");
  for (const std::string& m : o.methods)
    if (!is_trade_method(m))
      throw InputError(
          "command line", "--methods",
          "unknown method '" + m + "' (expected one of: " + trade_method_names() + ")");
  for (int i : o.projective_iterations)
    if (!limits::kIterations.contains(i))
      throw InputError("command line", "--projective-iterations", limits::kIterations.refusal(i));
  for (int i : o.vbd_iterations)
    if (!limits::kIterations.contains(i))
      throw InputError("command line", "--vbd-iterations", limits::kIterations.refusal(i));
  for (double t : o.implicit_tolerances)
    if (!limits::kLinearTolerance.contains(t))
      throw InputError("command line", "--implicit-tolerances",
                       limits::kLinearTolerance.refusal(t));
  if (o.workers && (*o.workers < 1 || *o.workers > kMaxTradeoffWorkers))
    throw InputError("command line", "--workers",
                     "must be in [1, " + std::to_string(kMaxTradeoffWorkers) + "], got " +
                         std::to_string(*o.workers) + " (method lines measured at once)");
  metric_option(o.metric, "--metric");
  TradeoffPlan plan;
  plan.ensemble.members = o.ensemble;
  const std::optional<double> shift = parse_length(o.perturbation);
  if (!shift)
    throw InputError("command line", "--perturbation",
                     "not a length: '" + o.perturbation + "' (e.g. 1mm, 0.5um, 1e-6)");
  plan.ensemble.shift = *shift;
  if (o.ensemble < kMinEnsemble || o.ensemble > kMaxEnsemble)
    throw InputError("command line", "--ensemble",
                     ensemble_refusal(plan.ensemble) + " (references of the scene's own spread)");
  if (const std::string why = ensemble_refusal(plan.ensemble); !why.empty())
    throw InputError("command line", "--perturbation", why);
  plan.workers = o.workers.value_or(0);
  for (const std::string& text : o.steps) {
    const std::optional<double> dt = parse_step(text);
    if (!dt)
      throw InputError("command line", "--dt", "not a step in s (0.01 or 1/60): '" + text + "'");
    if (const std::string why = step_refusal(*dt, o.seconds / o.samples); !why.empty())
      throw InputError("command line", "--dt", text + ": " + why);
    plan.steps.push_back(*dt);
  }
  if (!o.projective_iterations.empty()) plan.projective_iterations = o.projective_iterations;
  if (!o.vbd_iterations.empty()) plan.vbd_iterations = o.vbd_iterations;
  if (!o.implicit_tolerances.empty()) plan.implicit_tolerances = o.implicit_tolerances;
  plan.seconds = o.seconds;
  plan.samples = o.samples;
  plan.reference.budget_seconds = o.reference_budget;
  plan.method_budget_seconds = o.method_budget;
  plan.max_levels = o.levels;
  plan.methods = o.methods;
  return plan;
}

TradeTable measure_trade(const Scene& shipped, const std::string& scene_file,
                         const TradeoffPlan& plan) {
  // The reference's runs share their steps alike; measure_tradeoff gives the
  // lines one thread each in their steps when it measures several at once.
  Scene scene = shipped;
  scene.solver.threads = batch_step_threads(scene.topology.rest_positions.size());
  return measure_tradeoff(scene, scene_file, plan,
                          [](const std::string& line) { std::printf("  %s\n", line.c_str()); });
}

Scene sized_scene(Scene scene, const std::string& scene_path, const std::optional<int>& size) {
  if (!size) return scene;
  if (!limits::kGridSize.contains(*size))
    throw InputError("command line", "--size", limits::kGridSize.refusal(*size));
  if (!scene.grid)
    throw InputError("command line", "--size",
                     scene_path + " is not a grid scene: it has no N x N to resize to");
  try {
    return resized_grid(scene, *size);
  } catch (const std::invalid_argument& e) {
    throw InputError("command line", "--size", e.what());
  }
}

namespace {

// The chart (PNG bytes) and the summary of a trade, made in memory: a failure
// to draw leaves every file as it was.
struct Report {
  std::string png, md;
};
Report chart_and_summary(const TradeTable& trade, Metric metric, const std::string& png) {
  std::ostringstream chart;
  write_trade_chart(trade, metric, chart, png);
  release_chart_caches();  // the one chart of this process is drawn
  return {chart.str(), trade_summary(trade, metric, png.substr(png.find_last_of('/') + 1))};
}

int replot(const TradeoffOptions& o, Metric metric) {
  const Scene scene = sized_scene(load_scene(o.scene), o.scene, o.size);
  const TradeTable trade =
      o.size ? read_sized_trade(*o.replot, *o.size) : read_trade_csv(*o.replot);
  if (trade.scene != scene.name)
    throw InputError(*o.replot, "# scene",
                     "measured for scene '" + trade.scene + "', not for '" + scene.name + "'");
  if (!has_metric(trade, metric))
    throw InputError(*o.replot, "--metric",
                     std::string("this trade did not measure ") + to_string(metric));
  if (o.out.empty()) throw InputError("command line", "--out", "must name a file");
  check_writable(o.out);
  const Report report = chart_and_summary(trade, metric, o.out + ".png");
  write_file_atomically(o.out + ".png", report.png);
  write_file_atomically(o.out + ".md", report.md);
  std::printf("wrote %s.png and %s.md from %s in %s\n", o.out.c_str(), o.out.c_str(),
              o.replot->c_str(), to_string(metric));
  return kExitOk;
}

}  // namespace

int run_tradeoff(const TradeoffOptions& o) {
  const TradeoffPlan plan = tradeoff_plan(o);
  const Metric metric = metric_option(o.metric, "--metric");
  if (o.replot) return replot(o, metric);
  Scene scene = sized_scene(load_scene(o.scene), o.scene, o.size);
  if (o.out.empty()) throw InputError("command line", "--out", "must name a file");
  check_writable(o.out);

  std::printf(
      "tradeoff %s%s: %g s simulated per run, compared at %d times\n", scene.name.c_str(),
      o.size ? (" at " + std::to_string(*o.size) + " x " + std::to_string(*o.size)).c_str() : "",
      plan.seconds, plan.samples);
  std::fflush(stdout);
  const TradeTable trade = measure_trade(scene, o.scene, plan);

  const std::string csv = o.out + ".csv", png = o.out + ".png", md = o.out + ".md";
  const Report report = chart_and_summary(trade, metric, png);
  write_file_atomically(csv, trade_csv(trade));
  write_file_atomically(png, report.png);
  write_file_atomically(md, report.md);

  const ReferenceReport& r = trade.reference;
  std::printf("reference: rk4 dt = %.4g s, last halving changed %.3g of the size (target %g %s)\n",
              r.dt, r.change, r.target, r.met ? "met" : "NOT met");
  const double floor = trade.floor ? trade.floor->p90[slot(metric)] : std::nan("");
  if (std::isfinite(floor))
    std::printf(
        "the scene's own spread in %s (%d references shifted %g mm): %.3g%% "
        "(median %.3g%%)\n",
        to_string(metric), trade.floor->members, 1000 * trade.floor->shift, 100 * floor,
        100 * trade.floor->median[slot(metric)]);
  for (double budget : kErrorBudgets) {
    const double target = std::isfinite(floor) ? std::max(budget, floor) : budget;
    const auto pick = cheapest_meeting(trade.rows, target, metric);
    const std::string asked =
        percent(budget) + (target > budget ? " (the floor, " + percent(target) + ")" : "");
    if (metric == Metric::node_max && !trade.floor && budget < reference_resolution(trade))
      std::printf("  %-6s not certified (below the reference's resolution)\n", asked.c_str());
    else if (pick)
      std::printf("  %-6s %s: %s %.3g, %.3g s per simulated s\n", asked.c_str(),
                  describe_setting(trade.rows[*pick]).c_str(), to_string(metric),
                  row_error(trade.rows[*pick], metric),
                  trade.rows[*pick].wall_per_simulated_second);
    else
      std::printf("  %-6s no measured setting meets it\n", asked.c_str());
  }
  std::printf("measured in %.1f s; wrote %s, %s, %s\n", trade.wall_seconds, csv.c_str(),
              png.c_str(), md.c_str());
  return kExitOk;
}

}  // namespace neurocloth
