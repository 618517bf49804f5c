#include "core/io/csv_fields.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>

#include "core/io/input_error.h"

namespace neurocloth {

std::string_view trimmed(std::string_view s) {
  const auto space = [](char c) { return c == ' ' || c == '\t' || c == '\r'; };
  while (!s.empty() && space(s.front()))
    s.remove_prefix(1);
  while (!s.empty() && space(s.back()))
    s.remove_suffix(1);
  return s;
}

std::vector<std::string_view> split_fields(std::string_view line) {
  std::vector<std::string_view> fields;
  for (std::size_t at = 0;;) {
    const std::size_t comma = line.find(',', at);
    fields.push_back(
        trimmed(line.substr(at, comma == std::string_view::npos ? comma : comma - at)));
    if (comma == std::string_view::npos) return fields;
    at = comma + 1;
  }
}

std::string shown(std::string_view s) {
  std::string out = "'";
  for (const char c : s.substr(0, 40)) {
    const auto u = static_cast<unsigned char>(c);
    if (u < 0x20 || u == 0x7f) {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02x", u);
      out += hex;
    } else {
      out += c;
    }
  }
  return out + (s.size() > 40 ? "...'" : "'");
}

FieldNumber finite_number(std::string_view field) {
  const std::string s(field);  // strtod needs the terminating NUL
  char* end = nullptr;
  const double v = std::strtod(s.c_str(), &end);
  if (s.empty() || end != s.c_str() + s.size()) return {0, "not a number: " + shown(field)};
  // strtod reads "nan" and "inf", and overflows to infinity (ERANGE).
  if (!std::isfinite(v)) return {0, "NaN or infinite: " + shown(field)};
  // A finite result with ERANGE is an underflow: the nearest double (a
  // denormal, or 0 for 1e-400), kept as any decimal is kept rounded. A
  // denormal our writers print must read back.
  return {v, ""};
}

int walk_text_lines(const std::string& text, const std::string& path,
                    const std::function<void(std::string_view line, int number)>& each) {
  std::string_view rest(text);
  if (rest.substr(0, 3) == "\xEF\xBB\xBF") rest.remove_prefix(3);  // UTF-8 byte order mark
  int line_number = 0;
  while (!rest.empty()) {
    const std::size_t eol = rest.find('\n');
    const std::string_view line = trimmed(rest.substr(0, eol));
    rest.remove_prefix(eol == std::string_view::npos ? rest.size() : eol + 1);
    if (line_number == std::numeric_limits<int>::max())
      throw InputError(path, "", "too many lines", line_number);
    ++line_number;
    if (line.empty() || line.front() == '#') continue;
    each(line, line_number);
  }
  return line_number;
}

int walk_csv_lines(const std::string& text, const std::string& path, const std::string& no_header,
                   const std::function<void(std::string_view line, int number)>& header,
                   const std::function<void(std::string_view line, int number)>& row) {
  bool have_header = false;
  const int last = walk_text_lines(text, path, [&](std::string_view line, int number) {
    if (have_header) return row(line, number);
    header(line, number);
    have_header = true;
  });
  if (!have_header) throw InputError(path, "header", no_header, last);
  return last;
}

}  // namespace neurocloth
