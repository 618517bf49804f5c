#pragma once
// Writes a FuzzySystem as a MATLAB / Octave .fis file that read_fis() reads
// back to a system inferring the same numbers (17 significant digits). Throws
// std::invalid_argument, saying what, for a system .fis cannot express:
// stacked hedges, nested or repeated conditions, DEFAULT values, rule blocks
// with different methods. Three things only some readers take: one hedge as
// Octave's code (.05 somewhat, .20 very; Octave reads it, MATLAB does not),
// and, as fuzzylite writes them, a point-list term as 'discretemf' and
// Mamdani and Sugeno outputs together as Type='hybrid' (fuzzylite reads both,
// MATLAB and Octave neither).
#include <string>

#include "core/fuzzy/fuzzy_system.h"

namespace neurocloth::fuzzy {

std::string write_fis(const FuzzySystem& system);

}  // namespace neurocloth::fuzzy
