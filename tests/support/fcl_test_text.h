#pragma once
// The FCL text the reader tests edit, and how they check an error: one
// construct per line, so each edit knows the line and column its error must
// name. Shared by fcl_reader_test.cpp (what reads) and fcl_reader_error_test.cpp
// (what is refused).
#include <gtest/gtest.h>

#include <algorithm>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/fuzzy/formats/fcl_reader.h"
#include "core/io/input_error.h"

namespace neurocloth::fuzzy::fcl_test {

inline const std::string kPath = "base.fcl";

// One thing per line, so an edit knows the line and column its error must name.
inline const std::string kBase = R"(FUNCTION_BLOCK cloth
VAR_INPUT
  mass : REAL;
  force : REAL;
END_VAR
VAR_OUTPUT
  stiffness : REAL;
  damping : REAL;
END_VAR
FUZZIFY mass
  RANGE := (0 .. 2);
  TERM light := trian 0 0 1;
  TERM heavy := trape 0.5 1 2 2;
END_FUZZIFY
FUZZIFY force
  RANGE := (-10 .. 10);
  TERM small := gauss 0 2;
  TERM big := sigm 1 5;
END_FUZZIFY
DEFUZZIFY stiffness
  RANGE := (1 .. 1000);
  TERM low := trian 1 50 200;
  TERM high := trian 100 500 1000;
  METHOD : COG;
  DEFAULT := 100;
END_DEFUZZIFY
DEFUZZIFY damping
  RANGE := (0 .. 1);
  TERM none := 0;
  TERM lin := linear 0.1 force 0.01;
  METHOD : COGS;
END_DEFUZZIFY
RULEBLOCK rules
  AND : MIN;
  RULE 1 : IF mass IS heavy THEN stiffness IS high;
  RULE 2 : IF force IS NOT very small THEN damping IS lin WITH 0.5;
END_RULEBLOCK
END_FUNCTION_BLOCK
)";

using Edits = std::vector<std::pair<std::string, std::string>>;

inline std::string edited(const Edits& edits, std::string text = kBase) {
  for (const auto& [from, to] : edits) {
    const auto at = text.find(from);
    EXPECT_NE(at, std::string::npos) << "test bug: '" << from << "' is not in the text";
    if (at != std::string::npos) text.replace(at, from.size(), to);
  }
  return text;
}

// 1-based line and column of the only occurrence of `needle`.
inline std::pair<int, int> position_of(const std::string& text, const std::string& needle) {
  const auto at = text.find(needle);
  EXPECT_NE(at, std::string::npos) << "test bug: '" << needle << "' is not in the text";
  EXPECT_EQ(text.find(needle, at + 1), std::string::npos)
      << "test bug: '" << needle << "' is not unique";
  if (at == std::string::npos) return {0, 0};
  const auto line_start = text.rfind('\n', at);
  const int line = 1 + static_cast<int>(std::count(text.begin(), text.begin() + at, '\n'));
  const auto column = line_start == std::string::npos ? at + 1 : at - line_start;
  return {line, static_cast<int>(column)};
}

inline std::optional<InputError> parse_error(const std::string& text) {
  try {
    parse_fcl(text, kPath);
  } catch (const InputError& e) {
    return e;
  } catch (const std::exception& e) {
    ADD_FAILURE() << "expected InputError, got: " << e.what();
    return std::nullopt;
  }
  ADD_FAILURE() << "expected InputError, the text was accepted:\n" << text;
  return std::nullopt;
}

// The error is at the start of `at` in `text`, names `field`, and says `message`.
inline void expect_error(const std::string& text, const std::string& field, const std::string& at,
                         const std::string& message) {
  const auto e = parse_error(text);
  if (!e) return;
  const auto [line, column] = position_of(text, at);
  EXPECT_EQ(e->file(), kPath);
  EXPECT_EQ(e->field(), field) << e->what();
  EXPECT_EQ(e->line(), line) << e->what();
  EXPECT_EQ(e->column(), column) << e->what();
  EXPECT_NE(e->message().find(message), std::string::npos) << e->what();
  const std::string where = kPath + ":" + std::to_string(line) + ":" + std::to_string(column);
  EXPECT_EQ(std::string(e->what()).rfind(where, 0), 0u) << e->what();
}

// kBase from the first `begin` through the next `end`, inclusive.
inline std::string section(const std::string& begin, const std::string& end) {
  const auto from = kBase.find(begin);
  const auto to = kBase.find(end, from);
  return kBase.substr(from, to + end.size() - from);
}

}  // namespace neurocloth::fuzzy::fcl_test
