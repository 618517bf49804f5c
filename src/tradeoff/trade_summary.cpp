#include "tradeoff/trade_summary.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "tradeoff/accuracy_choice.h"
#include "tradeoff/pareto_front.h"

namespace neurocloth {
namespace {

std::string fmt(const char* format, double v) {
  char s[64];
  std::snprintf(s, sizeof s, format, v);
  return s;
}

std::string g3(double v) {
  return fmt("%.3g", v);
}

void reference_paragraph(std::ostringstream& md, const TradeTable& t) {
  const ReferenceReport& r = t.reference;
  md << "**Reference:** RK4 at dt = " << g3(r.dt) << " s (" << r.runs << " runs, "
     << fmt("%.1f", r.wall_seconds) << " s run cost). ";
  if (r.change < 0) {
    md << "No two finished runs could be compared, so no error here is certified.\n\n";
    return;
  }
  md << "Halving the step from " << g3(2 * r.dt) << " s to " << g3(r.dt)
     << " s moved no node, at any compared time, by more than " << g3(r.change)
     << " of the cloth's size";
  if (r.met)
    md << ": the " << g3(r.target) << " target was **met**.";
  else
    md << ": the " << g3(r.target) << " target was **not met** (stopped by its "
       << (r.stopped_by.empty() ? std::string("limit") : r.stopped_by) << "). Errors below "
       << g3(r.change)
       << " cannot be told apart from the reference's own, and budgets below it are not "
          "certified.";
  md << "\n\n";
  if (!r.change_by_sample.empty()) {
    md << "That change at each compared time:";
    for (std::size_t j = 0; j < r.change_by_sample.size(); ++j)
      md << (j ? ", " : " ") << "t = " << g3(t.seconds * (j + 1) / r.change_by_sample.size())
         << " s: " << g3(r.change_by_sample[j]);
    md << ".\n\n";
  }
}

}  // namespace

std::string percent(double fraction) {
  return fmt("%.3g", fraction * 100) + "%";
}

namespace {

void floor_paragraph(std::ostringstream& md, const TradeTable& t) {
  const EnsembleFloor& f = *t.floor;
  md << "**The scene's own spread:** " << f.members << " references, each the scene with its "
     << "cloth shifted " << g3(1000 * f.shift) << " mm in a seeded horizontal direction (seed "
     << f.seed << "), run by RK4 at dt = " << g3(f.member_dt)
     << " s. Their distances from each other, pair by pair, over the run (the worst compared "
        "time; node_rms over all). An error at or below the 90th percentile cannot be told from "
        "where the cloth was put: that is the floor.\n\n";
  md << "| metric | of | median | 90th percentile (the floor) |\n|---|---|---|---|\n";
  for (Metric m : kAllMetrics) {
    if (!std::isfinite(f.p90[slot(m)])) continue;
    md << "| " << to_string(m) << " | " << metric_meaning(m) << " | " << g3(f.median[slot(m)])
       << " | " << g3(f.p90[slot(m)]) << " |\n";
  }
  md << "\n";
}

}  // namespace

std::string trade_summary(const TradeTable& t, Metric metric, const std::string& chart) {
  std::ostringstream md;
  md << "# Speed against accuracy: " << t.scene << "\n\n";
  md << "Every integrator over a sweep of fixed steps (projective and vbd at several iterations "
        "counts per step as well) and the paper's adaptive propagation over a sweep of its safety "
        "factor, "
     << g3(t.seconds) << " s of `" << t.scene_file << "` each. Positions are compared with the "
     << "reference at " << t.samples << " times (every " << g3(t.seconds / t.samples)
     << " s); errors are relative to the cloth's size, " << g3(t.cloth_size)
     << " m (its bounding-box diagonal at the start). Cost is seconds per simulated second on "
        "the machine that measured it: the running thread's CPU time when the step has one "
        "thread, else wall time (the median of "
     << kTimingRepeats << " identical runs for runs under " << kShortRunSeconds << " s).\n\n";
  if (!chart.empty()) md << "![error against cost](" << chart << ")\n\n";
  reference_paragraph(md, t);
  if (t.floor) floor_paragraph(md, t);

  const char* name = to_string(metric);
  const double floor = t.floor ? t.floor->p90[slot(metric)] : std::nan("");
  const double resolution = reference_resolution(t);
  md << "Budgets in **" << name << "**"
     << (t.floor ? " (a setting's distance to the ensemble: "
                   "the median over its references)"
                 : "")
     << ":\n\n";
  md << "| error budget | cheapest setting meeting it | " << name
     << " | node max against the reference | s per simulated s | within the floor |\n";
  md << "|---|---|---|---|---|---|\n";
  bool floor_row = false;  // budgets below the floor all pick against it: said once
  for (double budget : kErrorBudgets) {
    const double target = std::isfinite(floor) ? std::max(budget, floor) : budget;
    if (target > budget) {
      if (floor_row) continue;
      floor_row = true;
      md << "| " << percent(budget) << " and below: the floor, " << percent(target) << " | ";
    } else {
      md << "| " << percent(budget) << " | ";
    }
    const auto pick = cheapest_meeting(t.rows, target, metric);
    if (metric == Metric::node_max && !t.floor && budget < resolution) {
      md << "not certified: below the reference's resolution (" << g3(resolution)
         << ") | | | | |\n";
    } else if (!pick) {
      const auto best = most_accurate(t.rows, metric);
      md << "none measured";
      if (best)
        md << "; the best: " << describe_setting(t.rows[*best]) << " at "
           << g3(row_error(t.rows[*best], metric));
      md << " | | | | |\n";
    } else {
      const TradeRow& r = t.rows[*pick];
      const double e = row_error(r, metric);
      md << describe_setting(r) << " | " << g3(e) << " | " << g3(r.position_error_max) << " | "
         << g3(r.wall_per_simulated_second) << " | "
         << (std::isfinite(floor) ? (e <= floor ? "yes" : "no") : "") << " |\n";
    }
  }
  md << "\n";

  md << "**Pareto front** in " << name
     << " (cheapest first; no other setting is both cheaper and more accurate):";
  for (std::size_t i : pareto_front(t.rows, metric))
    md << "\n- " << describe_setting(t.rows[i]) << ": " << name << " "
       << g3(row_error(t.rows[i], metric)) << ", " << g3(t.rows[i].wall_per_simulated_second)
       << " s per simulated s";
  md << "\n\n";

  // Where each line broke down: the settings that diverged or ran out of steps.
  bool first = true;
  for (const TradeRow& r : t.rows)
    if (!r.ok()) {
      md << (first ? "Settings that did not finish: " : "; ") << describe_setting(r) << " ("
         << r.status << ")";
      first = false;
    }
  if (!first) md << ".\n\n";
  if (!t.sweep_stops.empty()) {
    md << "Each sweep halves its step (or safety) until it has enough (docs/tradeoff.md):";
    for (std::size_t i = 0; i < t.sweep_stops.size(); ++i)
      md << (i ? "; " : " ") << t.sweep_stops[i];
    md << ".\n\n";
  }
  md << "Measured in " << fmt("%.1f", t.wall_seconds) << " s of wall time.\n";
  return md.str();
}

}  // namespace neurocloth
