#pragma once
// The trade's chart: the error in one metric against seconds of compute per
// simulated second, log-log, one line per method (projective: one per
// iterations count), the Pareto front ringed and joined, the scene's own spread
// as a band (its references' median to 90th percentile, with an ensemble), the
// reference's resolution as a dashed rule when it did not reach its target.
#include <iosfwd>
#include <string>

#include "chart/loglog_chart.h"
#include "tradeoff/trade_table.h"

namespace neurocloth {

// Each method's colour, the same in every chart (black is the Pareto front's).
Rgb method_colour(const std::string& method);
// A row's line: its method's colour (projective's shaded by its iterations,
// implicit_euler's by its CG tolerance).
Rgb line_colour(const TradeRow& row);

ChartSpec trade_chart_spec(const TradeTable& trade, Metric metric);

// The chart as PNG bytes on `out`. Throws std::runtime_error naming `name`
// (the file the bytes are for) when it cannot be drawn.
void write_trade_chart(const TradeTable& trade, Metric metric, std::ostream& out,
                       const std::string& name);
// The chart as the PNG file `path`, whole or not at all.
void write_trade_chart(const TradeTable& trade, Metric metric, const std::string& path);

}  // namespace neurocloth
