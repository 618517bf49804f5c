#pragma once
// Writes a FuzzySystem as FCL that read_fcl() reads back to the same system
// (numbers with 17 significant digits, so the round trip is exact).
#include <string>

#include "core/fuzzy/fuzzy_system.h"

namespace neurocloth::fuzzy {

std::string write_fcl(const FuzzySystem& system);

}  // namespace neurocloth::fuzzy
