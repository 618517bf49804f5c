#pragma once
// The lexical side of .fis files, private to src/core/fuzzy: sections and
// key=value lines, quoted names, numbers, [vectors], MF lines and rule lines.
// fis_reader.cpp gives them meaning. Every helper throws InputError naming the
// file, line and field it was given.
#include <cstddef>
#include <map>
#include <string>
#include <vector>

namespace neurocloth::fuzzy::fis {

// Caps on what a file's counts and section numbers may ask for: far above any
// rule base a person or a toolbox writes, far below what would exhaust memory
// or time.
inline constexpr int kMaxVariables = 1000;  // inputs, and outputs
inline constexpr int kMaxTerms = 1000;      // MFs of one variable
inline constexpr int kMaxRules = 100000;

struct Entry {
  std::string key, value;  // key in its canonical spelling ("NumMFs", "MF3")
  int line = 0;
};

struct Row {  // a line of [Rules]
  std::string text;
  int line = 0;
};

struct Section {
  std::string kind;  // "System", "Input", "Output" or "Rules"
  int index = 0;     // InputN / OutputN: N; else 0
  int line = 0;      // of its [header]
  std::vector<Entry> entries;
  std::vector<Row> rows;
  std::map<std::string, std::size_t> by_key;  // into entries: lookups stay cheap for long sections

  std::string title() const { return "[" + kind + (index ? std::to_string(index) : "") + "]"; }
  const Entry* find(const std::string& key) const;
  // Refuses a key not in `known`.
  template <std::size_t N>
  void only(const char* const (&known)[N], const std::string& path) const {
    only(known, N, path);
  }
  void only(const char* const* known, std::size_t n, const std::string& path) const;
};

// Splits the text into sections: '%' and '#' start comments (outside quotes),
// CR LF and a UTF-8 byte order mark are accepted, blank lines skipped.
// Refuses a line outside every section, an unknown or repeated section, a
// line that is no key=value outside [Rules], and a repeated key.
std::vector<Section> split_sections(const std::string& text, const std::string& path);

std::string lower(std::string s);
// `s` for a message: control bytes escaped, long text cut.
std::string shown(const std::string& s);
std::string show(double v);  // %g

// 'text', "text" or bare text, trimmed.
std::string text(const Entry& e, const Section& s, const std::string& path);
// A finite number within +-1e15, as the FCL reader allows.
double number(const std::string& s, const std::string& field, int line, const std::string& path);
// "[a b c]" (spaces or commas between); at most `max` numbers.
std::vector<double> vector(const std::string& s, const std::string& field, int line,
                           const std::string& path, std::size_t max);
// 3 for "MF3", -1 for any other key.
int mf_index(const std::string& key);
// A variable or term name: not empty, no control byte, no quote.
void check_name(const std::string& name, const std::string& field, int line,
                const std::string& path);

struct MfLine {
  std::string name, type;
  std::vector<double> params;
};
// 'name':'type',[params]
MfLine mf_line(const std::string& value, const std::string& field, int line,
               const std::string& path, std::size_t max_params);

struct RuleLine {
  std::vector<double> inputs, outputs;
  double weight = 1, connection = 1;
};
// "a1 .. an, c1 .. cm (w) : k" (the comma may be left out).
RuleLine rule_line(const std::string& text, int inputs, int outputs, const std::string& field,
                   int line, const std::string& path);

}  // namespace neurocloth::fuzzy::fis
