#pragma once
// Writes a FuzzySystem as a MATLAB / Octave .fis file that read_fis() reads
// back to a system inferring the same numbers (17 significant digits). Throws
// std::invalid_argument, saying what, for a system .fis cannot express:
// stacked hedges, nested or repeated conditions, point-list terms, DEFAULT
// values, rule blocks with different methods, Mamdani and Sugeno outputs
// mixed. One hedge is written as Octave's code (.05 somewhat, .20 very),
// which Octave reads and MATLAB does not.
#include <string>

#include "core/fuzzy/fuzzy_system.h"

namespace neurocloth::fuzzy {

std::string write_fis(const FuzzySystem& system);

}  // namespace neurocloth::fuzzy
