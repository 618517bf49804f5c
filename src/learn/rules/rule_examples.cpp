#include "learn/rules/rule_examples.h"

#include <sstream>
#include <string_view>

#include "core/io/csv_fields.h"
#include "core/io/input_error.h"
#include "core/io/text_file.h"

namespace neurocloth {
namespace {

using fuzzy::FuzzySystem;
using fuzzy::LinguisticVariable;

std::string range_of(const LinguisticVariable& v) {
  std::ostringstream os;
  os << "[" << v.min << ", " << v.max << "]";
  return os.str();
}

// What one column holds: an input (index into the rule base's inputs) or a target.
struct Column {
  std::string name;
  bool input;
  int index;  // input index, or k in RuleExamples::outputs
  const LinguisticVariable* variable;
};

class ExampleReader {
 public:
  ExampleReader(const std::string& path, const FuzzySystem& system) : path_(path), system_(system) {
    examples_.path = path;
  }

  void header(std::string_view line, int line_number) {
    const auto fields = split_fields(line);
    std::vector<bool> input_seen(system_.inputs.size(), false);
    for (std::size_t c = 0; c < fields.size(); ++c) {
      const std::string name(fields[c]);
      const int column = int(c) + 1;
      const int i = system_.input_index(name), o = system_.output_index(name);
      // An unknown name is the file's bytes (a binary file, a terminal
      // escape): quoted safely, never made the field.
      if (i < 0 && o < 0)
        throw InputError(path_, "header",
                         shown(name) + " is not an input or output of rule base '" + system_.name +
                             "'" + (name.empty() ? " (an empty column name)" : ""),
                         line_number, column);
      for (const Column& seen : columns_)
        if (seen.name == name)
          throw InputError(path_, name, "named twice in the header", line_number, column);
      if (i >= 0) {
        input_seen[i] = true;
        columns_.push_back({name, true, i, &system_.inputs[i]});
      } else {
        columns_.push_back({name, false, int(examples_.outputs.size()), &system_.outputs[o]});
        examples_.outputs.push_back(o);
      }
    }
    for (std::size_t i = 0; i < input_seen.size(); ++i)
      if (!input_seen[i])
        throw InputError(path_, system_.inputs[i].name,
                         "input missing from the header: every example gives every input of '" +
                             system_.name + "'",
                         line_number);
    if (examples_.outputs.empty())
      throw InputError(path_, "header",
                       "names no output of '" + system_.name +
                           "': add the outputs to tune, each with the value it should give",
                       line_number);
  }

  void row(std::string_view line, int line_number) {
    const auto fields = split_fields(line);
    if (fields.size() != columns_.size())
      throw InputError(path_, fields.size() < columns_.size() ? columns_[fields.size()].name : "",
                       "expected " + std::to_string(columns_.size()) +
                           " fields as the header, found " + std::to_string(fields.size()),
                       line_number);
    if (examples_.size() == kMaxExampleRows)
      throw InputError(path_, "", "more than " + std::to_string(kMaxExampleRows) + " examples",
                       line_number);
    std::vector<double> inputs(system_.inputs.size()), targets(examples_.outputs.size());
    for (std::size_t c = 0; c < fields.size(); ++c) {
      const Column& col = columns_[c];
      const double v = number(fields[c], col, line_number, int(c) + 1);
      if (v < col.variable->min || v > col.variable->max)
        throw InputError(path_, col.name,
                         shown(fields[c]) + " is outside " + col.name + "'s RANGE " +
                             range_of(*col.variable) +
                             (col.input ? " (refused rather than clamped: the rule base would see "
                                          "the clamped value)"
                                        : " (the rule base cannot give it)"),
                         line_number, int(c) + 1);
      (col.input ? inputs : targets)[col.index] = v;
    }
    examples_.inputs.push_back(std::move(inputs));
    examples_.targets.push_back(std::move(targets));
    examples_.lines.push_back(line_number);
  }

  RuleExamples finish(int last_line) {
    if (examples_.size() == 0)
      throw InputError(path_, "", "no examples: the header and no rows", last_line);
    return std::move(examples_);
  }

 private:
  double number(std::string_view field, const Column& col, int line, int column) const {
    const FieldNumber n = finite_number(field);
    if (!n.refusal.empty()) throw InputError(path_, col.name, n.refusal, line, column);
    return n.value;
  }

  const std::string& path_;
  const FuzzySystem& system_;
  std::vector<Column> columns_;
  RuleExamples examples_;
};

}  // namespace

RuleExamples parse_rule_examples(const std::string& text, const std::string& path,
                                 const FuzzySystem& system) {
  ExampleReader reader(path, system);
  const int line_number = walk_csv_lines(
      text, path, "empty: expected a header naming every input and the outputs to tune",
      [&](std::string_view line, int n) { reader.header(line, n); },
      [&](std::string_view line, int n) { reader.row(line, n); });
  return reader.finish(line_number);
}

RuleExamples read_rule_examples(const std::string& path, const FuzzySystem& system) {
  return parse_rule_examples(read_text_file(path, "examples file", kMaxExampleBytes), path, system);
}

}  // namespace neurocloth
