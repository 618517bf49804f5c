// Fuzzes the trade CSV reader, parse_trade_csv(). An accepted trade must hold
// finite measurements (NaN only where the format says so: the errors of a run
// that did not finish, and an unmeasured reference change, read as -1), and
// settings whose step can be run: 1/dt finite, projective's iterations in
// [1, 1000] (none for the other methods), the implicit step's tolerance in
// [1e-14, 0.01] (none for the others), and the counts it was written
// (not truncated to an int), each "# key" written once.
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <iterator>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "fuzz/fuzz_contract.h"
#include "tradeoff/trade_csv.h"

namespace neurocloth::fuzz {
namespace {

void check_trade(const Contract& c, const TradeTable& t) {
  c.finite(t.seconds, "# seconds");
  c.require(t.seconds > 0, "# seconds accepted <= 0");
  c.require(t.samples >= 1, "# samples accepted < 1");
  // A trade is quoted only at its grid (read_sized_trade): none, or a real one.
  c.require(
      (t.grid_rows == 0 && t.grid_cols == 0) || (t.grid_rows >= 2 && t.grid_cols >= 2),
      "# grid accepted as " + std::to_string(t.grid_rows) + "x" + std::to_string(t.grid_cols));
  c.finite(t.cloth_size, "# cloth_size_m");
  c.finite(t.energy_scale, "# energy_scale_j");
  c.finite(t.wall_seconds, "# wall_seconds");
  const ReferenceReport& r = t.reference;
  c.finite(r.dt, "# reference_dt");
  c.finite(r.change, "# reference_change");
  c.finite(r.rms_change, "# reference_rms_change");
  for (double v : r.change_by_sample)
    c.finite(v, "# reference_change_by_sample");
  c.finite(r.target, "# reference_target");
  c.finite(r.wall_seconds, "# reference_wall_seconds");
  c.require(!t.rows.empty(), "a trade accepted with no rows");
  for (std::size_t i = 0; i < t.rows.size(); ++i) {
    const TradeRow& row = t.rows[i];
    const std::string f = "row " + std::to_string(i + 1) + " ";
    c.finite(row.value, f + "value");
    c.finite(row.dt, f + "dt");
    c.require(row.dt > 0, f + "dt accepted <= 0");
    // `simulate --accuracy` runs the picked row's dt: seconds / dt steps.
    c.require(std::isfinite(1.0 / row.dt), f + "dt accepted as " + show(row.dt) +
                                               " (1/dt overflows: the setting cannot be run)");
    c.require(row.steps >= 0 && row.force_evaluations >= 0 && row.rejected_steps >= 0,
              f + "a negative count accepted");
    // Only projective iterates, and a picked row runs at its count: one a scene could ask for.
    c.require(
        row.iterations == 0 ||
            (row.method == "projective" && row.iterations >= 1 && row.iterations <= 1000),
        f + "iterations accepted as " + std::to_string(row.iterations) + " for " + row.method);
    // Only implicit_euler solves, and a picked row runs at its tolerance: one a scene could ask
    // for.
    c.require(
        row.linear_tolerance == 0 ||
            (row.method == "implicit_euler" && row.linear_tolerance >= 1e-14 &&
             row.linear_tolerance <= 1e-2),
        f + "linear_tolerance accepted as " + show(row.linear_tolerance) + " for " + row.method);
    for (double v : {row.position_error_max, row.position_error_rms, row.energy_error,
                     row.wall_per_simulated_second})
      c.require(std::isfinite(v) || (std::isnan(v) && !row.ok()),
                f + "a measurement accepted as " + show(v) + " on a run with status " + row.status);
  }
}

// The "#" lines before the header, without their line ends; blank lines skipped.
std::vector<std::string> metadata_lines(const std::string& text) {
  std::vector<std::string> lines;
  for (std::size_t pos = 0; pos < text.size();) {
    const std::size_t eol = std::min(text.find('\n', pos), text.size());
    std::string line = text.substr(pos, eol - pos);
    pos = eol + 1;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    if (line[0] != '#') break;  // the header: metadata ends
    lines.push_back(std::move(line));
  }
  return lines;
}

// The whole number a "# key: N" line before the header says, as written
// (the last such line wins, as in the reader); nullopt when there is none or
// it is not a plain decimal number.
std::optional<long long> written_count(const std::string& text, const std::string& key) {
  std::optional<long long> value;
  const std::string prefix = "# " + key + ": ";
  for (const std::string& line : metadata_lines(text)) {
    if (line.compare(0, prefix.size(), prefix) != 0 || line.find(": ") != prefix.size() - 2)
      continue;
    errno = 0;
    char* end = nullptr;
    const char* digits = line.c_str() + prefix.size();
    const long long v = std::strtoll(digits, &end, 10);
    value =
        errno == 0 && end != digits && *end == '\0' ? std::optional<long long>(v) : std::nullopt;
  }
  return value;
}

// The first "# key" (one the reader knows, other than sweep_stopped_by, which
// repeats by design) written twice before the header; "" when none is. The
// reader keeps the last, as nlohmann does with a JSON key.
std::string repeated_key(const std::string& text) {
  std::set<std::string> seen;
  for (const std::string& line : metadata_lines(text)) {
    const std::size_t colon = line.find(": ");
    if (colon == std::string::npos || line.compare(0, 2, "# ") != 0) continue;
    const std::string key = line.substr(2, colon - 2);
    static const std::set<std::string> kKeys(std::begin(kTradeMetadataKeys),
                                             std::end(kTradeMetadataKeys));
    if (kKeys.count(key) && !seen.insert(key).second) return key;
  }
  return {};
}

// An accepted count is the one the file wrote, not a truncation of it.
void check_counts(const Contract& c, const TradeTable& t, const std::string& text) {
  const auto samples = written_count(text, "samples");
  if (samples)
    c.require(*samples == t.samples, "# samples: " + std::to_string(*samples) + " accepted as " +
                                         std::to_string(t.samples));
  const std::string repeated = repeated_key(text);
  c.require(repeated.empty(),
            "accepted '# " + repeated + "' written twice (the last silently wins)");
  const auto runs = written_count(text, "reference_runs");
  if (runs)
    c.require(*runs == t.reference.runs, "# reference_runs: " + std::to_string(*runs) +
                                             " accepted as " + std::to_string(t.reference.runs));
}

}  // namespace
}  // namespace neurocloth::fuzz

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace neurocloth;
  const std::string text(reinterpret_cast<const char*>(data), size);
  const auto trade = fuzz::accepted("trade_csv", [&] { return parse_trade_csv(text, "fuzz.csv"); });
  if (!trade) return 0;
  const fuzz::Contract c("trade_csv");
  fuzz::check_trade(c, *trade);
  fuzz::check_counts(c, *trade, text);
  return 0;
}
