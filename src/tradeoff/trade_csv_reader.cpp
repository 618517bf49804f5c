// Reading a trade CSV back (for --accuracy and the chart): every field checked,
// every problem an InputError naming the file, line, column and field. Kept
// apart from trade_csv_writer.cpp: the reader must also take hand-edited and
// older files (absent optional columns, "nan" for "not measured").
#include "tradeoff/trade_csv.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <iterator>
#include <limits>
#include <map>
#include <set>

#include "core/io/csv_fields.h"
#include "core/io/input_error.h"
#include "core/io/physical_limits.h"
#include "core/io/text_file.h"

namespace neurocloth {
namespace {

constexpr std::size_t kColumns = std::size(kTradeColumns);

// One field of a line, with where it starts (1-based column).
struct Field {
  std::string text;
  int column;
};

std::vector<Field> split(const std::string& line) {
  std::vector<Field> fields;
  std::size_t start = 0;
  for (;;) {
    const std::size_t comma = line.find(',', start);
    fields.push_back(
        {line.substr(start, comma == std::string::npos ? std::string::npos : comma - start),
         static_cast<int>(start) + 1});
    if (comma == std::string::npos) return fields;
    start = comma + 1;
  }
}

class Reader {
 public:
  explicit Reader(std::string path) : path_(std::move(path)) {}

  [[noreturn]] void fail(const std::string& field, const std::string& message, int line,
                         int column = 0) const {
    throw InputError(path_, field, message, line, column);
  }

  // A finite number (or nothing, kept as NaN, when `nan_ok`: an empty field,
  // "none", or "nan" as files written before 2026-12 say it), at least `min`
  // (strictly above when `above`).
  double real(const Field& f, const std::string& field, int line, double min, bool above,
              bool nan_ok = false) const {
    if (nan_ok && (f.text.empty() || f.text == "none" || f.text == "nan")) return std::nan("");
    const FieldNumber n = finite_number(f.text);
    if (!n.refusal.empty()) fail(field, n.refusal, line, f.column);
    const double v = n.value;
    if (above ? !(v > min) : !(v >= min))
      fail(field,
           std::string("must be ") + (above ? "> " : ">= ") + show_number(min) + ", got " + f.text,
           line, f.column);
    return v;
  }

  // A whole number in [0, max]: the type it is stored in holds it as written.
  long count(const Field& f, const std::string& field, int line,
             long max = std::numeric_limits<long>::max()) const {
    errno = 0;
    char* end = nullptr;
    const long v = std::strtol(f.text.c_str(), &end, 10);
    if (f.text.empty() || end != f.text.c_str() + f.text.size() || errno == ERANGE || v < 0)
      fail(field, "not a whole number >= 0: '" + f.text + "'", line, f.column);
    if (v > max)
      fail(field, "must be at most " + std::to_string(max) + ", got " + f.text, line, f.column);
    return v;
  }

 private:
  std::string path_;
};

}  // namespace

namespace {

// Reads the file line by line into `table`; every method throws InputError
// naming the line (and column) it stopped at.
class TradeCsvParser {
 public:
  explicit TradeCsvParser(const std::string& path) : in_(path) {
    table_.reference.change = -1;
    std::fill(std::begin(index_), std::end(index_), kAbsent);
  }

  void line(const std::string& text) {
    ++line_;
    if (text.empty()) return;
    if (text[0] == '#') {
      // "# key: value" lines before the header describe the measurement; other
      // comment lines are for people.
      const std::size_t colon = text.find(": ");
      if (!have_header_ && colon != std::string::npos && text.compare(0, 2, "# ") == 0)
        metadata(text.substr(2, colon - 2), {text.substr(colon + 2), static_cast<int>(colon) + 3});
      return;
    }
    const std::vector<Field> f = split(text);
    if (!have_header_)
      header(f, text);
    else
      table_.rows.push_back(row(f, text));
  }

  TradeTable finish() {
    if (!have_header_)
      in_.fail("header", "no header line (" + std::string(kTradeColumns[0]) + ",...) found", line_);
    if (table_.rows.empty()) in_.fail("rows", "no settings after the header line", line_);
    if (table_.floor && table_.floor->members == 0)
      in_.fail("# ensemble",
               "missing: the file has a floor but does not say of how many references", line_);
    return std::move(table_);
  }

 private:
  // A number that may be missing (no two runs compared): kept as -1.
  double maybe_none(const Field& v, const std::string& field) const {
    const double c = in_.real(v, field, line_, 0, false, true);
    return std::isnan(c) ? -1 : c;
  }

  void metadata(const std::string& key, const Field& v) {
    const std::string field = "# " + key;
    // Each describes the one measurement: a second value would silently win.
    static const std::set<std::string> kOnce(std::begin(kTradeMetadataKeys),
                                             std::end(kTradeMetadataKeys));
    if (kOnce.count(key)) {
      const auto [first, fresh] = seen_.emplace(key, line_);
      if (!fresh)
        in_.fail(field, "given twice (first at line " + std::to_string(first->second) + ")", line_,
                 3);
    }
    TradeTable& t = table_;
    ReferenceReport& r = t.reference;
    if (key == "scene") {
      if (v.text.empty()) in_.fail(field, "empty", line_, v.column);
      t.scene = v.text;
      have_.scene = true;
    } else if (key == "scene_file") {
      t.scene_file = v.text;
    } else if (key == "seconds") {
      t.seconds = in_.real(v, field, line_, 0, true);
      have_.seconds = true;
    } else if (key == "samples") {
      t.samples = static_cast<int>(in_.count(v, field, line_, 1000));  // as tradeoff --samples
      if (t.samples < 1) in_.fail(field, "must be >= 1", line_, v.column);
      have_.samples = true;
    } else if (key == "grid") {
      grid(v, field);
    } else if (key == "cloth_size_m") {
      t.cloth_size = in_.real(v, field, line_, 0, true);
    } else if (key == "energy_scale_j") {
      t.energy_scale = in_.real(v, field, line_, 0, true);
    } else if (key == "reference_dt") {
      r.dt = in_.real(v, field, line_, 0, true);
    } else if (key == "reference_change") {
      r.change = maybe_none(v, field);
      have_.change = true;
    } else if (key == "reference_rms_change") {
      r.rms_change = maybe_none(v, field);
    } else if (key == "reference_change_by_sample") {
      for (std::size_t at = 0; at < v.text.size();) {
        const std::size_t space = v.text.find(' ', at);
        const std::size_t end = space == std::string::npos ? v.text.size() : space;
        if (end > at)
          r.change_by_sample.push_back(
              in_.real({v.text.substr(at, end - at), v.column + static_cast<int>(at)}, field, line_,
                       0, false));
        at = end + 1;
      }
    } else if (key == "reference_target") {
      r.target = in_.real(v, field, line_, 0, true);
    } else if (key == "reference_met") {
      if (v.text != "yes" && v.text != "no")
        in_.fail(field, "must be yes or no, got '" + v.text + "'", line_, v.column);
      r.met = v.text == "yes";
      have_.met = true;
    } else if (key == "reference_stopped_by") {
      r.stopped_by = v.text;
    } else if (key == "reference_runs") {
      r.runs = static_cast<int>(in_.count(v, field, line_, std::numeric_limits<int>::max()));
    } else if (key == "reference_wall_seconds") {
      r.wall_seconds = in_.real(v, field, line_, 0, false);
    } else if (key == "sweep_stopped_by") {
      t.sweep_stops.push_back(v.text);
    } else if (key == "wall_seconds") {
      t.wall_seconds = in_.real(v, field, line_, 0, false);
    } else if (key == "ensemble") {
      const long k = in_.count(v, field, line_, kMaxEnsemble);
      if (k < kMinEnsemble)
        in_.fail(field,
                 "must be in [" + std::to_string(kMinEnsemble) + ", " +
                     std::to_string(kMaxEnsemble) + "], got " + v.text,
                 line_, v.column);
      floor().members = static_cast<int>(k);
    } else if (key == "ensemble_shift_m") {
      const double d = in_.real(v, field, line_, 0, true);
      if (d < kMinShift || d > kMaxShift)
        in_.fail(field,
                 "must be in [" + show_number(kMinShift) + ", " + show_number(kMaxShift) +
                     "] m, got " + v.text,
                 line_, v.column);
      floor().shift = d;
    } else if (key == "ensemble_seed") {
      floor().seed = static_cast<std::uint64_t>(in_.count(v, field, line_));
    } else if (key == "ensemble_dt") {
      floor().member_dt = in_.real(v, field, line_, 0, true);
    } else if (key.compare(0, 6, "floor_") == 0) {
      floor_line(key, v, field);
    }
  }

  EnsembleFloor& floor() {
    if (!table_.floor) table_.floor.emplace();
    return *table_.floor;
  }

  // Space-separated figures >= 0, each or "none" (not measured).
  std::vector<double> figures(const Field& v, const std::string& field) const {
    std::vector<double> out;
    for (std::size_t at = 0; at < v.text.size();) {
      const std::size_t space = v.text.find(' ', at);
      const std::size_t end = space == std::string::npos ? v.text.size() : space;
      if (end > at)
        out.push_back(in_.real({v.text.substr(at, end - at), v.column + static_cast<int>(at)},
                               field, line_, 0, false, true));
      at = end + 1;
    }
    return out;
  }

  // "floor_M: MEDIAN P90", "floor_M_median_by_sample: ..." or "floor_M_p90_by_sample: ...".
  void floor_line(const std::string& key, const Field& v, const std::string& field) {
    for (Metric m : kAllMetrics) {
      const std::string base = std::string("floor_") + to_string(m);
      if (key.compare(0, base.size(), base) != 0) continue;
      const std::string rest = key.substr(base.size());
      if (rest != "" && rest != "_median_by_sample" && rest != "_p90_by_sample") continue;
      const auto [first, fresh] = seen_.emplace(key, line_);
      if (!fresh)
        in_.fail(field, "given twice (first at line " + std::to_string(first->second) + ")", line_,
                 3);
      const std::vector<double> f = figures(v, field);
      EnsembleFloor& e = floor();
      if (rest.empty()) {
        if (f.size() != 2)
          in_.fail(field, "must be MEDIAN P90, got '" + v.text + "'", line_, v.column);
        e.median[slot(m)] = f[0];
        e.p90[slot(m)] = f[1];
        return;
      }
      auto& series = rest == "_median_by_sample" ? e.median_by_sample : e.p90_by_sample;
      if (series.size() < f.size()) series.resize(f.size(), unmeasured_metrics());
      for (std::size_t j = 0; j < f.size(); ++j)
        series[j][slot(m)] = f[j];
      return;
    }
    // Other "# floor_..." lines are comments, as any unknown key is.
  }

  // "ROWSxCOLS", each a whole number >= 2 (a grid has at least two nodes a side).
  void grid(const Field& v, const std::string& field) {
    const std::size_t x = v.text.find('x');
    if (x == std::string::npos)
      in_.fail(field, "must be ROWSxCOLS (e.g. 128x128), got '" + v.text + "'", line_, v.column);
    const Field rows{v.text.substr(0, x), v.column};
    const Field cols{v.text.substr(x + 1), v.column + static_cast<int>(x) + 1};
    const long most = std::numeric_limits<int>::max();
    table_.grid_rows = static_cast<int>(in_.count(rows, field, line_, most));
    table_.grid_cols = static_cast<int>(in_.count(cols, field, line_, most));
    if (table_.grid_rows < 2 || table_.grid_cols < 2)
      in_.fail(field, "a grid has at least 2 nodes a side, got '" + v.text + "'", line_, v.column);
  }

  static bool optional(const std::string& name) {
    return std::find(std::begin(kOptionalTradeColumns), std::end(kOptionalTradeColumns), name) !=
           std::end(kOptionalTradeColumns);
  }

  // The columns must come in kTradeColumns' order; only the optional ones may be missing.
  void header(const std::vector<Field>& f, const std::string& text) {
    std::size_t at = 0;
    std::string skipped;  // the optional columns that could have stood where `at` is
    for (std::size_t c = 0; c < kColumns; ++c) {
      const std::string name = kTradeColumns[c];
      if (at < f.size() && f[at].text == name) {
        index_[c] = at++;
        skipped.clear();
        continue;
      }
      if (optional(name)) {
        skipped += "'" + name + "' or ";
        continue;
      }
      in_.fail("header",
               "column " + std::to_string(at + 1) + " must be " + skipped + "'" + name +
                   "', got '" + (at < f.size() ? f[at].text : std::string()) + "'",
               line_, at < f.size() ? f[at].column : static_cast<int>(text.size()) + 1);
    }
    if (f.size() != at)
      in_.fail("header", "more than " + std::to_string(at) + " columns", line_, f[at].column);
    columns_ = at;
    const char* missing = !have_.scene     ? "# scene"
                          : !have_.seconds ? "# seconds"
                          : !have_.samples ? "# samples"
                          : !have_.change  ? "# reference_change"
                          : !have_.met     ? "# reference_met"
                                           : nullptr;
    if (missing) in_.fail(missing, "missing (expected before the header line)", line_);
    have_header_ = true;
  }

  // The header's name for field `i` of a row.
  const char* column_name(std::size_t i) const {
    for (std::size_t c = 0; c < kColumns; ++c)
      if (index_[c] == i) return kTradeColumns[c];
    return "row";
  }

  TradeRow row(const std::vector<Field>& all, const std::string& text) const {
    if (all.size() != columns_)
      in_.fail(
          column_name(std::min(all.size(), columns_)),
          "expected " + std::to_string(columns_) + " fields, found " + std::to_string(all.size()),
          line_, all.size() < columns_ ? static_cast<int>(text.size()) + 1 : all[columns_].column);
    // The fields in kTradeColumns' order; an absent column reads as an empty field.
    std::vector<Field> f(kColumns, Field{"", 0});
    for (std::size_t c = 0; c < kColumns; ++c)
      if (index_[c] != kAbsent) f[c] = all[index_[c]];
    TradeRow r;
    r.method = f[0].text;
    const bool adaptive = is_adaptive_method(r.method);
    if (!is_trade_method(r.method))
      in_.fail("method",
               "unknown method '" + r.method + "' (expected one of: " + trade_method_names() + ")",
               line_, f[0].column);
    r.parameter = f[1].text;
    const char* expected = adaptive ? "safety" : "dt";
    if (r.parameter != expected)
      in_.fail(
          "parameter",
          std::string("must be '") + expected + "' for " + r.method + ", got '" + r.parameter + "'",
          line_, f[1].column);
    r.value = in_.real(f[2], "value", line_, 0, true);
    if (adaptive && r.value > 1)
      in_.fail("value", "a safety factor must be in (0, 1], got " + f[2].text, line_, f[2].column);
    r.dt = in_.real(f[3], "dt", line_, 0, true);
    // --accuracy may run this row: it must be a step a scene could ask for.
    if (!limits::kTimeStep.contains(r.dt))
      in_.fail("dt", limits::kTimeStep.refusal(r.dt), line_, f[3].column);
    if (!adaptive && r.value != r.dt)
      in_.fail("value", "must equal dt for a fixed step, got " + f[2].text, line_, f[2].column);
    r.iterations = iterations(f[4], r.method);
    r.linear_tolerance = tolerance(f[5], r.method);
    r.steps = in_.count(f[6], "steps", line_);
    r.status = f[13].text;
    if (r.status != "ok" && r.status != "diverged" && r.status != "stopped")
      in_.fail("status", "must be ok, diverged or stopped, got '" + r.status + "'", line_,
               f[13].column);
    // A run that did not finish has no error to measure (an empty field).
    const bool nan_ok = !r.ok();
    r.position_error_max = in_.real(f[7], "position_error_max", line_, 0, false, nan_ok);
    r.position_error_rms = in_.real(f[8], "position_error_rms", line_, 0, false, nan_ok);
    r.energy_error = in_.real(f[9], "energy_error", line_, 0, false, nan_ok);
    r.wall_per_simulated_second =
        in_.real(f[10], "wall_per_simulated_second", line_, 0, false, nan_ok);
    r.force_evaluations = in_.count(f[11], "force_evaluations", line_);
    r.rejected_steps = in_.count(f[12], "rejected_steps", line_);
    for (Metric m : kAllMetrics) {
      const std::size_t c = kFirstEnsembleColumn + slot(m);
      r.ensemble[slot(m)] = in_.real(f[c], kTradeColumns[c], line_, 0, false, true);
    }
    return r;
  }

  // The implicit step's tolerance: one a scene could ask for, or empty (a file
  // without the column: the scene's own). The other methods solve no linear
  // system: empty.
  double tolerance(const Field& f, const std::string& method) const {
    if (f.text.empty()) return 0;
    if (method != to_string(IntegratorKind::implicit_euler))
      in_.fail("linear_tolerance",
               "must be empty for " + method + " (only implicit_euler solves), got " + f.text,
               line_, f.column);
    const double v = in_.real(f, "linear_tolerance", line_, 0, true);
    if (!limits::kLinearTolerance.contains(v))
      in_.fail("linear_tolerance", limits::kLinearTolerance.refusal(v), line_, f.column);
    return v;
  }

  // Projective's or vbd's iterations per step: a count a scene could ask for, or
  // empty (a file without the column, or one re-written from it: the scene's
  // own). The other methods do not iterate: empty.
  int iterations(const Field& f, const std::string& method) const {
    if (f.text.empty()) return 0;
    const auto kind = parse_integrator(method);
    if (!kind || !iterates_per_step(*kind))
      in_.fail("iterations",
               "must be empty for " + method + " (only projective and vbd iterate), got " + f.text,
               line_, f.column);
    const long n = in_.count(f, "iterations", line_);
    if (!limits::kIterations.contains(static_cast<double>(n)))
      in_.fail("iterations", limits::kIterations.refusal(static_cast<double>(n)), line_, f.column);
    return static_cast<int>(n);
  }

  static constexpr std::size_t kAbsent = static_cast<std::size_t>(-1);
  Reader in_;
  std::size_t index_[kColumns];      // where each of kTradeColumns is in a row, or kAbsent
  std::size_t columns_ = 0;          // how many the header has
  std::map<std::string, int> seen_;  // metadata key -> its line
  TradeTable table_;
  int line_ = 0;
  bool have_header_ = false;
  struct {
    bool scene = false, seconds = false, samples = false, change = false, met = false;
  } have_;
};

}  // namespace

TradeTable parse_trade_csv(const std::string& text, const std::string& path) {
  TradeCsvParser parser(path);
  for (std::size_t pos = 0; pos < text.size();) {
    const std::size_t eol = text.find('\n', pos);
    std::string line = text.substr(pos, eol == std::string::npos ? std::string::npos : eol - pos);
    pos = eol == std::string::npos ? text.size() : eol + 1;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    parser.line(line);
  }
  return parser.finish();
}

TradeTable read_trade_csv(const std::string& path) {
  return parse_trade_csv(read_text_file(path, "trade file", kMaxTableBytes), path);
}

TradeTable read_sized_trade(const std::string& path, int n) {
  TradeTable t = read_trade_csv(path);
  const std::string asked = std::to_string(n) + " x " + std::to_string(n);
  if (t.grid_rows == 0)
    throw InputError(
        path, "# grid",
        "missing: the file does not say what grid it was measured on (asked for " + asked + ")");
  if (t.grid_rows != n || t.grid_cols != n)
    throw InputError(path, "# grid",
                     "measured on a " + std::to_string(t.grid_rows) + " x " +
                         std::to_string(t.grid_cols) + " grid, not " + asked);
  return t;
}

}  // namespace neurocloth
