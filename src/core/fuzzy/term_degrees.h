#pragma once
// A value of a linguistic variable said in its own words: the terms it belongs
// to and how much ("elasticity 0.71: big 0.8, medium 0.2"), what a fit of a
// material's inputs reports.
#include <string>
#include <vector>

#include "core/fuzzy/linguistic_variable.h"

namespace neurocloth::fuzzy {

struct TermDegree {
  std::string term;
  double degree = 0;  // membership in (0, 1]
};

// The terms x belongs to with a degree above zero, largest first (ties in the
// variable's order). x is clamped to the variable's RANGE, as inference does.
std::vector<TermDegree> term_degrees(const LinguisticVariable& variable, double x);

// "elasticity 0.712: big 0.8, medium 0.2" (values to 3 significant digits,
// degrees to 2 decimals; "no term" when none holds x).
std::string in_words(const LinguisticVariable& variable, double x);

}  // namespace neurocloth::fuzzy
