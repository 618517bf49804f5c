#pragma once
// Reads a MATLAB / Octave Fuzzy Logic Toolbox rule base (.fis: [System],
// [Input1..n], [Output1..m], [Rules]) into a FuzzySystem, and what
// fuzzylite's FisExporter adds to the format (Type='hybrid', 'discretemf',
// 'rampmf'). What is read and how
// it maps: docs/fcl.md, "Rule files from other tools". Every error is an
// InputError naming file, line and field ("[Input2] MF3"); nothing half-loaded
// is ever returned, and what this engine cannot evaluate (bisector, pimf, ...)
// is refused by name.
#include <string>

#include "core/fuzzy/fuzzy_system.h"

namespace neurocloth::fuzzy {

FuzzySystem read_fis(const std::string& path);
// `path` names the text in messages.
FuzzySystem parse_fis(const std::string& text, const std::string& path);

}  // namespace neurocloth::fuzzy
