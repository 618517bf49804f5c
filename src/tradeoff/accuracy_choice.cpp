#include "tradeoff/accuracy_choice.h"

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

AccuracyChoice choose_for_accuracy(const TradeTable& trade, const std::string& trade_path,
                                   double accuracy, const SolverSettings& base,
                                   const std::string& field) {
  char s[512];
  if (!(accuracy > 0) || !std::isfinite(accuracy)) {
    std::snprintf(s, sizeof s,
                  "must be a finite number > 0 (a fraction of the cloth's size), got %g", accuracy);
    throw InputError(trade_path, field, s);
  }
  const double resolution = reference_resolution(trade);
  if (accuracy < resolution) {
    std::snprintf(s, sizeof s,
                  "%g cannot be measured on %s: its reference only converged to %.3g of the "
                  "cloth's size (halving RK4's step still moved it that much)",
                  accuracy, trade.scene.c_str(), resolution);
    throw InputError(trade_path, field, s);
  }
  const std::optional<std::size_t> pick = cheapest_meeting(trade.rows, accuracy);
  if (!pick) {
    const std::optional<std::size_t> best = most_accurate(trade.rows);
    if (best)
      std::snprintf(s, sizeof s,
                    "no measured setting keeps %s within %g; the best achievable is %s with a max "
                    "error of %.3g",
                    trade.scene.c_str(), accuracy, describe_setting(trade.rows[*best]).c_str(),
                    trade.rows[*best].position_error_max);
    else
      std::snprintf(s, sizeof s, "no measured setting of %s finished its run", trade.scene.c_str());
    throw InputError(trade_path, field, s);
  }
  AccuracyChoice c;
  c.row_index = *pick;
  c.row = trade.rows[*pick];
  c.settings = settings_for(c.row, base);
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
