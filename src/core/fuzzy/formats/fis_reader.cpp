#include "core/fuzzy/formats/fis_reader.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <initializer_list>
#include <map>
#include <set>
#include <system_error>
#include <utility>
#include <vector>

#include "core/fuzzy/formats/fis_text.h"
#include "core/io/input_error.h"
#include "core/io/text_file.h"

namespace neurocloth::fuzzy {
namespace {

using fis::Entry;
using fis::Section;

using fis::kMaxRules;
using fis::kMaxTerms;
using fis::kMaxVariables;

// The most numbers an MF line may hold: a discretemf of kMaxPoints points, or
// a linear term over kMaxVariables inputs. More is refused while reading, before
// anything is stored.
constexpr std::size_t kMaxMfParameters =
    std::max<std::size_t>(2 * kMaxPoints + 2, 2 + kMaxVariables);

// What [System] Type says the outputs are. fuzzylite writes 'hybrid' for a
// system with both kinds; each output is then what its MFs are.
enum class FisType { mamdani, sugeno, hybrid };

// A rule's entry for one variable: which MF (1-based, 0 = none), NOT, and
// Octave's hedge code in the fraction (.05 somewhat, .2 very).
struct RuleEntry {
  int mf = 0;
  bool negated = false;
  std::vector<Hedge> hedges;
};

class FisParser {
 public:
  FisParser(const std::string& text, std::string path) : path_(std::move(path)) {
    sections_ = fis::split_sections(text, path_);
  }

  FuzzySystem parse() {
    const Section& system = section("System", 0);
    read_system(system);
    for (int k = 1; k <= num_inputs_; ++k)
      system_.inputs.push_back(variable(section_for("Input", k, system), false));
    for (int k = 1; k <= num_outputs_; ++k)
      system_.outputs.push_back(variable(section_for("Output", k, system), true));
    for (const Section& s : sections_)
      if (s.index > (s.kind == "Input" ? num_inputs_ : num_outputs_) && s.index > 0)
        fail("[" + s.kind + std::to_string(s.index) + "]",
             "section beyond Num" + s.kind +
                 "s=" + std::to_string(s.kind == "Input" ? num_inputs_ : num_outputs_),
             s.line);
    if (type_ == FisType::hybrid) check_hybrid_defuzz(system);
    rules(section_for("Rules", 0, system));
    return std::move(system_);
  }

 private:
  [[noreturn]] void fail(const std::string& field, const std::string& message, int line) const {
    throw InputError(path_, field, message, line);
  }

  // The section, or an error at the line of the count that calls for it.
  const Section& section_for(const std::string& kind, int index, const Section& system) {
    if (const Section* s = find(kind, index)) return *s;
    const std::string name = "[" + kind + (index ? std::to_string(index) : "") + "]";
    const std::string key = kind == "Input"    ? "NumInputs"
                            : kind == "Output" ? "NumOutputs"
                                               : "NumRules";
    const Entry* count = system.find(key);
    fail("[System] " + key,
         "missing section " + name + " (" + key + "=" +
             std::to_string(kind == "Input"    ? num_inputs_
                            : kind == "Output" ? num_outputs_
                                               : num_rules_) +
             ")",
         count ? count->line : system.line);
  }
  const Section& section(const std::string& kind, int index) {
    if (const Section* s = find(kind, index)) return *s;
    fail("[" + kind + "]", "missing section [" + kind + "]", 0);
  }
  const Section* find(const std::string& kind, int index) const {
    for (const Section& s : sections_)
      if (s.kind == kind && s.index == index) return &s;
    return nullptr;
  }

  const Entry& required(const Section& s, const std::string& key) {
    if (const Entry* e = s.find(key)) return *e;
    fail(s.title() + " " + key, "missing " + key + " in " + s.title(), s.line);
  }

  // ---- [System] -------------------------------------------------------------

  void read_system(const Section& s) {
    static const char* const kKnown[] = {"Name",       "Type",      "Version",     "NumInputs",
                                         "NumOutputs", "NumRules",  "AndMethod",   "OrMethod",
                                         "ImpMethod",  "AggMethod", "DefuzzMethod"};
    s.only(kKnown, path_);
    if (const Entry* e = s.find("Name")) {
      system_.name = fis::text(*e, s, path_);
      if (!system_.name.empty()) fis::check_name(system_.name, s.title() + " Name", e->line, path_);
    }
    if (const Entry* e = s.find("Version"))
      fis::number(e->value, s.title() + " Version", e->line, path_);
    const Entry& type = required(s, "Type");
    const std::string t = fis::lower(fis::text(type, s, path_));
    if (t != "mamdani" && t != "sugeno" && t != "hybrid")
      fail(s.title() + " Type",
           "Type '" + fis::shown(t) +
               "' is not supported: this engine reads mamdani, sugeno and hybrid (fuzzylite)",
           type.line);
    type_ = t == "sugeno" ? FisType::sugeno : t == "hybrid" ? FisType::hybrid : FisType::mamdani;
    const bool sugeno = type_ == FisType::sugeno;
    num_inputs_ = count(s, "NumInputs", kMaxVariables);
    num_outputs_ = count(s, "NumOutputs", kMaxVariables);
    num_rules_ = count(s, "NumRules", kMaxRules);
    if (num_outputs_ == 0)
      fail(s.title() + " NumOutputs", "a rule base needs an output",
           required(s, "NumOutputs").line);
    if (num_rules_ == 0)
      fail(s.title() + " NumRules", "a rule base needs a rule", required(s, "NumRules").line);
    // MATLAB's newfis defaults stand in for a method left out.
    and_ = method(s, "AndMethod", sugeno ? "prod" : "min",
                  {{"min", 0}, {"prod", 1}, {"algebraic_product", 1}});
    or_ = method(s, "OrMethod", sugeno ? "probor" : "max",
                 {{"max", 0}, {"probor", 1}, {"algebraic_sum", 1}});
    imp_ = method(s, "ImpMethod", sugeno ? "prod" : "min",
                  {{"min", 0}, {"prod", 1}, {"algebraic_product", 1}});
    agg_ = method(s, "AggMethod", sugeno ? "sum" : "max", {{"max", 0}, {"sum", 1}});
    // A hybrid system's DefuzzMethod is its first output's (what fuzzylite
    // writes); check_hybrid_defuzz() holds it to that once the outputs are read.
    if (type_ == FisType::hybrid)
      hybrid_defuzz_ = method(s, "DefuzzMethod", nullptr, {{"centroid", 0}, {"wtaver", 1}});
    else
      method(s, "DefuzzMethod", sugeno ? "wtaver" : "centroid",
             {{sugeno ? "wtaver" : "centroid", 0}});
  }

  void check_hybrid_defuzz(const Section& s) {
    const LinguisticVariable& first = system_.outputs.front();
    const int first_kind = first.method == Defuzzification::weighted_average ? 1 : 0;
    if (hybrid_defuzz_ >= 0 && hybrid_defuzz_ != first_kind)
      fail(s.title() + " DefuzzMethod",
           std::string("a hybrid system's DefuzzMethod is its first output's, and '") +
               fis::shown(first.name) + "' is " +
               (first_kind ? "sugeno (wtaver, its MFs are constant or linear)"
                           : "mamdani (centroid, its MFs are not constant or linear)"),
           required(s, "DefuzzMethod").line);
  }

  int count(const Section& s, const std::string& key, int max) {
    const Entry& e = required(s, key);
    const double v = fis::number(e.value, s.title() + " " + key, e.line, path_);
    if (!(v >= 0 && v <= max && v == std::floor(v)))
      fail(s.title() + " " + key,
           key + " must be a whole number from 0 to " + std::to_string(max) + ", got " +
               fis::shown(e.value),
           e.line);
    return static_cast<int>(v);
  }

  // The index of the method's name in `known` (0 or 1), or an error naming
  // what was found and what this engine offers.
  int method(const Section& s, const std::string& key, const char* fallback,
             std::initializer_list<std::pair<const char*, int>> known) {
    const Entry* e = s.find(key);
    if (!e && !fallback) return -1;  // nothing to default to: the caller decides
    const std::string name = e ? fis::lower(fis::text(*e, s, path_)) : fallback;
    std::string offered;
    for (const auto& [k, v] : known) {
      if (name == k) return v;
      offered += (offered.empty() ? "" : ", ") + std::string(k);
    }
    fail(s.title() + " " + key,
         key + " '" + fis::shown(name) + "' is not supported for " + type_name() +
             ": this engine offers " + offered,
         e ? e->line : s.line);
  }

  const char* type_name() const {
    return type_ == FisType::sugeno ? "sugeno" : type_ == FisType::hybrid ? "hybrid" : "mamdani";
  }

  // ---- [InputN] / [OutputN] -------------------------------------------------

  LinguisticVariable variable(const Section& s, bool output) {
    LinguisticVariable v;
    const std::string title = s.title();
    for (const Entry& e : s.entries)
      if (e.key != "Name" && e.key != "Range" && e.key != "NumMFs" && fis::mf_index(e.key) < 0)
        fail(title + " " + fis::shown(e.key),
             "unknown key '" + fis::shown(e.key) + "' in " + title +
                 " (expected Name, Range, NumMFs, MF1..MFn)",
             e.line);
    const Entry& name = required(s, "Name");
    v.name = fis::text(name, s, path_);
    fis::check_name(v.name, title + " Name", name.line, path_);
    for (const auto* list : {&system_.inputs, &system_.outputs})
      for (const LinguisticVariable& other : *list)
        if (other.name == v.name)
          fail(title + " Name", "duplicate variable name '" + fis::shown(v.name) + "'", name.line);
    const Entry& range = required(s, "Range");
    const std::vector<double> r = fis::vector(range.value, title + " Range", range.line, path_, 2);
    if (r.size() != 2 || !(r[0] < r[1]))
      fail(title + " Range", "Range needs [min max] with min < max, got " + fis::shown(range.value),
           range.line);
    v.min = r[0];
    v.max = r[1];
    const int n = count(s, "NumMFs", kMaxTerms);
    std::vector<const Entry*> mfs(static_cast<std::size_t>(n), nullptr);
    names_.clear();
    output_sugeno_ = output && type_ == FisType::sugeno;
    for (const Entry& e : s.entries) {
      const int k = fis::mf_index(e.key);
      if (k < 0) continue;
      if (k < 1 || k > n)
        fail(title + " " + e.key, e.key + " beyond NumMFs=" + std::to_string(n), e.line);
      mfs[static_cast<std::size_t>(k - 1)] = &e;
    }
    if (output && type_ == FisType::hybrid && n > 0 && mfs[0])
      output_sugeno_ = sugeno_mf(*mfs[0], title);
    for (int k = 1; k <= n; ++k) {
      const Entry* e = mfs[static_cast<std::size_t>(k - 1)];
      if (!e)
        fail(title + " NumMFs",
             "NumMFs=" + std::to_string(n) + " but MF" + std::to_string(k) + " is missing",
             required(s, "NumMFs").line);
      v.terms.push_back(term(*e, title, output));
    }
    if (n == 0)
      fail(title + " NumMFs", "'" + fis::shown(v.name) + "' has no membership function",
           required(s, "NumMFs").line);
    v.method = output_sugeno_ ? Defuzzification::weighted_average : Defuzzification::centroid;
    return v;
  }

  // In a hybrid system an output is sugeno when its MF1 is constant or linear
  // (as this engine reads FCL: COGS exactly when every term is a singleton or
  // linear); shape() holds the other MFs to the same kind.
  bool sugeno_mf(const Entry& e, const std::string& title) {
    const fis::MfLine mf =
        fis::mf_line(e.value, title + " " + e.key, e.line, path_, kMaxMfParameters);
    const std::string type = fis::lower(mf.type);
    return type == "constant" || type == "linear";
  }

  Term term(const Entry& e, const std::string& title, bool output) {
    const std::string field = title + " " + e.key;
    const fis::MfLine mf = fis::mf_line(e.value, field, e.line, path_, kMaxMfParameters);
    fis::check_name(mf.name, field, e.line, path_);
    if (!names_.insert(mf.name).second)
      fail(field, "duplicate membership function name '" + fis::shown(mf.name) + "'", e.line);
    Term t{mf.name, shape(mf, field, e.line, output)};
    const std::string problem = t.function.validate();
    if (!problem.empty()) fail(field, problem, e.line);
    // No check against Range: MATLAB's own default terms reach beyond it
    // (trimf [-0.4 0 0.4] on [0 1]). Inference reads a term only inside the
    // range (inputs are clamped to it, a centroid integrates over it), so such
    // a term means what it draws there, as in MATLAB.
    return t;
  }

  MembershipFunction shape(const fis::MfLine& mf, const std::string& field, int line, bool output) {
    const std::string type = fis::lower(mf.type);
    const auto& p = mf.params;
    const bool sugeno_out = output && output_sugeno_;
    const bool hybrid = type_ == FisType::hybrid;
    auto need = [&](std::size_t n) {
      if (p.size() != n)
        fail(field,
             type + " takes " + std::to_string(n) + " parameters, got " + std::to_string(p.size()),
             line);
    };
    if (type == "constant" || type == "linear") {
      if (!sugeno_out)
        fail(field,
             type + " is a Sugeno output; " +
                 (!output  ? "not an input's membership function"
                  : hybrid ? "this output of a hybrid system is mamdani (its MF1 is neither "
                             "constant nor linear)"
                           : "this system is mamdani"),
             line);
      if (type == "constant") {
        need(1);
        return {Shape::singleton, p};
      }
      // MATLAB: [a1 .. an c], the constant last; ours: c0 first.
      need(static_cast<std::size_t>(num_inputs_) + 1);
      std::vector<double> q{p.back()};
      q.insert(q.end(), p.begin(), p.end() - 1);
      return {Shape::linear, q};
    }
    if (sugeno_out)
      fail(field,
           "a sugeno output's membership functions are constant or linear, got " +
               fis::shown(mf.type) +
               (hybrid ? " (this output of a hybrid system is sugeno: its MF1 is constant or "
                         "linear)"
                       : ""),
           line);
    // fuzzylite's Discrete and Ramp, as its FisExporter writes them.
    if (type == "discretemf") {
      if (p.size() < 2 || p.size() % 2)
        fail(field,
             "discretemf takes x y pairs ([x1 y1 x2 y2 ...]), got " + std::to_string(p.size()) +
                 " numbers",
             line);
      return {Shape::points, p};  // validate() holds x in order, y in [0, 1], the count
    }
    if (type == "rampmf") {
      need(2);
      if (p[0] == p[1]) fail(field, "rampmf needs start != end", line);
      return ramp(p[0], p[1]);
    }
    // MATLAB's parameter orders; only gaussmf [sigma c] differs from ours.
    static const struct {
      const char* type;
      Shape shape;
    } kShapes[] = {{"trimf", Shape::triangle},
                   {"trapmf", Shape::trapezoid},
                   {"gaussmf", Shape::gaussian},
                   {"gbellmf", Shape::bell},
                   {"sigmf", Shape::sigmoid}};
    for (const auto& k : kShapes) {
      if (type != k.type) continue;
      need(static_cast<std::size_t>(parameter_count(k.shape)));
      if (k.shape == Shape::gaussian) return {Shape::gaussian, {p[1], p[0]}};
      return {k.shape, p};
    }

    fail(field,
         "membership function type '" + fis::shown(mf.type) +
             "' has no equivalent in this engine (it reads trimf, trapmf, gaussmf, gbellmf, sigmf, "
             "discretemf, rampmf, constant and linear)",
         line);
  }

  // ---- [Rules] --------------------------------------------------------------

  void rules(const Section& s) {
    if (static_cast<int>(s.rows.size()) != num_rules_)
      fail("[System] NumRules",
           "NumRules=" + std::to_string(num_rules_) + " but [Rules] holds " +
               std::to_string(s.rows.size()) + " rules",
           required(*find("System", 0), "NumRules").line);
    RuleBlock block;
    block.and_method = and_ ? AndMethod::product : AndMethod::min;
    block.or_method = or_ ? OrMethod::probabilistic_sum : OrMethod::max;
    block.activation = imp_ ? Activation::product : Activation::min;
    block.accumulation = agg_ ? Accumulation::sum : Accumulation::max;
    for (std::size_t i = 0; i < s.rows.size(); ++i)
      block.rules.push_back(rule(s.rows[i], static_cast<int>(i) + 1));
    system_.blocks.push_back(std::move(block));
  }

  Rule rule(const fis::Row& row, int number) {
    const std::string field = "[Rules] rule " + std::to_string(number);
    const fis::RuleLine r =
        fis::rule_line(row.text, num_inputs_, num_outputs_, field, row.line, path_);
    Rule out;
    out.label = std::to_string(number);
    out.line = row.line;
    out.weight = r.weight;
    if (!(r.weight >= 0 && r.weight <= 1))
      fail(field, "weight must be in [0, 1], got " + fis::show(r.weight), row.line);
    if (r.connection != 1 && r.connection != 2)
      fail(field, "connection must be 1 (AND) or 2 (OR), got " + fis::show(r.connection), row.line);
    std::vector<Condition> terms;
    for (int i = 0; i < num_inputs_; ++i) {
      const RuleEntry e =
          entry(r.inputs[static_cast<std::size_t>(i)], system_.inputs[static_cast<std::size_t>(i)],
                "input", field, row.line);
      if (e.mf == 0) continue;  // don't care
      Condition c;
      c.variable = i;
      c.term = e.mf - 1;
      c.negated = e.negated;
      c.hedges = e.hedges;
      terms.push_back(std::move(c));
    }
    if (terms.empty()) fail(field, "the rule tests no input (every input entry is 0)", row.line);
    if (terms.size() == 1) {
      out.condition = std::move(terms[0]);
    } else {
      out.condition.kind = r.connection == 1 ? Condition::Kind::all : Condition::Kind::any;
      out.condition.children = std::move(terms);
    }
    for (int o = 0; o < num_outputs_; ++o) {
      const RuleEntry e =
          entry(r.outputs[static_cast<std::size_t>(o)],
                system_.outputs[static_cast<std::size_t>(o)], "output", field, row.line);
      if (e.mf == 0) continue;
      if (system_.outputs[static_cast<std::size_t>(o)].method ==
              Defuzzification::weighted_average &&
          (e.negated || !e.hedges.empty()))
        fail(field,
             "NOT or a hedge on sugeno output '" +
                 fis::shown(system_.outputs[static_cast<std::size_t>(o)].name) +
                 "', whose terms are values",
             row.line);
      out.consequents.emplace_back(o, e.mf - 1, e.hedges, e.negated);
    }
    if (out.consequents.empty())
      fail(field, "the rule sets no output (every output entry is 0)", row.line);
    return out;
  }

  RuleEntry entry(double v, const LinguisticVariable& var, const char* what,
                  const std::string& field, int line) {
    RuleEntry e;
    e.negated = v < 0;
    const double a = std::abs(v);
    if (!(a <= kMaxTerms + 1))
      fail(field, "membership function index " + fis::show(v) + " is out of range", line);
    e.mf = static_cast<int>(a);
    // Octave's hedges: the fraction, rounded to two digits, is a power x 10.
    const long code = std::lround(100 * (a - e.mf));
    if (code == 5)
      e.hedges.push_back(Hedge::somewhat);
    else if (code == 20)
      e.hedges.push_back(Hedge::very);
    else if (code != 0)
      fail(field,
           "hedge code " + fis::show(v) + " (power " + fis::show(code / 10.0) +
               ") is not supported: this engine has somewhat (.05) and very (.20)",
           line);
    if (e.mf > static_cast<int>(var.terms.size()))
      fail(field,
           "the rule refers to membership function " + std::to_string(e.mf) + " of " + what + " '" +
               fis::shown(var.name) + "', which has " + std::to_string(var.terms.size()),
           line);
    if (e.mf == 0 && (e.negated || code != 0))
      fail(field, "entry " + fis::show(v) + " negates or hedges no membership function", line);
    return e;
  }

  std::string path_;
  std::vector<Section> sections_;
  std::set<std::string> names_;  // of the MFs of the variable being read
  FuzzySystem system_;
  FisType type_ = FisType::mamdani;
  bool output_sugeno_ = false;  // of the variable being read
  int hybrid_defuzz_ = -1;      // 0 centroid, 1 wtaver; -1 not given
  int num_inputs_ = 0, num_outputs_ = 0, num_rules_ = 0;
  int and_ = 0, or_ = 0, imp_ = 0, agg_ = 0;
};

}  // namespace

FuzzySystem parse_fis(const std::string& text, const std::string& path) {
  return FisParser(text, path).parse();
}

FuzzySystem read_fis(const std::string& path) {
  return parse_fis(read_text_file(path, "FIS file", kMaxRuleBaseBytes), path);
}

}  // namespace neurocloth::fuzzy
