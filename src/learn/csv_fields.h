#pragma once
// The small pieces every CSV reader of the learning stage shares (markers,
// rule-base examples): a line's fields, trimmed, and a field quoted safely
// for a one-line message.
#include <string>
#include <string_view>
#include <vector>

namespace neurocloth {

// Without leading and trailing spaces, tabs and carriage returns (CRLF files).
std::string_view trimmed(std::string_view s);
// The comma-separated fields of one line, each trimmed.
std::vector<std::string_view> split_fields(std::string_view line);
// A field quoted for a one-line message: at most 40 bytes, control bytes (a
// NUL, a carriage return, a terminal escape in a binary file) as \xNN.
std::string shown(std::string_view s);

}  // namespace neurocloth
