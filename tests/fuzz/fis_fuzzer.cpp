// Fuzzes the MATLAB / Octave .fis reader, parse_fis(). An accepted rule base
// must hold finite ranges and membership parameters that validate, rule
// weights in [0, 1], conditions and consequents that name existing variables
// and terms, infer finite outputs at the middle of every input's range, and
// write back (write_fis) to a text that reads to the same system: .fis is a
// format we write too, so what we read we must be able to write.
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/fuzzy/formats/fis_reader.h"
#include "core/fuzzy/formats/fis_writer.h"
#include "core/fuzzy/inference.h"
#include "fuzz/fuzz_contract.h"
#include "fuzz/fuzzy_contract.h"

namespace neurocloth::fuzz {
namespace {

using namespace neurocloth::fuzzy;

// .fis rules are one AND or one OR of terms: the tree is at most two deep.
void check_term(const Contract& c, const FuzzySystem& s, const Condition& t, const std::string& f) {
  c.require(t.kind == Condition::Kind::term, f + " holds a nested condition");
  c.require(t.variable >= 0 && t.variable < static_cast<int>(s.inputs.size()),
            f + " tests input " + std::to_string(t.variable) + ", which does not exist");
  const auto& terms = s.inputs[static_cast<std::size_t>(t.variable)].terms;
  c.require(t.term >= 0 && t.term < static_cast<int>(terms.size()),
            f + " tests MF " + std::to_string(t.term) + ", which does not exist");
}

void check_rules(const Contract& c, const FuzzySystem& s) {
  c.require(s.blocks.size() == 1, "a .fis system read into more than one rule block");
  for (const Rule& r : s.blocks[0].rules) {
    const std::string f = "rule " + r.label;
    c.finite(r.weight, f + " weight");
    c.require(r.weight >= 0 && r.weight <= 1, f + " weight accepted outside [0, 1]");
    if (r.condition.kind == Condition::Kind::term) {
      check_term(c, s, r.condition, f);
    } else {
      c.require(r.condition.children.size() >= 2, f + " AND/OR with fewer than two terms");
      for (const Condition& t : r.condition.children)
        check_term(c, s, t, f);
    }
    c.require(!r.consequents.empty(), f + " accepted with no consequent");
    for (const Consequent& k : r.consequents) {
      c.require(k.variable >= 0 && k.variable < static_cast<int>(s.outputs.size()),
                f + " sets output " + std::to_string(k.variable) + ", which does not exist");
      const auto& terms = s.outputs[static_cast<std::size_t>(k.variable)].terms;
      c.require(k.term >= 0 && k.term < static_cast<int>(terms.size()),
                f + " sets MF " + std::to_string(k.term) + ", which does not exist");
    }
  }
}

std::vector<double> middles(const FuzzySystem& s) {
  std::vector<double> x;
  for (const LinguisticVariable& v : s.inputs)
    x.push_back(v.min / 2 + v.max / 2);  // halves first: min + max may overflow
  return x;
}

void check_inference(const Contract& c, const FuzzySystem& s) {
  const auto report = accepted("fis", [&] { return infer(s, middles(s)); });
  c.require(report.has_value(), "inference refused an accepted rule base with InputError");
  for (std::size_t k = 0; k < report->outputs.size(); ++k)
    c.require(std::isfinite(report->outputs[k]), "output '" + s.outputs[k].name + "' infers " +
                                                     show(report->outputs[k]) +
                                                     " at the middle of every input's range");
}

// What was read writes, and the written text reads to the same text again.
void check_write_back(const Contract& c, const FuzzySystem& s) {
  std::string text;
  try {
    text = write_fis(s);
  } catch (const std::invalid_argument& e) {
    c.fail(std::string("write_fis refused a system parse_fis accepted: ") + e.what());
  }
  const auto back = accepted("fis", [&] { return parse_fis(text, "written.fis"); });
  c.require(back.has_value(), "parse_fis refused what write_fis wrote:\n" + text);
  c.require(write_fis(*back) == text,
            "write_fis(parse_fis(write_fis(s))) differs from write_fis(s)");
}

}  // namespace
}  // namespace neurocloth::fuzz

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace neurocloth;
  const std::string text(reinterpret_cast<const char*>(data), size);
  const auto system = fuzz::accepted("fis", [&] { return fuzzy::parse_fis(text, "fuzz.fis"); });
  if (!system) return 0;
  const fuzz::Contract c("fis");
  for (const auto& v : system->inputs)
    fuzz::check_variable(c, v, "input " + v.name, "Range", "MF");
  for (const auto& v : system->outputs)
    fuzz::check_variable(c, v, "output " + v.name, "Range", "MF");
  fuzz::check_rules(c, *system);
  fuzz::check_inference(c, *system);
  fuzz::check_write_back(c, *system);
  return 0;
}
