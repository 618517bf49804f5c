#include "core/fuzzy/formats/fcl_writer.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "core/fuzzy/formats/fcl_lexer.h"

namespace neurocloth::fuzzy {
namespace {

// Every refusal below is a system the reader could not read back as the same
// system; writing it anyway would make the round trip silently lossy.
[[noreturn]] void refuse(const std::string& what) {
  throw std::invalid_argument("write_fcl: " + what);
}

// 17 significant digits identify every double, so reading gives the same bits.
std::string number(double v) {
  if (!std::isfinite(v))
    refuse("FCL has no spelling for the non-finite number " + std::to_string(v));
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

const std::string& name(const std::string& s, const char* what) {
  if (!fcl::is_identifier(s))
    refuse(std::string(what) + " '" + s +
           "' is not an FCL identifier (letters, digits, '_'; no leading digit; not a keyword)");
  return s;
}

// A label reads back only if it is one number or one identifier token.
std::string label(const Rule& r, std::size_t position) {
  if (r.label.empty()) return std::to_string(position + 1);
  const auto tokens = fcl::Tokenizer(r.label).run();
  const fcl::Token& t = tokens.front();
  const bool one_token = tokens.size() == 2 && t.text == r.label;
  if (!one_token || !(t.kind == fcl::TokenKind::number || fcl::is_identifier(t.text)))
    refuse("rule label '" + r.label + "' is neither a number nor an identifier");
  return r.label;
}

std::string upper(const char* s) {
  std::string u(s);
  for (char& c : u)
    c = fcl::upper(c);
  return u;
}

class Writer {
 public:
  explicit Writer(const FuzzySystem& s) : s_(s) {}

  std::string run() {
    out_ = "FUNCTION_BLOCK";
    if (!s_.name.empty()) out_ += " " + name(s_.name, "function block name");
    out_ += "\n";
    declarations("VAR_INPUT", s_.inputs);
    declarations("VAR_OUTPUT", s_.outputs);
    for (const auto& v : s_.inputs)
      variable(v, false);
    for (const auto& v : s_.outputs)
      variable(v, true);
    for (const auto& b : s_.blocks)
      rule_block(b);
    out_ += "\nEND_FUNCTION_BLOCK\n";
    return std::move(out_);
  }

 private:
  void declarations(const char* keyword, const std::vector<LinguisticVariable>& vars) {
    if (vars.empty()) return;
    out_ += std::string("\n") + keyword + "\n";
    for (const auto& v : vars)
      out_ += "  " + name(v.name, "variable name") + " : REAL;\n";
    out_ += "END_VAR\n";
  }

  void variable(const LinguisticVariable& v, bool output) {
    const std::string keyword = output ? "DEFUZZIFY" : "FUZZIFY";
    out_ += "\n" + keyword + " " + v.name + "\n";
    out_ += "  RANGE := (" + number(v.min) + " .. " + number(v.max) + ");\n";
    for (const Term& t : v.terms) {
      const std::string problem = t.function.validate();
      if (!problem.empty()) refuse("term '" + t.name + "' of '" + v.name + "': " + problem);
      out_ += "  TERM " + name(t.name, "term name") + " := " + membership(inside(t, v)) + ";\n";
    }
    if (output) {
      const bool cogs = v.method == Defuzzification::weighted_average;
      out_ += std::string("  METHOD : ") + (cogs ? "COGS" : "COG") + ";\n";
      // NaN means "not given", which is what leaving DEFAULT out says.
      if (!std::isnan(v.default_value)) out_ += "  DEFAULT := " + number(v.default_value) + ";\n";
    }
    out_ += "END_" + keyword + "\n";
  }

  // FCL keeps a term's positions inside its RANGE (a .fis need not: MATLAB's
  // default terms reach beyond it). A piecewise-linear term is written as the
  // point list it draws inside the range, which is all inference reads of it.
  MembershipFunction inside(const Term& t, const LinguisticVariable& v) {
    const MembershipFunction& f = t.function;
    bool beyond = false;
    for (double x : f.axis_positions())
      beyond = beyond || x < v.min || x > v.max;
    if (!beyond) return f;
    if (!f.piecewise_linear())
      refuse("term '" + t.name + "' of '" + v.name +
             "' reaches beyond its RANGE, which FCL cannot hold for a " + to_string(f.shape));
    std::vector<double> xs = {v.min, v.max};
    for (double b : f.breakpoints())
      if (b > v.min && b < v.max) xs.push_back(b);
    std::sort(xs.begin(), xs.end());
    xs.erase(std::unique(xs.begin(), xs.end()), xs.end());
    MembershipFunction clipped;
    clipped.shape = Shape::points;
    for (double x : xs) {
      clipped.params.push_back(x);
      clipped.params.push_back(f(x));
    }
    return clipped;
  }

  std::string membership(const MembershipFunction& f) {
    std::string s;
    switch (f.shape) {
      case Shape::singleton:
        return number(f.params[0]);
      case Shape::points:
        for (std::size_t i = 0; i + 1 < f.params.size(); i += 2)
          s += (i ? " (" : "(") + number(f.params[i]) + ", " + number(f.params[i + 1]) + ")";
        return s;
      case Shape::linear:
        if (f.params.size() != 1 + s_.inputs.size())
          refuse("a linear term needs 1 + " + std::to_string(s_.inputs.size()) +
                 " parameters (c0, then one per input), got " + std::to_string(f.params.size()));
        s = "LINEAR " + number(f.params[0]);
        for (std::size_t i = 0; i < s_.inputs.size(); ++i)
          s += " " + s_.inputs[i].name + " " + number(f.params[i + 1]);
        return s;
      default:
        s = upper(to_string(f.shape));
        for (double p : f.params)
          s += " " + number(p);
        return s;
    }
  }

  void rule_block(const RuleBlock& b) {
    out_ += "\nRULEBLOCK";
    if (!b.name.empty()) out_ += " " + name(b.name, "rule block name");
    out_ += "\n";
    out_ += std::string("  AND : ") + (b.and_method == AndMethod::product ? "PROD" : "MIN") + ";\n";
    out_ += std::string("  OR : ") + (b.or_method == OrMethod::probabilistic_sum ? "ASUM" : "MAX") +
            ";\n";
    out_ +=
        std::string("  ACT : ") + (b.activation == Activation::product ? "PROD" : "MIN") + ";\n";
    out_ +=
        std::string("  ACCU : ") + (b.accumulation == Accumulation::sum ? "SUM" : "MAX") + ";\n";
    for (std::size_t i = 0; i < b.rules.size(); ++i)
      rule(b.rules[i], i);
    out_ += "END_RULEBLOCK\n";
  }

  void rule(const Rule& r, std::size_t position) {
    if (r.consequents.empty()) refuse("rule '" + r.label + "' has no consequent");
    out_ += "  RULE " + label(r, position) + " : IF " + condition(r.condition) + " THEN ";
    for (std::size_t i = 0; i < r.consequents.size(); ++i) {
      const Consequent& c = r.consequents[i];
      const LinguisticVariable& v = pick(s_.outputs, c.variable, "output");
      out_ += (i ? ", " : "") + v.name + " IS " + (c.negated ? "NOT " : "");
      for (Hedge h : c.hedges)
        out_ += upper(to_string(h)) + " ";
      out_ += pick(v.terms, c.term, "term").name;
    }
    if (r.weight != 1.0) out_ += " WITH " + number(r.weight);
    out_ += ";\n";
  }

  // Parentheses exactly where the reader needs them to rebuild the same tree:
  // a chain inside a chain of the same connective, an OR inside an AND, and
  // always after NOT (for the reader, NOT binds to one clause or one group).
  std::string condition(const Condition& c) {
    using Kind = Condition::Kind;
    switch (c.kind) {
      case Kind::term:
        return clause(c);
      case Kind::negation:
        if (c.children.size() != 1) refuse("NOT needs exactly one child condition");
        return "NOT (" + condition(c.children[0]) + ")";
      case Kind::all:
      case Kind::any:
        break;
    }
    if (c.children.size() < 2) refuse("AND and OR need at least two child conditions");
    const bool all = c.kind == Kind::all;
    std::string s;
    for (std::size_t i = 0; i < c.children.size(); ++i) {
      const Condition& child = c.children[i];
      const bool group = child.kind == Kind::any || (all && child.kind == Kind::all);
      if (i) s += all ? " AND " : " OR ";
      s += group ? "(" + condition(child) + ")" : condition(child);
    }
    return s;
  }

  std::string clause(const Condition& c) {
    const LinguisticVariable& v = pick(s_.inputs, c.variable, "input");
    std::string s = v.name + " IS ";
    if (c.negated) s += "NOT ";
    for (Hedge h : c.hedges)
      s += upper(to_string(h)) + " ";
    return s + pick(v.terms, c.term, "term").name;
  }

  template <class T>
  static const T& pick(const std::vector<T>& list, int index, const char* what) {
    if (index < 0 || static_cast<std::size_t>(index) >= list.size())
      refuse("a rule refers to " + std::string(what) + " index " + std::to_string(index) + " of " +
             std::to_string(list.size()));
    return list[static_cast<std::size_t>(index)];
  }

  const FuzzySystem& s_;
  std::string out_;
};

}  // namespace

std::string write_fcl(const FuzzySystem& system) {
  return Writer(system).run();
}

}  // namespace neurocloth::fuzzy
