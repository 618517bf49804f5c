// Writing the trade as CSV (trade_csv.h says what the file holds). Kept apart
// from trade_csv_reader.cpp: what is written is settled by the sweep, what is
// read must also survive hand-edited and older files.
#include "tradeoff/trade_csv.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iterator>
#include <sstream>

namespace neurocloth {
namespace {

// Projective's iterations, or an empty field for the methods that do not
// iterate (and for a projective row read from a file without the column).
std::string iterations_field(int iterations) {
  return iterations > 0 ? std::to_string(iterations) : "";
}

// The implicit step's tolerance as the shortest text that reads back as the
// same double (1e-06, not 9.9999999999999995e-07), or an empty field for the
// other methods (and for an implicit row read from a file without the column).
std::string tolerance_field(double tolerance) {
  if (tolerance == 0) return "";
  char s[40];
  for (int digits = 1; digits <= 17; ++digits) {
    std::snprintf(s, sizeof s, "%.*g", digits, tolerance);
    if (std::strtod(s, nullptr) == tolerance) break;
  }
  return s;
}

// "Not measured" (a run that did not finish, a reference never compared) is an
// empty field: a file of ours never holds NaN or Inf where a number belongs.
std::string number(double v, int digits) {
  if (!std::isfinite(v)) return "";
  char s[40];
  std::snprintf(s, sizeof s, "%.*g", digits, v);
  return s;
}

// A floor's figure, or "none" where the metric was not measured (no support).
std::string or_none(double v) {
  return std::isfinite(v) ? number(v, 6) : "none";
}

// Text that must stay on its line and in its field.
std::string one_line(std::string s) {
  for (char& c : s)
    if (c == '\n' || c == '\r') c = ' ';
  return s;
}

}  // namespace

std::string trade_csv(const TradeTable& t) {
  std::ostringstream s;
  const ReferenceReport& r = t.reference;
  s << "# neurocloth tradeoff: speed against accuracy (docs/tradeoff.md)\n";
  s << "# scene: " << one_line(t.scene) << "\n";
  s << "# scene_file: " << one_line(t.scene_file) << "\n";
  s << "# seconds: " << number(t.seconds, 17) << "\n";
  s << "# samples: " << t.samples << "\n";
  if (t.grid_rows > 0) s << "# grid: " << t.grid_rows << "x" << t.grid_cols << "\n";
  s << "# cloth_size_m: " << number(t.cloth_size, 6) << "\n";
  s << "# energy_scale_j: " << number(t.energy_scale, 6) << "\n";
  s << "# reference_dt: " << number(r.dt, 17) << "\n";
  // "none": no two finished runs were compared.
  s << "# reference_change: " << (r.change >= 0 ? number(r.change, 6) : "none") << "\n";
  s << "# reference_rms_change: " << (r.rms_change >= 0 ? number(r.rms_change, 6) : "none") << "\n";
  if (!r.change_by_sample.empty()) {
    s << "# reference_change_by_sample:";
    for (double c : r.change_by_sample)
      s << " " << number(c, 3);
    s << "\n";
  }
  s << "# reference_target: " << number(r.target, 6) << "\n";
  s << "# reference_met: " << (r.met ? "yes" : "no") << "\n";
  s << "# reference_stopped_by: " << one_line(r.stopped_by) << "\n";
  s << "# reference_runs: " << r.runs << "\n";
  s << "# reference_wall_seconds: " << number(r.wall_seconds, 6) << "\n";
  s << "# wall_seconds: " << number(t.wall_seconds, 6) << "\n";
  if (t.floor) {
    const EnsembleFloor& f = *t.floor;
    s << "# ensemble: " << f.members << "\n";
    s << "# ensemble_shift_m: " << number(f.shift, 17) << "\n";
    s << "# ensemble_seed: " << f.seed << "\n";
    s << "# ensemble_dt: " << number(f.member_dt, 17) << "\n";
    for (Metric m : kAllMetrics) {
      const std::string key = std::string("# floor_") + to_string(m);
      s << key << ": " << or_none(f.median[slot(m)]) << " " << or_none(f.p90[slot(m)]) << "\n";
      s << key << "_median_by_sample:";
      for (const MetricValues& v : f.median_by_sample)
        s << " " << or_none(v[slot(m)]);
      s << "\n" << key << "_p90_by_sample:";
      for (const MetricValues& v : f.p90_by_sample)
        s << " " << or_none(v[slot(m)]);
      s << "\n";
    }
  }
  for (const std::string& stop : t.sweep_stops)
    s << "# sweep_stopped_by: " << one_line(stop) << "\n";
  for (std::size_t c = 0; c < std::size(kTradeColumns); ++c)
    s << (c ? "," : "") << kTradeColumns[c];
  s << "\n";
  for (const TradeRow& row : t.rows) {
    s << row.method << ',' << row.parameter << ',' << number(row.value, 17) << ','
      << number(row.dt, 17) << ',' << iterations_field(row.iterations) << ','
      << tolerance_field(row.linear_tolerance) << ',' << row.steps << ','
      << number(row.position_error_max, 6) << ',' << number(row.position_error_rms, 6) << ','
      << number(row.energy_error, 6) << ',' << number(row.wall_per_simulated_second, 6) << ','
      << row.force_evaluations << ',' << row.rejected_steps << ',' << row.status;
    for (Metric m : kAllMetrics)
      s << ',' << number(row.ensemble[slot(m)], 6);
    s << "\n";
  }
  return s.str();
}

}  // namespace neurocloth
