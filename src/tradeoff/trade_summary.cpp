#include "tradeoff/trade_summary.h"

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
  return fmt("%g", fraction * 100) + "%";
}

std::string trade_summary(const TradeTable& t, const std::string& chart) {
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

  const double resolution = reference_resolution(t);
  md << "| error budget | cheapest setting meeting it | max error | RMS error | s per "
        "simulated s | force evaluations |\n";
  md << "|---|---|---|---|---|---|\n";
  for (double budget : kErrorBudgets) {
    md << "| " << percent(budget) << " | ";
    const auto pick = cheapest_meeting(t.rows, budget);
    if (budget < resolution) {
      md << "not certified: below the reference's resolution (" << g3(resolution)
         << ") | | | | |\n";
    } else if (!pick) {
      const auto best = most_accurate(t.rows);
      md << "none measured";
      if (best)
        md << "; the best: " << describe_setting(t.rows[*best]) << " at "
           << g3(t.rows[*best].position_error_max);
      md << " | | | | |\n";
    } else {
      const TradeRow& r = t.rows[*pick];
      md << describe_setting(r) << " | " << g3(r.position_error_max) << " | "
         << g3(r.position_error_rms) << " | " << g3(r.wall_per_simulated_second) << " | "
         << r.force_evaluations << " |\n";
    }
  }
  md << "\n";

  md << "**Pareto front** (cheapest first; no other setting is both cheaper and more accurate):";
  for (std::size_t i : pareto_front(t.rows))
    md << "\n- " << describe_setting(t.rows[i]) << ": max error "
       << g3(t.rows[i].position_error_max) << ", " << g3(t.rows[i].wall_per_simulated_second)
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
