#pragma once
// Picks the cheapest measured setting that keeps a scene within an accuracy:
// what `simulate --accuracy E` and the viewer's accuracy slider do. The
// accuracy is an error in one metric (cloth_metrics.h; 0.01 = 1% of the
// cloth's size), never asked tighter than the scene's own spread: a trade with
// an ensemble picks against max(E, its floor) and says so.
#include <optional>
#include <string>

#include "tradeoff/trade_table.h"

namespace neurocloth {

// The budgets the summary reports: 10%, 3%, 1%, 0.1%, 0.01%.
inline constexpr double kErrorBudgets[] = {0.1, 0.03, 0.01, 0.001, 0.0001};

// The smallest error the trade can vouch for: the reference's own change between
// its last two halvings (infinity when it never compared two runs). An error
// smaller than this is within the reference's own uncertainty.
double reference_resolution(const TradeTable& trade);

struct AccuracyChoice {
  std::size_t row_index = 0;
  TradeRow row;
  SolverSettings settings;  // the scene's own, with the picked integrator, step, safety
  Metric metric = Metric::node_max;
  double requested = 0;  // E
  double floor = 0;      // the scene's spread in the metric (p90); NaN without an ensemble
  double target = 0;     // what was picked against: max(E, floor)
  double error = 0;      // the picked row's, in the metric
  // "asked 1%: this scene's own spread is 2.4%; picked against 2.4%" when E was
  // below the floor; empty otherwise.
  std::string floor_note;
  bool within_floor() const { return error <= floor; }
};

// The metric a trade's picks use unless told: kDefaultMetric when the trade
// measured it, else node_max (a trade without an ensemble).
Metric default_metric(const TradeTable& trade);

// The cheapest setting of `trade` meeting max(`accuracy`, the floor) in
// `metric` (default_metric when unset; pareto_front.h's rule), on top of `base`.
// Throws InputError naming `trade_path` and `field` when `accuracy` is not a
// finite number > 0, lies below the reference's resolution (node_max), or no
// measured setting meets it (the message names the best achievable); naming
// `metric_field` when the trade did not measure `metric`.
AccuracyChoice choose_for_accuracy(const TradeTable& trade, const std::string& trade_path,
                                   double accuracy, const SolverSettings& base,
                                   const std::string& field = "--accuracy",
                                   std::optional<Metric> metric = std::nullopt,
                                   const std::string& metric_field = "--metric");

// Where a shipped scene's committed trade lives: assets/tradeoff/<scene file stem>.csv
// (whether or not it exists).
std::string committed_trade_path(const std::string& scene_path);
// Where the trade of a shipped scene resized to n x n (resized_grid) lives:
// assets/tradeoff/<scene file stem>.<n>.csv. A trade holds at the resolution it
// was measured at only; read it with read_sized_trade (trade_csv.h).
std::string sized_trade_path(const std::string& scene_path, int n);

}  // namespace neurocloth
