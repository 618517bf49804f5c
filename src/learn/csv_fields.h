#pragma once
// The small pieces every CSV reader of the learning stage shares (markers,
// rule-base examples): a line's fields, trimmed, and a field quoted safely
// for a one-line message.
#include <functional>
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

// Walks a CSV text line by line: a UTF-8 byte order mark skipped, each line
// trimmed, blank lines and '#' comments left out; `header` gets the first
// line, `row` every other, each with its line number. Returns the number of
// the last line. Throws InputError naming `path` and field "header" with
// `no_header` when there is no header line.
int walk_csv_lines(const std::string& text, const std::string& path, const std::string& no_header,
                   const std::function<void(std::string_view line, int number)>& header,
                   const std::function<void(std::string_view line, int number)>& row);

}  // namespace neurocloth
