#pragma once
// The trade in a few lines of Markdown: how far the reference converged, the
// scene's own spread (with an ensemble), and for error budgets of 10%, 3%, 1%,
// 0.1% and 0.01% in one metric (never below the spread) the cheapest setting
// and its cost.
#include <string>

#include "tradeoff/trade_table.h"

namespace neurocloth {

// `chart` is the chart's file name to link (empty: no link).
std::string trade_summary(const TradeTable& trade, Metric metric, const std::string& chart = "");

// "10%", "0.1%", "0.01%": a budget as people write it.
std::string percent(double fraction);

}  // namespace neurocloth
