#pragma once
// Reads a rule base in the Fuzzy Control Language (IEC 61131-7), with the
// common extensions for named membership functions, and the dialects
// fuzzylite and jFuzzyLogic write (fcl_dialect.cpp). Grammar, extensions and
// dialects: docs/fcl.md. Every error is an InputError naming file, line, column and what
// was expected; nothing half-loaded is ever returned.
#include <string>

#include "core/fuzzy/fuzzy_system.h"

namespace neurocloth::fuzzy {

FuzzySystem read_fcl(const std::string& path);
// `path` names the text in messages.
FuzzySystem parse_fcl(const std::string& text, const std::string& path);

}  // namespace neurocloth::fuzzy
