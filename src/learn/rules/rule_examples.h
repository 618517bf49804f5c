#pragma once
// Examples a rule base should reproduce, for `tune-rules` (docs/learning.md,
// "Tuning a rule base from examples"): a CSV whose header names every input of
// the rule base and the outputs to tune, one example per row.
//
//   mass,elasticity,force,spring_constant,viscosity
//   0.2,0.5,3,240,0.08
//
// Read against the rule base, so every error names the file, the line, the
// column and the field: an unknown or repeated name, a missing input, no
// output, a row of the wrong length, a cell that is not a finite number, an
// input or a target outside its variable's RANGE (refused, not clamped: the
// engine would clamp the input and the example would teach something else;
// a centroid never leaves its range), no rows, too many rows.
#include <cstddef>
#include <string>
#include <vector>

#include "core/fuzzy/fuzzy_system.h"

namespace neurocloth {

inline constexpr std::size_t kMaxExampleRows = 1000000;
inline constexpr std::size_t kMaxExampleBytes = 64u << 20;

struct RuleExamples {
  std::string path;
  std::vector<int> outputs;  // the named outputs' indices in the rule base, in column order
  std::vector<std::vector<double>> inputs;   // [example][input], in the rule base's input order
  std::vector<std::vector<double>> targets;  // [example][k]: what outputs[k] should give
  std::vector<int> lines;                    // each example's line in the file

  std::size_t size() const { return inputs.size(); }
};

// Throws InputError (file, line, column, field) for anything the header lists.
RuleExamples read_rule_examples(const std::string& path, const fuzzy::FuzzySystem& system);
// `path` names the text in messages.
RuleExamples parse_rule_examples(const std::string& text, const std::string& path,
                                 const fuzzy::FuzzySystem& system);

}  // namespace neurocloth
