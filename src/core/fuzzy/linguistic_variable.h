#pragma once
// A linguistic variable ("mass", "spring_constant"): a range and named terms
// ("small", "big"). Outputs also carry how they are defuzzified and the value
// they keep when no rule fires.
#include <limits>
#include <string>
#include <vector>

#include "core/fuzzy/membership_function.h"

namespace neurocloth::fuzzy {

struct Term {
  std::string name;
  MembershipFunction function;
};

enum class Defuzzification {
  centroid,          // FCL COG: Mamdani, centre of gravity of the accumulated set
  weighted_average,  // FCL COGS: Takagi-Sugeno, activations weighting singletons or linear
                     // consequents
};

struct LinguisticVariable {
  std::string name;
  double min = 0, max = 1;  // RANGE; inputs outside it are clamped (and reported)
  std::vector<Term> terms;
  // Outputs only.
  Defuzzification method = Defuzzification::centroid;
  // The value when no rule fires (FCL DEFAULT). NaN means "not given": then the
  // middle of the range is used, and reported.
  double default_value = std::numeric_limits<double>::quiet_NaN();

  int term_index(const std::string& term) const {
    for (std::size_t i = 0; i < terms.size(); ++i)
      if (terms[i].name == term) return static_cast<int>(i);
    return -1;
  }
};

}  // namespace neurocloth::fuzzy
