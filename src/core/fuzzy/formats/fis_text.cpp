#include "core/fuzzy/formats/fis_text.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <system_error>

#include "core/io/input_error.h"

namespace neurocloth::fuzzy::fis {
namespace {

[[noreturn]] void fail(const std::string& path, const std::string& field,
                       const std::string& message, int line) {
  throw InputError(path, field, message, line);
}

bool blank(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v';
}

std::string trim(const std::string& s) {
  std::size_t a = 0, b = s.size();
  while (a < b && blank(s[a]))
    ++a;
  while (b > a && blank(s[b - 1]))
    --b;
  return s.substr(a, b - a);
}

bool same(const std::string& a, const char* b) {
  return lower(a) == lower(b);
}

// A comment starts at '%' or '#' outside quotes.
std::string strip_comment(const std::string& line) {
  char quote = 0;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quote) {
      if (c == quote) quote = 0;
    } else if (c == '\'' || c == '"') {
      quote = c;
    } else if (c == '%' || c == '#') {
      return line.substr(0, i);
    }
  }
  return line;
}

const char* const kKeys[] = {"Name",         "Type",      "Version",  "NumInputs", "NumOutputs",
                             "NumRules",     "AndMethod", "OrMethod", "ImpMethod", "AggMethod",
                             "DefuzzMethod", "Range",     "NumMFs"};

// Keys are matched without regard to case; this is how they are spelled.
std::string canonical_key(const std::string& key) {
  for (const char* k : kKeys)
    if (same(key, k)) return k;
  if (key.size() > 2 && same(key.substr(0, 2), "MF")) return "MF" + key.substr(2);
  return key;
}

// "[Input3]" -> kind "Input", index 3.
Section header(const std::string& line, int number, const std::string& path) {
  const std::string name = trim(line.substr(1, line.size() - 2));
  Section s;
  s.line = number;
  for (const char* kind : {"System", "Rules"})
    if (same(name, kind)) {
      s.kind = kind;
      return s;
    }
  for (const char* kind : {"Input", "Output"}) {
    const std::size_t n = std::char_traits<char>::length(kind);
    if (name.size() <= n || !same(name.substr(0, n), kind)) continue;
    const std::string digits = name.substr(n);
    int index = 0;
    const auto r = std::from_chars(digits.data(), digits.data() + digits.size(), index);
    if (r.ec == std::errc() && r.ptr == digits.data() + digits.size() && index >= 1 &&
        index <= kMaxVariables && digits[0] != '+') {
      s.kind = kind;
      s.index = index;
      return s;
    }
  }
  fail(path, "[" + shown(name) + "]",
       "unknown section (expected [System], [Input<n>], [Output<n>] or [Rules], n from 1 to " +
           std::to_string(kMaxVariables) + ")",
       number);
}

}  // namespace

const Entry* Section::find(const std::string& key) const {
  const auto it = by_key.find(key);
  return it == by_key.end() ? nullptr : &entries[it->second];
}

void Section::only(const char* const* known, std::size_t n, const std::string& path) const {
  for (const Entry& e : entries) {
    bool ok = false;
    for (std::size_t i = 0; i < n; ++i)
      ok = ok || e.key == known[i];
    if (!ok)
      fail(path, title() + " " + shown(e.key), "unknown key '" + shown(e.key) + "' in " + title(),
           e.line);
  }
}

std::vector<Section> split_sections(const std::string& text, const std::string& path) {
  std::vector<Section> sections;
  std::size_t at = text.compare(0, 3, "\xEF\xBB\xBF") == 0 ? 3 : 0;  // byte order mark
  for (int number = 1; at <= text.size(); ++number) {
    std::size_t end = text.find('\n', at);
    if (end == std::string::npos) end = text.size();
    const std::string line = trim(strip_comment(text.substr(at, end - at)));
    at = end + 1;
    if (line.empty()) continue;
    if (line.front() == '[' && line.back() == ']') {
      Section s = header(line, number, path);
      for (const Section& other : sections)
        if (other.kind == s.kind && other.index == s.index)
          fail(path, s.title(),
               "section given twice (the first is at line " + std::to_string(other.line) + ")",
               number);
      sections.push_back(std::move(s));
      continue;
    }
    if (sections.empty())
      fail(path, "[System]", "expected a [System] section before '" + shown(line) + "'", number);
    Section& s = sections.back();
    if (s.kind == "Rules") {
      s.rows.push_back({line, number});
      continue;
    }
    const std::size_t eq = line.find('=');
    if (eq == std::string::npos)
      fail(path, s.title(), "expected key=value, got '" + shown(line) + "'", number);
    Entry e{canonical_key(trim(line.substr(0, eq))), trim(line.substr(eq + 1)), number};
    if (const Entry* first = s.find(e.key))
      fail(path, s.title() + " " + shown(e.key),
           e.key + " given twice (the first is at line " + std::to_string(first->line) + ")",
           number);
    s.by_key.emplace(e.key, s.entries.size());
    s.entries.push_back(std::move(e));
  }
  return sections;
}

std::string lower(std::string s) {
  for (char& c : s)
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  return s;
}

std::string shown(const std::string& s) {
  std::string out;
  for (std::size_t i = 0; i < s.size() && i < 60; ++i) {
    const unsigned char c = static_cast<unsigned char>(s[i]);
    if (c >= 32 && c < 127) {
      out += static_cast<char>(c);
    } else {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02X", c);
      out += buf;
    }
  }
  return s.size() > 60 ? out + "..." : out;
}

std::string show(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

std::string text(const Entry& e, const Section& s, const std::string& path) {
  const std::string& v = e.value;
  if (!v.empty() && (v.front() == '\'' || v.front() == '"')) {
    if (v.size() < 2 || v.back() != v.front())
      fail(path, s.title() + " " + e.key, "unbalanced quote in '" + shown(v) + "'", e.line);
    return v.substr(1, v.size() - 2);
  }
  if (v.empty()) fail(path, s.title() + " " + e.key, e.key + " is empty", e.line);
  return v;
}

double number(const std::string& s, const std::string& field, int line, const std::string& path) {
  const std::string t = trim(s);
  const char* first = t.data() + (!t.empty() && t[0] == '+' ? 1 : 0);
  double v = 0;
  const auto r = std::from_chars(first, t.data() + t.size(), v);
  if (t.empty() || r.ec != std::errc() || r.ptr != t.data() + t.size())
    fail(path, field, "expected a number, got '" + shown(t) + "'", line);
  if (!std::isfinite(v)) fail(path, field, "'" + shown(t) + "' is not a finite number", line);
  // As in FCL: beyond this the engine's centroids would overflow.
  if (!(std::abs(v) <= 1e15))
    fail(path, field, "number '" + shown(t) + "' is beyond +-1e15, more than a rule base can use",
         line);
  return v;
}

std::vector<double> vector(const std::string& s, const std::string& field, int line,
                           const std::string& path, std::size_t max) {
  const std::string t = trim(s);
  if (t.size() < 2 || t.front() != '[' || t.back() != ']')
    fail(path, field, "expected [numbers], got '" + shown(t) + "'", line);
  std::vector<double> out;
  std::size_t i = 1;
  const std::size_t end = t.size() - 1;
  while (i < end) {
    while (i < end && (blank(t[i]) || t[i] == ',' || t[i] == ';'))
      ++i;
    std::size_t j = i;
    while (j < end && !(blank(t[j]) || t[j] == ',' || t[j] == ';'))
      ++j;
    if (j == i) break;
    if (out.size() == max)
      fail(path, field, "more than " + std::to_string(max) + " numbers in '" + shown(t) + "'",
           line);
    out.push_back(number(t.substr(i, j - i), field, line, path));
    i = j;
  }
  return out;
}

int mf_index(const std::string& key) {
  if (key.size() < 3 || key.compare(0, 2, "MF") != 0) return -1;
  int k = 0;
  const auto r = std::from_chars(key.data() + 2, key.data() + key.size(), k);
  if (r.ec != std::errc() || r.ptr != key.data() + key.size() || key[2] == '+') return -1;
  return k;
}

void check_name(const std::string& name, const std::string& field, int line,
                const std::string& path) {
  if (name.empty()) fail(path, field, "empty name", line);
  for (char c : name)
    if (static_cast<unsigned char>(c) < 32 || c == 127 || c == '\'' || c == '"')
      fail(path, field, "name '" + shown(name) + "' holds a control character or a quote", line);
}

MfLine mf_line(const std::string& value, const std::string& field, int line,
               const std::string& path, std::size_t max_params) {
  MfLine mf;
  std::size_t i = 0;
  // A quoted string at i, moving i past it.
  auto quoted = [&](const char* what) {
    while (i < value.size() && blank(value[i]))
      ++i;
    if (i >= value.size() || (value[i] != '\'' && value[i] != '"'))
      fail(path, field, "expected the " + std::string(what) + " in quotes: 'name':'type',[params]",
           line);
    const char q = value[i];
    const std::size_t close = value.find(q, i + 1);
    if (close == std::string::npos)
      fail(path, field, "unbalanced quote in the " + std::string(what), line);
    const std::string s = value.substr(i + 1, close - i - 1);
    i = close + 1;
    return s;
  };
  auto separator = [&](char c) {
    while (i < value.size() && blank(value[i]))
      ++i;
    if (i >= value.size() || value[i] != c)
      fail(path, field, std::string("expected '") + c + "' in 'name':'type',[params]", line);
    ++i;
  };
  mf.name = quoted("name");
  separator(':');
  mf.type = quoted("type");
  separator(',');
  mf.params = vector(value.substr(i), field, line, path, max_params);
  return mf;
}

RuleLine rule_line(const std::string& text, int inputs, int outputs, const std::string& field,
                   int line, const std::string& path) {
  RuleLine r;
  const std::size_t colon = text.rfind(':');
  const std::size_t open = text.find('('), close = text.find(')');
  if (colon == std::string::npos || open == std::string::npos || close == std::string::npos ||
      !(open < close && close < colon))
    fail(path, field, "expected 'inputs, outputs (weight) : connection', got '" + shown(text) + "'",
         line);
  r.weight = number(text.substr(open + 1, close - open - 1), field, line, path);
  r.connection = number(text.substr(colon + 1), field, line, path);
  if (!trim(text.substr(close + 1, colon - close - 1)).empty())
    fail(path, field, "unexpected text between ')' and ':' in '" + shown(text) + "'", line);
  // The entries: whitespace-separated, with one comma between inputs and outputs.
  const std::string entries = text.substr(0, open);
  const std::size_t comma = entries.find(',');
  const std::size_t cap = static_cast<std::size_t>(inputs + outputs);
  auto numbers = [&](const std::string& s) {
    return vector("[" + s + "]", field, line, path, cap + 1);
  };
  if (comma != std::string::npos) {
    r.inputs = numbers(entries.substr(0, comma));
    r.outputs = numbers(entries.substr(comma + 1));
  } else {
    std::vector<double> all = numbers(entries);
    if (all.size() == cap) {
      r.inputs.assign(all.begin(), all.begin() + inputs);
      r.outputs.assign(all.begin() + inputs, all.end());
    } else {
      r.inputs = all;  // the count check below says what is wrong
    }
  }
  if (r.inputs.size() != static_cast<std::size_t>(inputs) ||
      r.outputs.size() != static_cast<std::size_t>(outputs))
    fail(path, field,
         "expected " + std::to_string(inputs) + " input and " + std::to_string(outputs) +
             " output entries (NumInputs, NumOutputs), got " + std::to_string(r.inputs.size()) +
             " and " + std::to_string(r.outputs.size()),
         line);
  return r;
}

}  // namespace neurocloth::fuzzy::fis
