// Fuzzes the FCL rule-base reader, parse_fcl(). An accepted rule base must
// hold finite ranges and membership parameters that validate, rule weights in
// [0, 1], conditions and consequents that name existing variables and terms,
// and infer finite outputs at the middle of every input's range.
#include <cctype>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "core/fuzzy/formats/fcl_reader.h"
#include "core/fuzzy/inference.h"
#include "fuzz/fuzz_contract.h"
#include "fuzz/fuzzy_contract.h"

namespace neurocloth::fuzz {
namespace {

using namespace neurocloth::fuzzy;

// Walks a condition tree without recursion: the harness must not overflow
// its own stack on a tree the reader built.
void check_condition(const Contract& c, const FuzzySystem& s, const Condition& root,
                     const std::string& f) {
  std::vector<const Condition*> open{&root};
  while (!open.empty()) {
    const Condition* node = open.back();
    open.pop_back();
    if (node->kind == Condition::Kind::term) {
      c.require(node->variable >= 0 && node->variable < static_cast<int>(s.inputs.size()),
                f + " tests input " + std::to_string(node->variable) + ", which does not exist");
      const auto& terms = s.inputs[static_cast<std::size_t>(node->variable)].terms;
      c.require(node->term >= 0 && node->term < static_cast<int>(terms.size()),
                f + " tests term " + std::to_string(node->term) + ", which does not exist");
      continue;
    }
    const std::size_t need = node->kind == Condition::Kind::negation ? 1 : 2;
    c.require(node->kind == Condition::Kind::negation ? node->children.size() == 1
                                                      : node->children.size() >= need,
              f + " has an AND, OR or NOT with the wrong number of operands");
    for (const Condition& child : node->children)
      open.push_back(&child);
  }
}

void check_rules(const Contract& c, const FuzzySystem& s) {
  for (const RuleBlock& b : s.blocks)
    for (const Rule& r : b.rules) {
      const std::string f = "RULEBLOCK " + b.name + " RULE " + r.label;
      c.finite(r.weight, f + " weight");
      c.require(r.weight >= 0 && r.weight <= 1, f + " weight accepted outside [0, 1]");
      check_condition(c, s, r.condition, f);
      c.require(!r.consequents.empty(), f + " accepted with no consequent");
      for (const Consequent& k : r.consequents) {
        c.require(k.variable >= 0 && k.variable < static_cast<int>(s.outputs.size()),
                  f + " sets output " + std::to_string(k.variable) + ", which does not exist");
        const auto& terms = s.outputs[static_cast<std::size_t>(k.variable)].terms;
        c.require(k.term >= 0 && k.term < static_cast<int>(terms.size()),
                  f + " sets term " + std::to_string(k.term) + ", which does not exist");
      }
    }
}

// What the rule base is for: inputs inside their ranges give finite outputs.
void check_inference(const Contract& c, const FuzzySystem& s) {
  std::vector<double> x;
  for (const LinguisticVariable& v : s.inputs)
    x.push_back(v.min / 2 + v.max / 2);  // halves first: min + max may overflow
  const auto report = accepted("fcl", [&] { return infer(s, x); });
  c.require(report.has_value(), "inference refused an accepted rule base with InputError");
  for (std::size_t k = 0; k < report->outputs.size(); ++k)
    c.require(std::isfinite(report->outputs[k]), "output '" + s.outputs[k].name + "' infers " +
                                                     show(report->outputs[k]) +
                                                     " at the middle of every input's range");
}

// The known stack overflows (~10,000 nested '(' or ~50,000 NOT in a rule):
// a campaign that skips known kinds leaves deep conditions alone.
bool deep_condition(const std::string& text) {
  int depth = 0, deepest = 0, nots = 0;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '(') deepest = std::max(deepest, ++depth);
    if (text[i] == ')') --depth;
    if (i + 3 <= text.size() && std::toupper(static_cast<unsigned char>(text[i])) == 'N' &&
        std::toupper(static_cast<unsigned char>(text[i + 1])) == 'O' &&
        std::toupper(static_cast<unsigned char>(text[i + 2])) == 'T')
      ++nots;
  }
  return deepest > 1000 || nots > 1000;
}

}  // namespace
}  // namespace neurocloth::fuzz

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace neurocloth;
  const std::string text(reinterpret_cast<const char*>(data), size);
  if (fuzz::skip_known() && fuzz::deep_condition(text)) return 0;
  const auto system = fuzz::accepted("fcl", [&] { return fuzzy::parse_fcl(text, "fuzz.fcl"); });
  if (!system) return 0;
  const fuzz::Contract c("fcl");
  for (const auto& v : system->inputs)
    fuzz::check_variable(c, v, "FUZZIFY " + v.name, "RANGE", "TERM");
  for (const auto& v : system->outputs)
    fuzz::check_variable(c, v, "DEFUZZIFY " + v.name, "RANGE", "TERM");
  fuzz::check_rules(c, *system);
  fuzz::check_inference(c, *system);
  return 0;
}
