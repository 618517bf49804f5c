#include "ui/accuracy_control.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include "tradeoff/accuracy_choice.h"
#include "tradeoff/pareto_front.h"
#include "tradeoff/trade_csv.h"

namespace neurocloth {

AccuracyTrade load_accuracy_trade(const std::string& scene_path, int resized_to) {
  AccuracyTrade t;
  t.path =
      resized_to > 0 ? sized_trade_path(scene_path, resized_to) : committed_trade_path(scene_path);
  if (!std::filesystem::exists(t.path)) {
    const std::string n = std::to_string(resized_to);
    t.note =
        resized_to > 0
            ? "no trade measured at " + n + " x " + n + " (neurocloth-cli tradeoff --size " + n +
                  " writes " + t.path + ")"
            : "no measured trade for this scene (neurocloth-cli tradeoff writes " + t.path + ")";
    return t;
  }
  try {
    TradeTable table =
        resized_to > 0 ? read_sized_trade(t.path, resized_to) : read_trade_csv(t.path);
    const Metric metric = default_metric(table);
    const auto best = most_accurate(table.rows, metric);
    if (!best) {
      t.note = t.path + ": no setting finished ok";
      return t;
    }
    // Finer than the best measured setting, than the scene's own spread, or
    // (without an ensemble) than the reference could tell apart, cannot be
    // vouched for.
    const double best_error = row_error(table.rows[*best], metric);
    t.finest = std::max(best_error,
                        table.floor ? table.floor->p90[slot(metric)] : reference_resolution(table));
    if (!std::isfinite(t.finest) || t.finest <= 0) t.finest = best_error;
    t.loosest = std::max(t.finest, kErrorBudgets[0]);
    t.table = std::move(table);
  } catch (const std::exception& e) {
    t.note = e.what();
  }
  return t;
}

AccuracyPick pick_for_accuracy(const AccuracyTrade& trade, double accuracy,
                               const SolverSettings& scene_solver) {
  if (!trade.table) throw std::logic_error("pick_for_accuracy without a trade");
  const AccuracyChoice c =
      choose_for_accuracy(*trade.table, trade.path, accuracy, scene_solver, "accuracy");
  AccuracyPick p;
  p.command = solver_command(c.settings);
  char line[200];
  if (std::isfinite(c.floor))
    std::snprintf(line, sizeof line, ": error %.3g%% (%s; spread %.3g%%) at %.3g s per s",
                  100 * c.error, to_string(c.metric), 100 * c.floor,
                  c.row.wall_per_simulated_second);
  else
    std::snprintf(line, sizeof line, ": measured %.3g%% at %.3g wall s per s", 100 * c.error,
                  c.row.wall_per_simulated_second);
  p.description = describe_setting(c.row) + line;
  return p;
}

}  // namespace neurocloth
