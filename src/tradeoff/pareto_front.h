#pragma once
// Which settings are worth choosing: cost is seconds of compute per simulated second,
// error the max position error. Only finished rows (status ok) count.
#include <optional>
#include <vector>

#include "tradeoff/trade_table.h"

namespace neurocloth {

// Indices of the rows no other row beats: none is at least as cheap and at
// least as accurate and strictly better in one. Two identical points are both
// on the front (neither beats the other). Ordered by cost, then error, then index.
std::vector<std::size_t> pareto_front(const std::vector<TradeRow>& rows);

// The cheapest row whose max position error is at most `budget`; equal costs go
// to the smaller error, then to the earlier row. nullopt when none meets it.
std::optional<std::size_t> cheapest_meeting(const std::vector<TradeRow>& rows, double budget);

// The row with the smallest max position error; equal errors go to the cheaper,
// then to the earlier row. nullopt when no row finished.
std::optional<std::size_t> most_accurate(const std::vector<TradeRow>& rows);

}  // namespace neurocloth
