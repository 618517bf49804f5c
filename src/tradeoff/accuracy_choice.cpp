#include "tradeoff/accuracy_choice.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>

#include "core/io/asset_paths.h"
#include "core/io/input_error.h"
#include "tradeoff/pareto_front.h"

namespace neurocloth {

double reference_resolution(const TradeTable& trade) {
  return trade.reference.change >= 0 ? trade.reference.change
                                     : std::numeric_limits<double>::infinity();
}

Metric default_metric(const TradeTable& trade) {
  return has_metric(trade, kDefaultMetric) ? kDefaultMetric : Metric::node_max;
}

AccuracyChoice choose_for_accuracy(const TradeTable& trade, const std::string& trade_path,
                                   double accuracy, const SolverSettings& base,
                                   const std::string& field, std::optional<Metric> metric_asked,
                                   const std::string& metric_field) {
  char s[768];
  if (!(accuracy > 0) || !std::isfinite(accuracy)) {
    std::snprintf(s, sizeof s,
                  "must be a finite number > 0 (a fraction of the cloth's size), got %g", accuracy);
    throw InputError(trade_path, field, s);
  }
  const Metric metric = metric_asked.value_or(default_metric(trade));
  const char* name = to_string(metric);
  if (!has_metric(trade, metric))
    throw InputError(trade_path, metric_field,
                     std::string("this trade did not measure ") + name +
                         (trade.floor ? " (the scene has no support to drape over)"
                                      : " (it has no ensemble: only node_max; measure it again "
                                        "with tradeoff --ensemble K)"));
  AccuracyChoice c;
  c.metric = metric;
  c.requested = accuracy;
  c.floor = trade.floor ? trade.floor->p90[slot(metric)] : std::nan("");
  c.target = std::isfinite(c.floor) ? std::max(accuracy, c.floor) : accuracy;
  const double resolution = reference_resolution(trade);
  if (metric == Metric::node_max && c.target < resolution) {
    std::snprintf(s, sizeof s,
                  "%g cannot be measured on %s: its reference only converged to %.3g of the "
                  "cloth's size (halving RK4's step still moved it that much)",
                  accuracy, trade.scene.c_str(), resolution);
    throw InputError(trade_path, field, s);
  }
  const std::optional<std::size_t> pick = cheapest_meeting(trade.rows, c.target, metric);
  if (!pick) {
    const std::optional<std::size_t> best = most_accurate(trade.rows, metric);
    if (best)
      std::snprintf(s, sizeof s,
                    "no measured setting keeps %s within %g (%s)%s; the best achievable is %s "
                    "with %.3g",
                    trade.scene.c_str(), c.target, name,
                    c.target > accuracy ? ", the scene's own spread" : "",
                    describe_setting(trade.rows[*best]).c_str(),
                    row_error(trade.rows[*best], metric));
    else
      std::snprintf(s, sizeof s, "no measured setting of %s finished its run", trade.scene.c_str());
    throw InputError(trade_path, field, s);
  }
  c.row_index = *pick;
  c.row = trade.rows[*pick];
  c.error = row_error(c.row, metric);
  c.settings = settings_for(c.row, base);
  if (c.target > accuracy) {
    std::snprintf(s, sizeof s,
                  "asked %g%%: this scene's own spread is %.3g%% (%s, %d references shifted %g "
                  "mm); picked against %.3g%%",
                  100 * accuracy, 100 * c.floor, name, trade.floor->members,
                  1000 * trade.floor->shift, 100 * c.target);
    c.floor_note = s;
  }
  return c;
}

std::string committed_trade_path(const std::string& scene_path) {
  return assets_directory() + "/tradeoff/" + std::filesystem::path(scene_path).stem().string() +
         ".csv";
}

std::string sized_trade_path(const std::string& scene_path, int n) {
  return assets_directory() + "/tradeoff/" + std::filesystem::path(scene_path).stem().string() +
         "." + std::to_string(n) + ".csv";
}

}  // namespace neurocloth
