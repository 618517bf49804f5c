#pragma once
// The Solver panel's accuracy slider: instead of choosing a time step by hand,
// the user asks for an accuracy (the largest position error, as a fraction of
// the cloth's size) and gets the cheapest setting the scene's measured trade
// says meets it. The trade is what `neurocloth-cli tradeoff` wrote for the
// scene (assets/tradeoff/<scene file stem>.csv; docs/tradeoff.md); the pick is
// core's choose_for_accuracy, the same as `simulate --accuracy`.
#include <optional>
#include <string>

#include "runtime/sim_command.h"
#include "tradeoff/trade_table.h"

namespace neurocloth {

struct AccuracyTrade {
  std::optional<TradeTable> table;
  std::string path;  // where it was looked for
  std::string note;  // when there is none (or it does not read): why, in one line
  // The slider's range: the loosest budget the summary reports (10%) down to the
  // finest accuracy the trade can vouch for.
  double loosest = 0.1, finest = 0.1;
};

// Never throws: a missing or broken trade leaves `table` empty and says why.
// For a cloth resized to n x n (`resized_to` = n), the trade measured at that
// size (sized_trade_path), never the scene's own: its errors are another cloth's.
AccuracyTrade load_accuracy_trade(const std::string& scene_path, int resized_to = 0);

struct AccuracyPick {
  SetSolver command;
  std::string description;  // "rk4, dt 0.000977 s: measured 0.6% at 0.055 wall s per s"
};

// Throws InputError naming the trade file when `accuracy` is outside what the
// trade can vouch for (the message names the best achievable).
AccuracyPick pick_for_accuracy(const AccuracyTrade& trade, double accuracy,
                               const SolverSettings& scene_solver);

}  // namespace neurocloth
