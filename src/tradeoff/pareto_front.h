#pragma once
// Which settings are worth choosing: cost is seconds of compute per simulated second,
// error the row's in a metric (row_error, trade_table.h). Only finished rows
// (status ok) with an error in that metric count.
#include <optional>
#include <vector>

#include "tradeoff/trade_table.h"

namespace neurocloth {

// Indices of the rows no other row beats: none is at least as cheap and at
// least as accurate and strictly better in one. Two identical points are both
// on the front (neither beats the other). Ordered by cost, then error, then index.
std::vector<std::size_t> pareto_front(const std::vector<TradeRow>& rows, Metric metric);

// The cheapest row whose error is at most `budget`; equal costs go
// to the smaller error, then to the earlier row. nullopt when none meets it.
std::optional<std::size_t> cheapest_meeting(const std::vector<TradeRow>& rows, double budget,
                                            Metric metric);

// The row with the smallest error; equal errors go to the cheaper,
// then to the earlier row. nullopt when no row finished.
std::optional<std::size_t> most_accurate(const std::vector<TradeRow>& rows, Metric metric);

}  // namespace neurocloth
