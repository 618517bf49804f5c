#include "tradeoff/pareto_front.h"

#include <algorithm>
#include <cmath>

namespace neurocloth {
namespace {

bool usable(const TradeRow& r, Metric m) {
  return r.ok() && std::isfinite(row_error(r, m)) && std::isfinite(r.wall_per_simulated_second);
}

// a beats b: no worse in both, better in one.
bool beats(const TradeRow& a, const TradeRow& b, Metric m) {
  const double ca = a.wall_per_simulated_second, cb = b.wall_per_simulated_second;
  const double ea = row_error(a, m), eb = row_error(b, m);
  return ca <= cb && ea <= eb && (ca < cb || ea < eb);
}

}  // namespace

std::vector<std::size_t> pareto_front(const std::vector<TradeRow>& rows, Metric metric) {
  std::vector<std::size_t> front;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    if (!usable(rows[i], metric)) continue;
    bool beaten = false;
    for (std::size_t j = 0; j < rows.size() && !beaten; ++j)
      beaten = j != i && usable(rows[j], metric) && beats(rows[j], rows[i], metric);
    if (!beaten) front.push_back(i);
  }
  std::stable_sort(front.begin(), front.end(), [&](std::size_t a, std::size_t b) {
    const TradeRow &ra = rows[a], &rb = rows[b];
    if (ra.wall_per_simulated_second != rb.wall_per_simulated_second)
      return ra.wall_per_simulated_second < rb.wall_per_simulated_second;
    return row_error(ra, metric) < row_error(rb, metric);
  });
  return front;
}

namespace {

// The usable row that `admit` lets through with the smallest (key, tie) pair;
// the first such row when two tie on both.
template <typename Admit, typename Key, typename Tie>
std::optional<std::size_t> best_row(const std::vector<TradeRow>& rows, Metric metric, Admit admit,
                                    Key key, Tie tie) {
  std::optional<std::size_t> best;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const TradeRow& r = rows[i];
    if (!usable(r, metric) || !admit(r)) continue;
    if (best) {
      const TradeRow& b = rows[*best];
      if (!(key(r) < key(b) || (key(r) == key(b) && tie(r) < tie(b)))) continue;
    }
    best = i;
  }
  return best;
}

}  // namespace

std::optional<std::size_t> cheapest_meeting(const std::vector<TradeRow>& rows, double budget,
                                            Metric metric) {
  const auto cost = [](const TradeRow& r) { return r.wall_per_simulated_second; };
  const auto error = [metric](const TradeRow& r) { return row_error(r, metric); };
  return best_row(
      rows, metric, [&](const TradeRow& r) { return error(r) <= budget; }, cost, error);
}

std::optional<std::size_t> most_accurate(const std::vector<TradeRow>& rows, Metric metric) {
  const auto cost = [](const TradeRow& r) { return r.wall_per_simulated_second; };
  const auto error = [metric](const TradeRow& r) { return row_error(r, metric); };
  return best_row(
      rows, metric, [](const TradeRow&) { return true; }, error, cost);
}

}  // namespace neurocloth
