#pragma once
// One entry point for rule-base files, picking the format by extension:
// ".fis" (MATLAB / Octave, fis_reader.h), or else FCL (IEC 61131-7 and the
// fuzzylite / jFuzzyLogic dialects, fcl_reader.h). docs/fcl.md.
#include <string>

#include "core/fuzzy/fuzzy_system.h"

namespace neurocloth::fuzzy {

enum class RuleFormat { fcl, fis };

// ".fis" (any case) is fis; every other name, extension or none, is FCL.
RuleFormat rule_format(const std::string& path);

// Throws InputError as the reader does.
FuzzySystem read_rule_file(const std::string& path);

// Writes through a temporary file (nothing half-written). Throws
// std::invalid_argument when the format cannot hold the system (nothing is
// written then) and std::runtime_error when the file cannot be written.
void write_rule_file(const FuzzySystem& system, const std::string& path);

}  // namespace neurocloth::fuzzy
