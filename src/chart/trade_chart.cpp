#include "chart/trade_chart.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "tradeoff/accuracy_choice.h"
#include "tradeoff/pareto_front.h"

namespace neurocloth {

Rgb method_colour(const std::string& method) {
  if (method == "network") return {0.12, 0.47, 0.71};                // blue
  if (method == "explicit_euler") return {1.00, 0.50, 0.05};         // orange
  if (method == "verlet") return {0.17, 0.63, 0.17};                 // green
  if (method == "rk4") return {0.84, 0.15, 0.16};                    // red
  if (method == "implicit_euler") return {0.58, 0.40, 0.74};         // purple
  if (method == "projective") return {0.09, 0.75, 0.81};             // cyan
  if (method == "vbd") return {0.74, 0.74, 0.13};                    // olive
  if (method == kAdaptiveMethod) return {0.55, 0.34, 0.29};          // brown
  if (method == kAdaptiveImplicitMethod) return {0.89, 0.47, 0.76};  // pink
  return {0.5, 0.5, 0.5};
}

Rgb line_colour(const TradeRow& row) {
  const Rgb c = method_colour(row.method);
  double shade = 1;
  if (row.iterations != 0)
    // Projective's (and vbd's) lines in its colour, darker the fewer iterations: 1 at 40%, 30
    // and more at full strength, log-spaced between.
    shade =
        0.4 + 0.6 * std::min(1.0, std::log(static_cast<double>(row.iterations)) / std::log(30.0));
  else if (row.linear_tolerance != 0)
    // The implicit step's in its purple, darker the looser the solve: 0.01 at
    // 40%, 1e-10 and tighter at full strength, log-spaced between.
    shade = 0.4 + 0.6 * std::clamp((-2 - std::log10(row.linear_tolerance)) / 8, 0.0, 1.0);
  return {c.r * shade, c.g * shade, c.b * shade};
}

ChartSpec trade_chart_spec(const TradeTable& t, Metric metric) {
  ChartSpec spec;
  char title[200];
  std::snprintf(title, sizeof title, "%s: error against cost (%g s simulated)", t.scene.c_str(),
                t.seconds);
  spec.title = title;
  // The run's thread CPU time unless its step had threads (docs/tradeoff.md).
  spec.x_label = "seconds of compute per simulated second";
  spec.y_label =
      metric == Metric::node_max && !t.floor
          ? "max position error / cloth size"
          : std::string(to_string(metric)) + " to the ensemble / " + metric_meaning(metric);
  spec.ring_legend = "Pareto front";
  const std::vector<std::size_t> front = pareto_front(t.rows, metric);
  // One series per line (a method, or projective at one iterations count), in
  // the order the lines first appear.
  for (std::size_t i = 0; i < t.rows.size(); ++i) {
    const TradeRow& r = t.rows[i];
    if (!r.ok()) continue;
    const std::string name = line_name(r);
    auto s = std::find_if(spec.series.begin(), spec.series.end(),
                          [&](const ChartSeries& c) { return c.name == name; });
    if (s == spec.series.end()) {
      spec.series.push_back({name, line_colour(r), {}});
      s = spec.series.end() - 1;
    }
    const bool on_front = std::find(front.begin(), front.end(), i) != front.end();
    s->points.push_back({r.wall_per_simulated_second, row_error(r, metric), on_front});
  }
  // A line none of whose settings finished still gets its legend entry, saying so.
  for (const TradeRow& r : t.rows)
    if (std::none_of(spec.series.begin(), spec.series.end(),
                     [&](const ChartSeries& c) { return c.name == line_name(r); }))
      spec.series.push_back({line_name(r), line_colour(r), {}});
  for (ChartSeries& s : spec.series) {
    if (s.points.empty()) s.name += " (none finished)";
  }
  for (ChartSeries& s : spec.series)
    std::stable_sort(s.points.begin(), s.points.end(),
                     [](const ChartPoint& a, const ChartPoint& b) { return a.x < b.x; });
  if (t.floor && std::isfinite(t.floor->p90[slot(metric)])) {
    char band[160];
    std::snprintf(band, sizeof band, "the scene's own spread (%d references, %g mm shifts)",
                  t.floor->members, 1000 * t.floor->shift);
    spec.bands.push_back({t.floor->median[slot(metric)], t.floor->p90[slot(metric)], band});
  }
  // The resolution is the converged reference's, in node distance.
  if (metric == Metric::node_max && !t.reference.met && t.reference.change > 0)
    spec.rules.push_back({t.reference.change, "reference resolution"});
  return spec;
}

void write_trade_chart(const TradeTable& trade, Metric metric, std::ostream& out,
                       const std::string& name) {
  LogLogChart(trade_chart_spec(trade, metric)).write_png(out, name);
}

void write_trade_chart(const TradeTable& trade, Metric metric, const std::string& path) {
  LogLogChart(trade_chart_spec(trade, metric)).write_png(path);
}

}  // namespace neurocloth
