#pragma once
// IF <condition> THEN <output> IS <term> [, ...] [WITH weight]
// The condition is a small tree of AND, OR, NOT over "variable IS [NOT]
// [hedges] term". Variables and terms are indices into the FuzzySystem, so
// inference never compares strings.
#include <string>
#include <vector>

namespace neurocloth::fuzzy {

// Applied to a membership degree, innermost (closest to the term) first:
// "very somewhat big" = very(somewhat(big)).
enum class Hedge { very, somewhat };  // mu^2, sqrt(mu)
const char* to_string(Hedge h);

struct Condition {
  enum class Kind { term, all, any, negation };  // IS, AND, OR, NOT
  Kind kind = Kind::term;
  // Kind::term
  int variable = -1;          // input index
  int term = -1;              // term index in that input
  std::vector<Hedge> hedges;  // in source order: "very somewhat" -> {very, somewhat}
  bool negated = false;       // "IS NOT": 1 - mu, applied after the hedges
  // all / any: two or more children; negation: one
  std::vector<Condition> children;
};

// "THEN spring_constant IS very low": hedges and NOT shape the output set
// (Mamdani outputs only: a Takagi-Sugeno consequent is a value, not a set).
struct Consequent {
  Consequent() = default;
  Consequent(int variable_, int term_, std::vector<Hedge> hedges_ = {}, bool negated_ = false)
      : variable(variable_), term(term_), hedges(std::move(hedges_)), negated(negated_) {}

  int variable = -1;          // output index
  int term = -1;              // term index in that output
  std::vector<Hedge> hedges;  // as in Condition
  bool negated = false;
};

struct Rule {
  Condition condition;
  std::vector<Consequent> consequents;
  double weight = 1.0;  // WITH
  std::string label;    // "RULE 3" -> "3"
  int line = 0;         // where it came from, for messages (0 if built in code)
};

enum class AndMethod { min, product };           // FCL AND : MIN | PROD
enum class OrMethod { max, probabilistic_sum };  // FCL OR : MAX | ASUM
enum class Activation { min, product };          // FCL ACT : MIN | PROD
enum class Accumulation { max, sum };            // FCL ACCU : MAX | SUM

struct RuleBlock {
  std::string name;
  AndMethod and_method = AndMethod::min;
  OrMethod or_method = OrMethod::max;
  Activation activation = Activation::min;
  Accumulation accumulation = Accumulation::max;
  std::vector<Rule> rules;
};

}  // namespace neurocloth::fuzzy
