#include "core/fuzzy/formats/fis_writer.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <vector>

namespace neurocloth::fuzzy {
namespace {

// Every refusal is a system that .fis cannot hold, so that writing it anyway
// would give a file inferring other numbers.
[[noreturn]] void refuse_fis(const std::string& what) {
  throw std::invalid_argument("write_fis: " + what);
}

// 17 significant digits identify every double, so reading gives the same bits.
std::string fis_number(double v) {
  if (!std::isfinite(v)) refuse_fis(".fis has no spelling for a non-finite fis_number");
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

std::string vector(const std::vector<double>& v) {
  std::string s = "[";
  for (std::size_t i = 0; i < v.size(); ++i)
    s += (i ? " " : "") + fis_number(v[i]);
  return s + "]";
}

const std::string& quoted_name(const std::string& s, const char* what) {
  if (s.empty()) refuse_fis(std::string(what) + " has an empty name");
  for (char c : s)
    if (static_cast<unsigned char>(c) < 32 || c == 127 || c == '\'' || c == '"')
      refuse_fis(std::string(what) + " '" + s + "' holds a quote or a control character");
  return s;
}

// A rule entry: the 1-based MF index, negative for NOT, and one hedge as
// Octave's fraction code (.05 somewhat, .20 very; MATLAB has no hedges).
std::string entry(int term, bool negated, const std::vector<Hedge>& hedges,
                  const std::string& where) {
  if (hedges.size() > 1)
    refuse_fis(where + " stacks hedges, which .fis cannot hold (Octave codes one hedge per entry)");
  std::string s = (negated ? "-" : "") + std::to_string(term + 1);
  if (!hedges.empty()) s += hedges[0] == Hedge::very ? ".20" : ".05";
  return s;
}

bool same_methods(const RuleBlock& a, const RuleBlock& b) {
  return a.and_method == b.and_method && a.or_method == b.or_method &&
         a.activation == b.activation && a.accumulation == b.accumulation;
}

class FisWriter {
 public:
  explicit FisWriter(const FuzzySystem& s) : s_(s) {}

  std::string run() {
    check_system();
    const RuleBlock& b = s_.blocks.front();
    out_ = "[System]\n";
    out_ += "Name='" + (s_.name.empty() ? std::string("fis") : quoted_name(s_.name, "the system")) +
            "'\n";
    out_ += std::string("Type='") + (hybrid_ ? "hybrid" : sugeno_ ? "sugeno" : "mamdani") + "'\n";
    out_ += "Version=2.0\n";
    out_ += "NumInputs=" + std::to_string(s_.inputs.size()) + "\n";
    out_ += "NumOutputs=" + std::to_string(s_.outputs.size()) + "\n";
    out_ += "NumRules=" + std::to_string(rule_count_) + "\n";
    out_ +=
        std::string("AndMethod='") + (b.and_method == AndMethod::product ? "prod" : "min") + "'\n";
    out_ += std::string("OrMethod='") +
            (b.or_method == OrMethod::probabilistic_sum ? "probor" : "max") + "'\n";
    out_ +=
        std::string("ImpMethod='") + (b.activation == Activation::product ? "prod" : "min") + "'\n";
    out_ +=
        std::string("AggMethod='") + (b.accumulation == Accumulation::sum ? "sum" : "max") + "'\n";
    // The first output's (a hybrid system's other outputs differ).
    out_ += std::string("DefuzzMethod='") + (sugeno_ ? "wtaver" : "centroid") + "'\n";
    for (std::size_t i = 0; i < s_.inputs.size(); ++i)
      variable("Input", i, s_.inputs[i], false);
    for (std::size_t i = 0; i < s_.outputs.size(); ++i)
      variable("Output", i, s_.outputs[i], true);
    out_ += "\n[Rules]\n";
    for (const RuleBlock& block : s_.blocks)
      for (const Rule& r : block.rules)
        rule(r);
    return std::move(out_);
  }

 private:
  // One set of methods for every rule: a .fis system has a single [System]
  // saying them. Outputs defuzzified differently (COG and COGS) make
  // fuzzylite's 'hybrid', whose DefuzzMethod is the first output's and whose
  // readers tell each output's kind by its MFs.
  void check_system() {
    if (s_.outputs.empty()) refuse_fis("the system has no output");
    sugeno_ = s_.outputs.front().method == Defuzzification::weighted_average;
    for (const LinguisticVariable& v : s_.outputs)
      hybrid_ = hybrid_ || (v.method == Defuzzification::weighted_average) != sugeno_;
    if (s_.blocks.empty()) refuse_fis("the system has no rule block");
    for (const RuleBlock& b : s_.blocks) {
      if (!same_methods(b, s_.blocks.front()))
        refuse_fis("rule blocks '" + s_.blocks.front().name + "' and '" + b.name +
                   "' use different AND/OR/ACT/ACCU methods; .fis has one set per system");
      rule_count_ += b.rules.size();
    }
    if (rule_count_ == 0) refuse_fis("the system has no rules");
  }

  void variable(const char* kind, std::size_t i, const LinguisticVariable& v, bool output) {
    out_ += "\n[" + std::string(kind) + std::to_string(i + 1) + "]\n";
    out_ += "Name='" + quoted_name(v.name, "a variable") + "'\n";
    out_ += "Range=" + vector({v.min, v.max}) + "\n";
    out_ += "NumMFs=" + std::to_string(v.terms.size()) + "\n";
    if (output && !std::isnan(v.default_value))
      refuse_fis("output '" + v.name + "' has DEFAULT " + fis_number(v.default_value) +
                 "; .fis has no default (MATLAB takes the middle of the range)");
    for (std::size_t k = 0; k < v.terms.size(); ++k) {
      const Term& t = v.terms[k];
      const std::string problem = t.function.validate();
      if (!problem.empty()) refuse_fis("term '" + t.name + "' of '" + v.name + "': " + problem);
      out_ += "MF" + std::to_string(k + 1) + "='" + quoted_name(t.name, "a term") +
              "':" + membership(t, v, output && v.method == Defuzzification::weighted_average) +
              "\n";
    }
  }

  std::string membership(const Term& t, const LinguisticVariable& v, bool sugeno_output) {
    const auto& p = t.function.params;
    const std::string where = "term '" + t.name + "' of '" + v.name + "'";
    switch (t.function.shape) {
      case Shape::triangle:
        return "'trimf'," + vector(p);
      case Shape::trapezoid:
        return "'trapmf'," + vector(p);
      case Shape::gaussian:
        return "'gaussmf'," + vector({p[1], p[0]});  // [sigma c]
      case Shape::bell:
        return "'gbellmf'," + vector(p);
      case Shape::sigmoid:
        return "'sigmf'," + vector(p);
      case Shape::singleton:
        if (!sugeno_output)
          refuse_fis(where + " is a singleton, which .fis has only as a sugeno output (constant)");
        return "'constant'," + vector(p);
      case Shape::linear: {
        if (p.size() != 1 + s_.inputs.size())
          refuse_fis(where + " needs 1 + " + std::to_string(s_.inputs.size()) + " coefficients");
        std::vector<double> q(p.begin() + 1, p.end());
        q.push_back(p[0]);  // MATLAB: [a1 .. an c], the constant last
        return "'linear'," + vector(q);
      }
      case Shape::points:
        // fuzzylite's Discrete: x y pairs in one list (MATLAB has no such type).
        return "'discretemf'," + vector(p);
    }
    refuse_fis(where + " has a shape .fis has no membership function type for");
  }

  // "a1 .. an, c1 .. cm (w) : k": the MF index of each variable (0 when not
  // tested or not set), negative for NOT.
  void rule(const Rule& r) {
    const std::string where = "rule '" + r.label + "'";
    std::vector<std::string> in(s_.inputs.size(), "0"), out(s_.outputs.size(), "0");
    int connection = 1;
    const Condition& c = r.condition;
    if (c.kind == Condition::Kind::all || c.kind == Condition::Kind::any) {
      connection = c.kind == Condition::Kind::all ? 1 : 2;
      for (const Condition& child : c.children)
        clause(child, in, where);
    } else {
      clause(c, in, where);
    }
    if (r.consequents.empty()) refuse_fis(where + " has no consequent");
    for (const Consequent& k : r.consequents) {
      if (k.variable < 0 || static_cast<std::size_t>(k.variable) >= out.size() || k.term < 0 ||
          static_cast<std::size_t>(k.term) >=
              s_.outputs[static_cast<std::size_t>(k.variable)].terms.size())
        refuse_fis(where + " sets an output or term that does not exist");
      std::string& slot = out[static_cast<std::size_t>(k.variable)];
      if (slot != "0") refuse_fis(where + " sets one output twice, which .fis cannot hold");
      slot = entry(k.term, k.negated, k.hedges, where);
    }
    std::string line;
    for (std::size_t i = 0; i < in.size(); ++i)
      line += (i ? " " : "") + in[i];
    line += ",";
    for (const std::string& o : out)
      line += " " + o;
    out_ += line + " (" + fis_number(r.weight) + ") : " + std::to_string(connection) + "\n";
  }

  // A term, or NOT of a term: one entry per input, at most once each.
  void clause(const Condition& c, std::vector<std::string>& in, const std::string& where) {
    const Condition* t = &c;
    bool negated = false;
    if (c.kind == Condition::Kind::negation && c.children.size() == 1 &&
        c.children[0].kind == Condition::Kind::term && !c.children[0].negated) {
      t = &c.children[0];
      negated = true;
    }
    if (t->kind != Condition::Kind::term)
      refuse_fis(where + " nests AND, OR or NOT; .fis rules are one AND or one OR of terms");

    if (t->variable < 0 || static_cast<std::size_t>(t->variable) >= in.size() || t->term < 0 ||
        static_cast<std::size_t>(t->term) >=
            s_.inputs[static_cast<std::size_t>(t->variable)].terms.size())
      refuse_fis(where + " tests an input or term that does not exist");
    std::string& slot = in[static_cast<std::size_t>(t->variable)];
    if (slot != "0") refuse_fis(where + " tests one input twice, which .fis cannot hold");
    slot = entry(t->term, negated != t->negated, t->hedges, where);
  }

  const FuzzySystem& s_;
  bool sugeno_ = false;  // the first output is
  bool hybrid_ = false;  // and some other output is not
  std::size_t rule_count_ = 0;
  std::string out_;
};

}  // namespace

std::string write_fis(const FuzzySystem& system) {
  return FisWriter(system).run();
}

}  // namespace neurocloth::fuzzy
