// The trade's CSV: a bit-exact round trip, and broken files named by file,
// line, column and field.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "core/io/asset_paths.h"
#include "core/io/input_error.h"
#include "support/hand_made_trade.h"
#include "support/scratch_dir.h"
#include "tradeoff/trade_csv.h"

namespace neurocloth {
namespace {

using test::hand_made_trade;
using test::kNaN;

TradeTable csv_table() {
  TradeTable t = hand_made_trade();
  t.scene_file = "assets/scenes/hand.json";
  t.cloth_size = 1.3435;
  t.energy_scale = 52.45;
  t.grid_rows = t.grid_cols = 32;
  ReferenceReport& r = t.reference;
  r.dt = 6.103515625e-05;
  r.change = 1.07e-10;
  r.change_by_sample = {1e-13, 1.07e-10};
  r.rms_change = 1e-11;
  r.met = true;
  r.runs = 7;
  r.wall_seconds = 0.88;
  r.stopped_by = "target";
  t.wall_seconds = 6.6;
  t.sweep_stops = {"network: levels", "adaptive: error floor"};
  t.rows[1].dt = t.rows[1].value = 0.0009765625;
  t.rows[1].steps = 2048;
  t.rows[1].force_evaluations = 4096;
  t.rows[7].rejected_steps = 12;
  // The implicit step's second knob, swept at each step.
  TradeRow implicit = test::row("implicit_euler", 0.9, 0.02);
  implicit.dt = implicit.value = 0.00390625;
  implicit.linear_tolerance = 1e-6;
  t.rows.push_back(implicit);
  // Projective's second knob, swept at each step.
  TradeRow projective = test::row("projective", 0.7, 0.03);
  projective.dt = projective.value = 0.015625;
  projective.iterations = 4;
  t.rows.push_back(projective);
  return t;
}

// `text` without the column `name`, header and rows: as files written before
// that knob was swept.
std::string without_column(const std::string& text, const std::string& name) {
  std::string out;
  std::size_t index = std::string::npos;  // the column's field index, once the header is seen
  for (std::size_t pos = 0; pos < text.size();) {
    const std::size_t eol = text.find('\n', pos);
    const std::string line = text.substr(pos, eol - pos);
    pos = eol + 1;
    std::vector<std::string> fields;
    for (std::size_t at = 0;;) {
      const std::size_t comma = line.find(',', at);
      fields.push_back(line.substr(at, comma - at));
      if (comma == std::string::npos) break;
      at = comma + 1;
    }
    if (line.rfind("method,", 0) == 0)
      index =
          static_cast<std::size_t>(std::find(fields.begin(), fields.end(), name) - fields.begin());
    if (index == std::string::npos || line.empty() || line[0] == '#') {
      out += line + "\n";
      continue;
    }
    fields.erase(fields.begin() + static_cast<std::ptrdiff_t>(index));
    for (std::size_t k = 0; k < fields.size(); ++k)
      out += (k ? "," : "") + fields[k];
    out += "\n";
  }
  return out;
}

// As files written before the ensemble.
std::string without_ensemble_columns(std::string text) {
  for (Metric m : kAllMetrics)
    text = without_column(text, std::string("ensemble_") + to_string(m));
  return text;
}

// As files written before either second knob was swept (the committed trades
// before issue 41): without the ensemble's columns either.
std::string without_knob_columns(const std::string& text) {
  return without_column(without_column(without_ensemble_columns(text), "linear_tolerance"),
                        "iterations");
}

TEST(TradeoffCsv, RoundTrips) {
  const TradeTable t = csv_table();
  const std::string text = trade_csv(t);
  const TradeTable back = parse_trade_csv(text, "x.csv");
  EXPECT_EQ(trade_csv(back), text);
  EXPECT_EQ(back.scene, "hand");
  EXPECT_EQ(back.scene_file, t.scene_file);
  EXPECT_EQ(back.seconds, 2);
  EXPECT_EQ(back.samples, 8);
  EXPECT_EQ(back.grid_rows, 32);
  EXPECT_EQ(back.grid_cols, 32);
  EXPECT_EQ(back.reference.dt, t.reference.dt);  // settings: exact
  EXPECT_EQ(back.reference.change, t.reference.change);
  EXPECT_EQ(back.reference.change_by_sample, t.reference.change_by_sample);
  EXPECT_TRUE(back.reference.met);
  EXPECT_EQ(back.reference.stopped_by, "target");
  EXPECT_EQ(back.sweep_stops, t.sweep_stops);
  ASSERT_EQ(back.rows.size(), t.rows.size());
  for (std::size_t i = 0; i < t.rows.size(); ++i) {
    SCOPED_TRACE(i);
    const TradeRow &a = t.rows[i], &b = back.rows[i];
    EXPECT_EQ(b.method, a.method);
    EXPECT_EQ(b.parameter, a.parameter);
    EXPECT_EQ(b.value, a.value);
    EXPECT_EQ(b.dt, a.dt);
    EXPECT_EQ(b.iterations, a.iterations);
    EXPECT_EQ(b.linear_tolerance, a.linear_tolerance);
    EXPECT_EQ(b.steps, a.steps);
    EXPECT_EQ(b.status, a.status);
    EXPECT_EQ(b.force_evaluations, a.force_evaluations);
    EXPECT_EQ(b.rejected_steps, a.rejected_steps);
    if (a.ok()) {
      EXPECT_NEAR(b.position_error_max, a.position_error_max, 1e-6 * a.position_error_max);
      EXPECT_NEAR(b.wall_per_simulated_second, a.wall_per_simulated_second,
                  1e-6 * a.wall_per_simulated_second);
    } else {
      EXPECT_TRUE(std::isnan(b.position_error_max));
    }
  }
}

// The InputError parse_trade_csv throws for `text`, or a failure.
std::optional<InputError> csv_error(const std::string& text) {
  try {
    parse_trade_csv(text, "broken.csv");
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "accepted:\n" << text;
  return std::nullopt;
}

// `text` with the first `from` on line `line` (1-based) replaced by `to`.
std::string edit_line(std::string text, int line, const std::string& from, const std::string& to) {
  std::size_t at = 0;
  for (int l = 1; l < line; ++l)
    at = text.find('\n', at) + 1;
  const std::size_t hit = text.find(from, at);
  EXPECT_LT(hit, text.find('\n', at)) << "test bug: '" << from << "' not on line " << line;
  return text.replace(hit, from.size(), to);
}

int line_of(const std::string& text, const std::string& start) {
  const std::size_t at = text.find("\n" + start);
  EXPECT_NE(at, std::string::npos) << start;
  return static_cast<int>(std::count(text.begin(), text.begin() + at + 1, '\n')) + 1;
}

struct BrokenCsv {
  const char* what;
  const char* line_start;  // the line edited
  const char* from;
  const char* to;
  const char* field;
  const char* at;  // the error's column is where this first is on the edited line ("": its end)
  const char* message;
};

TEST(TradeoffCsv, BrokenFilesNameFileLineColumnAndField) {
  const std::string good = trade_csv(csv_table());
  const BrokenCsv cases[] = {
      {"a word for a number", "verlet,", "0.01,", "0.0x1,", "position_error_max", "0.0x1",
       "not a number: '0.0x1'"},
      {"an unknown method", "verlet,", "verlet", "leapfrog", "method", "leapfrog",
       "unknown method"},
      {"the wrong parameter", "adaptive,", "safety", "dt", "parameter", "dt", "must be 'safety'"},
      {"a safety above 1", "adaptive,", "0.25", "1.5", "value", "1.5", "(0, 1]"},
      {"a negative step", "network,", "0.001,0.001", "0.001,-0.001", "dt", "-0.001", "must be > 0"},
      {"a fraction of a step count", "network,", ",0,", ",1.5,", "steps", "1.5", "whole number"},
      {"no error on a finished run", "rk4,dt,0.001,0.001,,,0,0.05", "0.05", "nan",
       "position_error_max", "nan", "NaN or infinite: 'nan'"},
      {"more samples than an int holds", "# samples", "8", "4294967304", "# samples", "4294967304",
       "must be at most 1000"},
      {"a step below the floor", "network,", "0.001,0.001", "0.001,1e-12", "dt", "1e-12",
       "microsecond"},
      {"an unknown status", "rk4,dt,0.001,0.001,,,0,0.05", ",ok", ",fine", "status", "fine",
       "must be ok, diverged or stopped"},
      {"a missing field", "network,", ",0,ok,,,,,,,", ",ok,,,,,,,", "ensemble_energy", "",
       "expected 21 fields, found 20"},
      {"a misspelt column", "method,", "position_error_rms", "position_error_rsm", "header",
       "position_error_rsm", "column 9 must be 'position_error_rms'"},
      {"iterations that are not a count", "projective,", ",4,", ",4.5,", "iterations", "4.5",
       "not a whole number >= 0: '4.5'"},
      {"no iterations", "projective,", ",4,", ",0,", "iterations", "0,", "must be in [1, 1000]"},
      {"too many iterations", "projective,", ",4,", ",1001,", "iterations", "1001",
       "must be in [1, 1000]"},
      {"iterations for a method that does not iterate", "verlet,", "0.0009765625,,",
       "0.0009765625,3,", "iterations", "3,", "must be empty for verlet"},
      {"a misspelt optional column", "method,", "iterations", "iterashuns", "header", "iterashuns",
       "column 5 must be 'iterations' or 'linear_tolerance' or 'steps', got 'iterashuns'"},
      {"a tolerance that is not a number", "implicit_euler,dt,0.0039", ",1e-06,", ",1e-6x,",
       "linear_tolerance", "1e-6x", "not a number: '1e-6x'"},
      {"a tolerance of 0", "implicit_euler,dt,0.0039", ",1e-06,", ",0,", "linear_tolerance", "0,",
       "must be > 0"},
      {"too loose a tolerance", "implicit_euler,dt,0.0039", ",1e-06,", ",0.5,", "linear_tolerance",
       "0.5", "must be in [1e-14, 0.01]"},
      {"a tolerance for a method that solves no system", "verlet,", "0.0009765625,,,",
       "0.0009765625,,1e-6,", "linear_tolerance", "1e-6", "must be empty for verlet"},
      {"a bad metadata value", "# seconds", "2", "two", "# seconds", "two", "not a number: 'two'"},
      {"a grid without its x", "# grid", "32x32", "32by32", "# grid", "32by32", "ROWSxCOLS"},
      {"a grid of one node a side", "# grid", "32x32", "1x32", "# grid", "1x32", "at least 2"},
      {"a grid side that is not a count", "# grid", "32x32", "32x3.5", "# grid", "3.5",
       "not a whole number"},
      {"reference_met neither yes nor no", "# reference_met", "yes", "maybe", "# reference_met",
       "maybe", "yes or no"},
  };
  for (const BrokenCsv& c : cases) {
    SCOPED_TRACE(c.what);
    const int line = line_of(good, c.line_start);
    const std::string text = edit_line(good, line, c.from, c.to);
    std::size_t start = 0;
    for (int l = 1; l < line; ++l)
      start = text.find('\n', start) + 1;
    const std::string edited = text.substr(start, text.find('\n', start) - start);
    const int column = static_cast<int>(*c.at ? edited.find(c.at) + 1 : edited.size() + 1);
    const auto e = csv_error(text);
    if (!e) continue;
    EXPECT_EQ(e->file(), "broken.csv");
    EXPECT_EQ(e->line(), line) << e->what();
    EXPECT_EQ(e->field(), c.field) << e->what();
    EXPECT_EQ(e->column(), column) << e->what();
    const std::string what = e->what();
    EXPECT_EQ(what.rfind("broken.csv:" + std::to_string(line) + ":", 0), 0u) << what;
    EXPECT_NE(what.find(c.message), std::string::npos) << what;
  }
}

// A number too small for a normal double is written as the denormal it is and
// read back as that denormal (a field is refused only for NaN, infinity or text).
TEST(TradeoffCsv, ADenormalErrorReadsBack) {
  TradeTable t = csv_table();
  const double tiny = std::numeric_limits<double>::denorm_min();
  ASSERT_TRUE(t.rows[0].ok());
  t.rows[0].position_error_max = tiny;
  EXPECT_EQ(parse_trade_csv(trade_csv(t), "x.csv").rows[0].position_error_max, tiny);
}

// A setting that did not finish has no error: the file says so with an empty
// field, never "nan" or "inf" (no file of ours holds them); and the files
// written before that, with "nan", still read.
TEST(TradeoffCsv, WritesNoNaNOrInfinity) {
  TradeTable t = csv_table();
  t.reference.change = -1;  // never compared
  ASSERT_FALSE(t.rows[4].ok());
  t.rows[4].wall_per_simulated_second = std::numeric_limits<double>::infinity();
  const std::string text = trade_csv(t);
  for (const char* bad : {"nan", "inf", "NaN", "Inf"})
    EXPECT_EQ(text.find(bad), std::string::npos) << bad << " in:\n" << text;
  bool diverged = false;
  for (const TradeRow& row : t.rows)
    diverged = diverged || !row.ok();
  ASSERT_TRUE(diverged) << "the hand-made trade needs a row that did not finish";
  const TradeTable back = parse_trade_csv(text, "x.csv");
  EXPECT_EQ(back.reference.change, -1);
  for (std::size_t i = 0; i < t.rows.size(); ++i)
    if (!t.rows[i].ok()) {
      EXPECT_TRUE(std::isnan(back.rows[i].position_error_max)) << i;
    }

  // Empty is "not measured" only where a run did not finish.
  const int finished = line_of(text, "rk4,dt,0.001,0.001,,,0,0.05");
  const auto e = csv_error(edit_line(text, finished, "0.05,", ","));
  ASSERT_TRUE(e);
  EXPECT_EQ(e->line(), finished);
  EXPECT_EQ(e->field(), "position_error_max");
  EXPECT_NE(e->message().find("not a number: ''"), std::string::npos) << e->what();

  // As files written before 2026-12 say it: "nan", and no iterations column.
  std::string legacy = without_knob_columns(text);
  for (std::size_t at; (at = legacy.find(",,")) != std::string::npos;)
    legacy.replace(at, 2, ",nan,");
  for (std::size_t at; (at = legacy.find(": none\n")) != std::string::npos;)
    legacy.replace(at, 7, ": nan\n");
  ASSERT_NE(legacy, text);
  const TradeTable legacy_back = parse_trade_csv(legacy, "old.csv");
  for (std::size_t i = 0; i < t.rows.size(); ++i)
    if (!t.rows[i].ok()) {
      EXPECT_TRUE(std::isnan(legacy_back.rows[i].position_error_max)) << i;
    }
  EXPECT_EQ(without_knob_columns(trade_csv(legacy_back)), without_knob_columns(text));
}

// A measurement has one scene, one duration...: a second value for a key
// would silently win (found by fuzzing). Sweep stops may repeat.
TEST(TradeoffCsv, AMetadataKeyGivenTwiceIsNamed) {
  const std::string good = trade_csv(csv_table());
  const int line = line_of(good, "# samples");
  const auto e = csv_error(edit_line(good, line, "# samples: 8", "# samples: 8\n# seconds: 9"));
  ASSERT_TRUE(e);
  EXPECT_EQ(e->line(), line + 1);
  EXPECT_EQ(e->field(), "# seconds");
  EXPECT_NE(e->message().find("given twice (first at line " +
                              std::to_string(line_of(good, "# seconds")) + ")"),
            std::string::npos)
      << e->what();
  EXPECT_EQ(parse_trade_csv(good, "x.csv").sweep_stops.size(), 2u);
}

TEST(TradeoffCsv, MissingPartsAreNamed) {
  const std::string good = trade_csv(csv_table());
  const std::string no_scene = edit_line(good, 2, "# scene: hand", "# nothing here");
  auto e = csv_error(no_scene);
  ASSERT_TRUE(e);
  EXPECT_EQ(e->field(), "# scene");
  EXPECT_EQ(e->line(), line_of(good, "method,"));

  e = csv_error(good.substr(0, good.find("method,")));
  ASSERT_TRUE(e);
  EXPECT_EQ(e->field(), "header");

  e = csv_error(good.substr(0, good.find("network,")));
  ASSERT_TRUE(e);
  EXPECT_EQ(e->field(), "rows");

  e = csv_error("");
  ASSERT_TRUE(e);
  EXPECT_EQ(e->field(), "header");

  try {
    read_trade_csv("/no/such/trade.csv");
    ADD_FAILURE() << "read a file that does not exist";
  } catch (const InputError& err) {
    EXPECT_EQ(err.file(), "/no/such/trade.csv");
  }
}

TEST(TradeoffCsv, BlankLinesCountTowardsLineNumbers) {
  std::string text = trade_csv(csv_table());
  const int line = line_of(text, "verlet,");
  text.insert(text.find("method,"), "\n\n");
  const auto e = csv_error(edit_line(text, line + 2, "verlet", "leapfrog"));
  ASSERT_TRUE(e);
  EXPECT_EQ(e->line(), line + 2) << e->what();
}

TEST(TradeoffCsv, AcceptsWindowsLineEndsAndPeoplesComments) {
  std::string text = trade_csv(csv_table());
  text.insert(text.find("method,"), "# measured on a quiet afternoon\n");
  std::string crlf;
  for (char c : text)
    crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
  const TradeTable t = parse_trade_csv(crlf, "x.csv");
  EXPECT_EQ(t.rows.size(), csv_table().rows.size());
  EXPECT_EQ(t.rows.back().status, "ok");
}

TEST(TradeoffCsv, ProjectiveRowsKeepTheirIterations) {
  const std::string text = trade_csv(csv_table());
  EXPECT_NE(text.find("\nmethod,parameter,value,dt,iterations,linear_tolerance,steps,"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("\nprojective,dt,0.015625,0.015625,4,,0,"), std::string::npos) << text;
  EXPECT_NE(text.find("\nverlet,dt,0.0009765625,0.0009765625,,,2048,"), std::string::npos) << text;
  const TradeTable back = parse_trade_csv(text, "x.csv");
  EXPECT_EQ(back.rows.back().iterations, 4);
  EXPECT_EQ(settings_for(back.rows.back(), SolverSettings{}).iterations, 4);
  EXPECT_EQ(describe_setting(back.rows.back()), "projective 4 it., dt 0.01562 s");
}

// The tolerance is written as the shortest text that reads back as the same
// double, and a picked implicit row runs at it.
TEST(TradeoffCsv, ImplicitRowsKeepTheirLinearTolerance) {
  const std::string text = trade_csv(csv_table());
  EXPECT_NE(text.find("\nimplicit_euler,dt,0.00390625,0.00390625,,1e-06,0,"), std::string::npos)
      << text;
  const TradeTable back = parse_trade_csv(text, "x.csv");
  const TradeRow& implicit = back.rows[back.rows.size() - 2];
  ASSERT_EQ(implicit.method, "implicit_euler");
  EXPECT_EQ(implicit.linear_tolerance, 1e-6);
  EXPECT_EQ(settings_for(implicit, SolverSettings{}).linear_tolerance, 1e-6);
  EXPECT_EQ(describe_setting(implicit), "implicit_euler tol 1e-6, dt 0.003906 s");
  // Only implicit_euler solves a linear system: a tolerance elsewhere is refused.
  TradeRow verlet = back.rows[1];
  verlet.linear_tolerance = 1e-6;
  EXPECT_THROW(settings_for(verlet, SolverSettings{}), std::invalid_argument);
}

// Files written before the column (the committed trades among them) still read:
// every row's iterations is 0, and a projective row runs at the scene's own.
TEST(TradeoffCsv, AFileWithoutTheIterationsColumnReads) {
  const std::string old = without_knob_columns(trade_csv(csv_table()));
  ASSERT_NE(old.find("\nmethod,parameter,value,dt,steps,"), std::string::npos) << old;
  const TradeTable back = parse_trade_csv(old, "old.csv");
  ASSERT_EQ(back.rows.size(), csv_table().rows.size());
  for (const TradeRow& r : back.rows) {
    EXPECT_EQ(r.iterations, 0) << describe_setting(r);
    EXPECT_EQ(r.linear_tolerance, 0) << describe_setting(r);
  }
  EXPECT_EQ(back.rows[1].steps, 2048) << "the columns after it are where they were";
  SolverSettings scene;
  scene.iterations = 12;
  const SolverSettings s = settings_for(back.rows.back(), scene);
  EXPECT_EQ(s.integrator, IntegratorKind::projective);
  EXPECT_EQ(s.iterations, 12);
  // An implicit row runs at the scene's own tolerance.
  SolverSettings implicit_scene;
  implicit_scene.linear_tolerance = 1e-8;
  const TradeRow& implicit = back.rows[back.rows.size() - 2];
  ASSERT_EQ(implicit.method, "implicit_euler");
  EXPECT_EQ(settings_for(implicit, implicit_scene).linear_tolerance, 1e-8);
  EXPECT_EQ(settings_for(implicit, SolverSettings{}).linear_tolerance, 1e-10);
  EXPECT_EQ(describe_setting(implicit), "implicit_euler, dt 0.003906 s");
  // Written again, the columns are there and the knob fields are empty (the
  // scene's own): that reads too.
  const std::string again = trade_csv(back);
  EXPECT_NE(again.find("\nprojective,dt,0.015625,0.015625,,,0,"), std::string::npos) << again;
  EXPECT_EQ(trade_csv(parse_trade_csv(again, "again.csv")), again);
  // A missing field is named after the file's own columns.
  const int line = line_of(old, "network,");
  std::string shorter = old;
  const std::size_t row_at = shorter.find("\nnetwork,") + 1;
  shorter.erase(shorter.find(",ok\n", row_at), 3);
  const auto e = csv_error(shorter);
  ASSERT_TRUE(e);
  EXPECT_EQ(e->line(), line);
  EXPECT_EQ(e->field(), "status");
  EXPECT_NE(e->message().find("expected 12 fields, found 11"), std::string::npos) << e->what();
}

// A trade holds at the grid it was measured on: read for another size (or from
// a file that does not say), it is refused, naming the file and the field.
TEST(TradeoffCsv, ASizedTradeRefusesAnotherSize) {
  const std::string path = test::scratch_path("at32.csv");
  std::ofstream(path, std::ios::trunc) << trade_csv(csv_table());
  EXPECT_EQ(read_sized_trade(path, 32).grid_rows, 32);
  try {
    read_sized_trade(path, 128);
    ADD_FAILURE() << "a 32 x 32 trade was read for 128 x 128";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), path);
    EXPECT_EQ(e.field(), "# grid");
    EXPECT_NE(e.message().find("measured on a 32 x 32 grid, not 128 x 128"), std::string::npos)
        << e.what();
  }
  TradeTable unsized = csv_table();
  unsized.grid_rows = unsized.grid_cols = 0;
  const std::string old = test::scratch_path("unsized.csv");
  std::ofstream(old, std::ios::trunc) << trade_csv(unsized);
  EXPECT_EQ(read_trade_csv(old).grid_rows, 0);  // still a trade at the scene's own size
  try {
    read_sized_trade(old, 32);
    ADD_FAILURE() << "a trade that does not say its grid was read as 32 x 32";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), old);
    EXPECT_EQ(e.field(), "# grid");
    EXPECT_NE(e.message().find("missing"), std::string::npos) << e.what();
  }
}

TEST(TradeoffCsv, TheCommittedTradesRead) {
  for (const char* scene : {"hanging", "table_drape", "flag"}) {
    SCOPED_TRACE(scene);
    const TradeTable t = read_trade_csv(assets_directory() + "/tradeoff/" + scene + ".csv");
    EXPECT_EQ(t.scene, scene);
    EXPECT_FALSE(t.rows.empty());
  }
}

}  // namespace
}  // namespace neurocloth
