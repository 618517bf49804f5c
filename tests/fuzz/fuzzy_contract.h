#pragma once
// What every rule-base reader's harness holds a variable it read to: a finite,
// non-empty range, at least one term, every term's parameters finite and
// valid, and no infinite default. `range` and `term` are the format's words
// for them in findings ("RANGE"/"TERM" in FCL, "Range"/"MF" in .fis).
#include <cmath>
#include <string>

#include "core/fuzzy/linguistic_variable.h"
#include "fuzz/fuzz_contract.h"

namespace neurocloth::fuzz {

inline void check_variable(const Contract& c, const fuzzy::LinguisticVariable& v,
                           const std::string& f, const std::string& range,
                           const std::string& term) {
  c.finite(v.min, f + " " + range + " min");
  c.finite(v.max, f + " " + range + " max");
  c.require(v.min < v.max, f + " " + range + " accepted with min >= max");
  c.require(!v.terms.empty(), f + " accepted with no " + term);
  for (const fuzzy::Term& t : v.terms) {
    for (double p : t.function.params)
      c.finite(p, f + " " + term + " " + t.name + " parameter");
    const std::string problem = t.function.validate();
    c.require(problem.empty(), f + " " + term + " " + t.name + " accepted but invalid: " + problem);
  }
  // NaN is "not given" (FCL's DEFAULT := NC; a .fis has none); infinity is not.
  c.require(!std::isinf(v.default_value), f + " DEFAULT accepted as infinite");
}

}  // namespace neurocloth::fuzz
