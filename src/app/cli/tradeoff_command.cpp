// `neurocloth-cli tradeoff`: measures what each integrator's accuracy costs on a
// scene and writes the trade as CSV, a log-log chart and a Markdown summary.
// All three are made in memory first, so a failure to measure or draw leaves
// the old files as they were; each is then written whole or not at all.
#include <unistd.h>

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
  TradeoffPlan plan;
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

int run_tradeoff(const TradeoffOptions& o) {
  const TradeoffPlan plan = tradeoff_plan(o);
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
  const std::string chart_name = png.substr(png.find_last_of('/') + 1);
  std::ostringstream chart;
  write_trade_chart(trade, chart, png);
  release_chart_caches();  // the one chart of this process is drawn
  write_file_atomically(csv, trade_csv(trade));
  write_file_atomically(png, chart.str());
  write_file_atomically(md, trade_summary(trade, chart_name));

  const ReferenceReport& r = trade.reference;
  std::printf("reference: rk4 dt = %.4g s, last halving changed %.3g of the size (target %g %s)\n",
              r.dt, r.change, r.target, r.met ? "met" : "NOT met");
  for (double budget : kErrorBudgets) {
    const auto pick = cheapest_meeting(trade.rows, budget);
    if (budget < reference_resolution(trade))
      std::printf("  %-6s not certified (below the reference's resolution)\n",
                  percent(budget).c_str());
    else if (pick)
      std::printf("  %-6s %s: %.3g s per simulated s\n", percent(budget).c_str(),
                  describe_setting(trade.rows[*pick]).c_str(),
                  trade.rows[*pick].wall_per_simulated_second);
    else
      std::printf("  %-6s no measured setting meets it\n", percent(budget).c_str());
  }
  std::printf("measured in %.1f s; wrote %s, %s, %s\n", trade.wall_seconds, csv.c_str(),
              png.c_str(), md.c_str());
  return kExitOk;
}

}  // namespace neurocloth
