#include "tradeoff/pareto_front.h"

#include <algorithm>
#include <cmath>

namespace neurocloth {
namespace {

bool usable(const TradeRow& r) {
  return r.ok() && std::isfinite(r.position_error_max) &&
         std::isfinite(r.wall_per_simulated_second);
}

// a beats b: no worse in both, better in one.
bool beats(const TradeRow& a, const TradeRow& b) {
  const double ca = a.wall_per_simulated_second, cb = b.wall_per_simulated_second;
  const double ea = a.position_error_max, eb = b.position_error_max;
  return ca <= cb && ea <= eb && (ca < cb || ea < eb);
}

}  // namespace

std::vector<std::size_t> pareto_front(const std::vector<TradeRow>& rows) {
  std::vector<std::size_t> front;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    if (!usable(rows[i])) continue;
    bool beaten = false;
    for (std::size_t j = 0; j < rows.size() && !beaten; ++j)
      beaten = j != i && usable(rows[j]) && beats(rows[j], rows[i]);
    if (!beaten) front.push_back(i);
  }
  std::stable_sort(front.begin(), front.end(), [&](std::size_t a, std::size_t b) {
    const TradeRow &ra = rows[a], &rb = rows[b];
    if (ra.wall_per_simulated_second != rb.wall_per_simulated_second)
      return ra.wall_per_simulated_second < rb.wall_per_simulated_second;
    return ra.position_error_max < rb.position_error_max;
  });
  return front;
}

namespace {

// The usable row that `admit` lets through with the smallest (key, tie) pair;
// the first such row when two tie on both.
template <typename Admit>
std::optional<std::size_t> best_row(const std::vector<TradeRow>& rows, Admit admit,
                                    double TradeRow::*key, double TradeRow::*tie) {
  std::optional<std::size_t> best;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const TradeRow& r = rows[i];
    if (!usable(r) || !admit(r)) continue;
    if (best) {
      const TradeRow& b = rows[*best];
      if (!(r.*key < b.*key || (r.*key == b.*key && r.*tie < b.*tie))) continue;
    }
    best = i;
  }
  return best;
}

}  // namespace

std::optional<std::size_t> cheapest_meeting(const std::vector<TradeRow>& rows, double budget) {
  return best_row(
      rows, [budget](const TradeRow& r) { return r.position_error_max <= budget; },
      &TradeRow::wall_per_simulated_second, &TradeRow::position_error_max);
}

std::optional<std::size_t> most_accurate(const std::vector<TradeRow>& rows) {
  return best_row(
      rows, [](const TradeRow&) { return true; }, &TradeRow::position_error_max,
      &TradeRow::wall_per_simulated_second);
}

}  // namespace neurocloth
