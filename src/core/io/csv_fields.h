#pragma once
// The small pieces every CSV reader shares (markers, rule-base examples, the
// trade): a line's fields, trimmed; a field quoted safely for a one-line
// message; a field read as a finite number. Each reader still throws its own
// InputError, since only it knows the file, line, column and field name.
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

// A whole field read as a finite double, or why it is not one.
struct FieldNumber {
  double value = 0;
  // Empty when `value` is the field's number; else the message for the
  // caller's InputError, the field shown in it: "not a number: 'x'" (empty, or
  // more than a number) or "NaN or infinite: 'x'" ("nan", "inf", or beyond a
  // double's range, which strtod reads as infinity).
  std::string refusal;
};
// strtod's syntax (leading spaces, "1e3", hex), which must take the whole field.
FieldNumber finite_number(std::string_view field);

// Walks a text line by line: a UTF-8 byte order mark skipped, each line
// trimmed, blank lines and '#' comments left out; `each` gets every other
// line with its number. Returns the number of the last line. What the CSV
// readers and the XYZ reader share.
int walk_text_lines(const std::string& text, const std::string& path,
                    const std::function<void(std::string_view line, int number)>& each);

// Walks a CSV text line by line: a UTF-8 byte order mark skipped, each line
// trimmed, blank lines and '#' comments left out; `header` gets the first
// line, `row` every other, each with its line number. Returns the number of
// the last line. Throws InputError naming `path` and field "header" with
// `no_header` when there is no header line.
int walk_csv_lines(const std::string& text, const std::string& path, const std::string& no_header,
                   const std::function<void(std::string_view line, int number)>& header,
                   const std::function<void(std::string_view line, int number)>& row);

}  // namespace neurocloth
