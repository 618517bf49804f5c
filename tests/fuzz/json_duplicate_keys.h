#pragma once
// An independent look at a JSON text for an object that names a key twice.
// nlohmann keeps the last value and says nothing, so a reader built on it
// cannot see the duplicate; the harnesses use this to tell when one was
// accepted (a known finding: a typo'd second "dt" silently wins).
#include <string>

namespace neurocloth::fuzz {

// The first key an object repeats (with its object's path, "cloth.grid: rows"),
// or "" when none does or the text is not JSON.
std::string first_duplicate_key(const std::string& text);

}  // namespace neurocloth::fuzz
