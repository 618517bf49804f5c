#pragma once
// Picks the cheapest measured setting that keeps a scene within an accuracy:
// what `simulate --accuracy E` and the viewer's accuracy slider do. The
// accuracy is the max position error over the compared times and free nodes,
// relative to the cloth's size (0.01 = 1%).
#include <optional>
#include <string>

#include "tradeoff/trade_table.h"

namespace neurocloth {

// The budgets the summary reports: 10%, 1%, 0.1%, 0.01%.
inline constexpr double kErrorBudgets[] = {0.1, 0.01, 0.001, 0.0001};

// The smallest error the trade can vouch for: the reference's own change between
// its last two halvings (infinity when it never compared two runs). An error
// smaller than this is within the reference's own uncertainty.
double reference_resolution(const TradeTable& trade);

struct AccuracyChoice {
  std::size_t row_index = 0;
  TradeRow row;
  SolverSettings settings;  // the scene's own, with the picked integrator, step, safety
};

// The cheapest setting of `trade` meeting `accuracy` (pareto_front.h's rule), on top
// of `base`. Throws InputError naming `trade_path` and `field` when `accuracy` is not
// a finite number > 0, lies below the reference's resolution, or no measured setting
// meets it (the message names the best achievable).
AccuracyChoice choose_for_accuracy(const TradeTable& trade, const std::string& trade_path,
                                   double accuracy, const SolverSettings& base,
                                   const std::string& field = "--accuracy");

// Where a shipped scene's committed trade lives: assets/tradeoff/<scene file stem>.csv
// (whether or not it exists).
std::string committed_trade_path(const std::string& scene_path);
// Where the trade of a shipped scene resized to n x n (resized_grid) lives:
// assets/tradeoff/<scene file stem>.<n>.csv. A trade holds at the resolution it
// was measured at only; read it with read_sized_trade (trade_csv.h).
std::string sized_trade_path(const std::string& scene_path, int n);

}  // namespace neurocloth
