#pragma once
// Small rule bases built in code for the engine's tests (the FCL reader has its
// own tests; these check inference independently of it).
#include "core/fuzzy/fuzzy_system.h"

namespace neurocloth::fuzzy::test {

inline MembershipFunction mf(Shape s, std::vector<double> p) {
  return {s, std::move(p)};
}

inline LinguisticVariable variable(std::string name, double lo, double hi,
                                   std::vector<Term> terms) {
  LinguisticVariable v;
  v.name = std::move(name);
  v.min = lo;
  v.max = hi;
  v.terms = std::move(terms);
  return v;
}

inline Condition is(int variable, int term, std::vector<Hedge> hedges = {}, bool negated = false) {
  Condition c;
  c.variable = variable;
  c.term = term;
  c.hedges = std::move(hedges);
  c.negated = negated;
  return c;
}

inline Condition combine(Condition::Kind kind, std::vector<Condition> children) {
  Condition c;
  c.kind = kind;
  c.children = std::move(children);
  return c;
}

inline Rule rule(Condition c, int output, int term, double weight = 1.0) {
  Rule r;
  r.condition = std::move(c);
  r.consequents = {{output, term}};
  r.weight = weight;
  r.label = "r";
  return r;
}

}  // namespace neurocloth::fuzzy::test
