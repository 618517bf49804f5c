#include "fcl_reader.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <system_error>
#include <utility>

#include "fcl_lexer.h"
#include "input_error.h"

namespace neurocloth::fuzzy {
namespace {

using fcl::Pos;
using fcl::Token;
using fcl::TokenKind;
using fcl::where;

std::string show(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

// "a, b, c" from variables or terms.
template <class T>
std::string names(const std::vector<T>& list) {
  std::string s;
  for (const T& item : list)
    s += (s.empty() ? "" : ", ") + item.name;
  return s.empty() ? "none" : s;
}

// The parameters that are positions on the variable's axis (checked against
// RANGE, and what RANGE is inferred from when absent).
std::vector<double> x_positions(const MembershipFunction& f) {
  const auto& p = f.params;
  if (f.shape == Shape::points) return f.breakpoints();
  if (f.shape == Shape::gaussian) return {p[0]};  // mean
  if (f.shape == Shape::bell) return {p[2]};      // centre c
  if (f.shape == Shape::sigmoid) return {p[1]};   // centre
  if (f.shape == Shape::linear) return {};
  return p;  // trian, trape, singleton: every parameter
}

// "variable IS term" in a rule, kept by name until the whole file is read: a
// RULEBLOCK may come before the blocks that define its variables and terms.
struct Reference {
  std::string variable, term, field;
  Pos variable_at, term_at;
};

// "linear 0.5 mass 2": inputs are named, and their order (VAR_INPUT) is only
// known at the end.
struct LinearInput {
  std::string name;
  double coefficient = 0;
  Pos at;
};

struct TermSource {
  Pos at;  // the term's name
  std::vector<LinearInput> inputs;
};

struct VariableBlock {
  LinguisticVariable variable;
  bool output = false;
  std::string field;  // "FUZZIFY mass"
  Pos at;             // the variable's name
  std::vector<TermSource> terms;
  bool has_range = false, has_method = false, has_default = false;
  Pos method_at;
};

struct Declaration {
  std::string name;
  bool input = true;
  Pos at;
};

class Parser : fcl::Cursor {
 public:
  Parser(const std::string& text, const std::string& path) : Cursor(text, path) {}

  FuzzySystem parse() {
    function_block();
    return resolve();
  }

 private:
  // ---- FUNCTION_BLOCK and VAR -----------------------------------------------

  void function_block() {
    const Token head = expect_keyword("FUNCTION_BLOCK", "FUNCTION_BLOCK");
    if (at_name()) system_.name = take().text;
    outer_field_ = "FUNCTION_BLOCK" + (system_.name.empty() ? "" : " " + system_.name);
    function_at_ = where(head);
    open(head, outer_field_, "END_FUNCTION_BLOCK");
    while (!accept_keyword("END_FUNCTION_BLOCK")) {
      if (at_keyword("VAR_INPUT") || at_keyword("VAR_OUTPUT"))
        declarations(at_keyword("VAR_INPUT"));
      else if (at_keyword("FUZZIFY") || at_keyword("DEFUZZIFY"))
        variable_block(at_keyword("DEFUZZIFY"));
      else if (at_keyword("RULEBLOCK"))
        rule_block();
      else
        unexpected("VAR_INPUT, VAR_OUTPUT, FUZZIFY, DEFUZZIFY, RULEBLOCK or END_FUNCTION_BLOCK");
    }
    close();
    if (peek().kind != TokenKind::end)
      fail("expected end of file after END_FUNCTION_BLOCK (one function block per file), got '" +
               peek().text + "'",
           where(peek()));
  }

  void declarations(bool input) {
    const Token head = take();
    open(head, input ? "VAR_INPUT" : "VAR_OUTPUT", "END_VAR");
    while (!accept_keyword("END_VAR")) {
      const Token name = expect_name("a variable name or END_VAR");
      expect_symbol(":", "':' after the variable name");
      expect_keyword("REAL", "REAL (the only variable type)");
      expect_symbol(";", "';' after REAL");
      for (const Declaration& d : declared_)
        if (d.name == name.text)
          fail("duplicate variable '" + name.text + "' (first declared at line " +
                   std::to_string(d.at.line) + ")",
               where(name));
      declared_.push_back({name.text, input, where(name)});
    }
    close();
  }

  // ---- FUZZIFY and DEFUZZIFY --------------------------------------------------

  void variable_block(bool output) {
    const Token head = take();
    const std::string keyword = output ? "DEFUZZIFY" : "FUZZIFY";
    const Token name = expect_name("a variable name after " + keyword);
    VariableBlock b;
    b.output = output;
    b.variable.name = name.text;
    b.field = keyword + " " + name.text;
    b.at = where(name);
    open(head, b.field, output ? "END_DEFUZZIFY" : "END_FUZZIFY");
    for (const VariableBlock& other : blocks_)
      if (other.variable.name == name.text)
        fail("duplicate block for variable '" + name.text + "' (the first is at line " +
                 std::to_string(other.at.line) + ")",
             b.at);
    while (!accept_keyword(output ? "END_DEFUZZIFY" : "END_FUZZIFY")) {
      if (at_keyword("TERM"))
        term(b);
      else if (at_keyword("RANGE"))
        range(b);
      else if (output && at_keyword("METHOD"))
        method(b);
      else if (output && at_keyword("DEFAULT"))
        default_value(b);
      else
        unexpected(output ? "TERM, RANGE, METHOD, DEFAULT or END_DEFUZZIFY"
                          : "TERM, RANGE or END_FUZZIFY");
    }
    finish(b);
    close();
    blocks_.push_back(std::move(b));
  }

  void range(VariableBlock& b) {
    const Token head = take();
    if (b.has_range) fail("RANGE given twice", where(head));
    expect_symbol(":=", "':=' after RANGE");
    expect_symbol("(", "'(' to open the RANGE");
    const double lo = expect_number("the RANGE minimum (a number)");
    expect_symbol("..", "'..' between the RANGE bounds");
    const double hi = expect_number("the RANGE maximum (a number)");
    expect_symbol(")", "')' to close the RANGE");
    expect_symbol(";", "';' after RANGE");
    if (!(lo < hi))
      fail("RANGE needs min < max, got (" + show(lo) + " .. " + show(hi) + ")", where(head));
    b.has_range = true;
    b.variable.min = lo;
    b.variable.max = hi;
  }

  void term(VariableBlock& b) {
    take();
    const Token name = expect_name("a term name after TERM");
    field_ = "TERM " + name.text;
    if (b.variable.term_index(name.text) >= 0)
      fail("duplicate term '" + name.text + "' in " + b.field, where(name));
    expect_symbol(":=", "':=' after the term name");
    TermSource source{where(name), {}};
    Term t{name.text, membership(b, source)};
    expect_symbol(";", "';' after TERM definition");
    const std::string problem = t.function.validate();
    if (!problem.empty()) fail(problem, where(name));
    b.variable.terms.push_back(std::move(t));
    b.terms.push_back(std::move(source));
    field_ = b.field;
  }

  // Shape names are to_string(Shape), as the writer writes them.
  MembershipFunction membership(const VariableBlock& b, TermSource& source) {
    if (peek().kind == TokenKind::number) return {Shape::singleton, {take().value}};
    if (at_symbol("(")) return points();
    MembershipFunction f{Shape::points, {}};
    for (Shape s : {Shape::triangle, Shape::trapezoid, Shape::gaussian, Shape::bell, Shape::sigmoid,
                    Shape::singleton, Shape::linear})
      if (at_keyword(to_string(s))) f.shape = s;
    if (f.shape == Shape::points)
      unexpected(
          "a membership function (a number, '(x, y) ...', trian, trape, gauss, gbell, "
          "sigm, singleton or linear)");
    const Token head = take();
    if (f.shape == Shape::linear) return linear(b, head, source);
    const int n = parameter_count(f.shape);
    for (int i = 0; i < n; ++i)
      f.params.push_back(expect_number("a number (" + std::string(to_string(f.shape)) + " takes " +
                                       std::to_string(n) + " parameters)"));
    return f;
  }

  MembershipFunction points() {
    MembershipFunction f{Shape::points, {}};
    while (accept_symbol("(")) {
      f.params.push_back(expect_number("a point's x (a number)"));
      expect_symbol(",", "',' between a point's x and its degree");
      f.params.push_back(expect_number("a point's membership degree (a number)"));
      expect_symbol(")", "')' to close the point");
    }
    return f;
  }

  // The constant now; each named input's coefficient goes to its place once
  // VAR_INPUT's order is known (resolve_linear).
  MembershipFunction linear(const VariableBlock& b, const Token& head, TermSource& source) {
    if (!b.output)
      fail("linear terms are Takagi-Sugeno consequents, allowed only in DEFUZZIFY", where(head));
    MembershipFunction f{Shape::linear, {expect_number("the constant c0 after linear")}};
    while (at_name()) {
      const Token input = take();
      for (const LinearInput& seen : source.inputs)
        if (seen.name == input.text)
          fail("input '" + input.text + "' appears twice in this linear term", where(input));
      const double c = expect_number("a coefficient after '" + input.text + "'");
      source.inputs.push_back({input.text, c, where(input)});
    }
    return f;
  }

  void method(VariableBlock& b) {
    const Token head = take();
    if (b.has_method) fail("METHOD given twice", where(head));
    expect_symbol(":", "':' after METHOD");
    if (at_keyword("COG"))
      b.variable.method = Defuzzification::centroid;
    else if (at_keyword("COGS"))
      b.variable.method = Defuzzification::weighted_average;
    else
      unexpected("COG or COGS (the supported defuzzification methods)");
    take();
    expect_symbol(";", "';' after METHOD");
    b.has_method = true;
    b.method_at = where(head);
  }

  void default_value(VariableBlock& b) {
    const Token head = take();
    if (b.has_default) fail("DEFAULT given twice", where(head));
    expect_symbol(":=", "':=' after DEFAULT");
    b.variable.default_value = accept_keyword("NC")
                                   ? std::numeric_limits<double>::quiet_NaN()
                                   : expect_number("a number or NC after DEFAULT :=");
    expect_symbol(";", "';' after DEFAULT");
    b.has_default = true;
  }

  // Checks that need the whole block: RANGE (given or inferred), METHOD.
  void finish(VariableBlock& b) {
    LinguisticVariable& v = b.variable;
    if (v.terms.empty()) fail("'" + v.name + "' has no TERM", b.at);
    if (!b.has_range) infer_range(b);
    for (std::size_t i = 0; i < v.terms.size(); ++i)
      for (double x : x_positions(v.terms[i].function))
        if (x < v.min || x > v.max) {
          field_ = "TERM " + v.terms[i].name;
          fail("term out of range: x = " + show(x) + " lies outside the RANGE (" + show(v.min) +
                   " .. " + show(v.max) + ") of '" + v.name + "'",
               b.terms[i].at);
        }
    if (b.output) check_method(b);
  }

  void infer_range(VariableBlock& b) {
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const Term& t : b.variable.terms)
      for (double x : x_positions(t.function)) {
        lo = std::min(lo, x);
        hi = std::max(hi, x);
      }
    if (!(lo < hi))
      fail(
          "no RANGE given, and the terms' x positions span no interval to infer one from; add "
          "RANGE := (min .. max);",
          b.at);
    b.variable.min = lo;
    b.variable.max = hi;
  }

  // COG integrates membership functions; COGS weights constants (singleton or
  // linear). A mixture has no meaning under either.
  void check_method(const VariableBlock& b) {
    if (!b.has_method) fail("no METHOD given (expected METHOD : COG; or METHOD : COGS;)", b.at);
    const bool sugeno = b.variable.method == Defuzzification::weighted_average;
    for (std::size_t i = 0; i < b.variable.terms.size(); ++i) {
      const Term& t = b.variable.terms[i];
      const bool constant =
          t.function.shape == Shape::singleton || t.function.shape == Shape::linear;
      if (constant == sugeno) continue;
      const std::string term = "term '" + t.name + "' (line " + std::to_string(b.terms[i].at.line) +
                               ") is " + to_string(t.function.shape);
      fail(sugeno ? "METHOD COGS needs every term to be singleton or linear, but " + term
                  : "METHOD COG needs membership functions, but " + term + "; use COGS",
           b.method_at);
    }
  }

  // ---- RULEBLOCK ------------------------------------------------------------

  void rule_block() {
    const Token head = take();
    RuleBlock rb;
    const Pos name_at = where(peek());
    if (at_name()) rb.name = take().text;
    open(head, "RULEBLOCK" + (rb.name.empty() ? "" : " " + rb.name), "END_RULEBLOCK");
    for (const RuleBlock& other : system_.blocks)
      if (!rb.name.empty() && other.name == rb.name)
        fail("duplicate RULEBLOCK name '" + rb.name + "'", name_at);
    std::array<bool, 4> given{};
    while (!accept_keyword("END_RULEBLOCK")) {
      if (at_keyword("RULE"))
        rb.rules.push_back(rule(rb));
      else if (!setting(rb, given))
        unexpected("RULE, AND, OR, ACT, ACCU or END_RULEBLOCK");
    }
    close();
    system_.blocks.push_back(std::move(rb));
  }

  // AND : MIN; OR : MAX; ACT : MIN; ACCU : MAX; and their alternatives. False
  // when the next token starts none of them.
  bool setting(RuleBlock& rb, std::array<bool, 4>& given) {
    static const char* const kSetting[4][3] = {{"AND", "MIN", "PROD"},
                                               {"OR", "MAX", "ASUM"},
                                               {"ACT", "MIN", "PROD"},
                                               {"ACCU", "MAX", "SUM"}};
    int which = -1;
    for (int i = 0; i < 4; ++i)
      if (at_keyword(kSetting[i][0])) which = i;
    if (which < 0) return false;
    const Token head = take();
    const std::string name = head.text, first = kSetting[which][1], second = kSetting[which][2];
    if (std::exchange(given[which], true))
      fail(name + " given twice in this RULEBLOCK", where(head));
    expect_symbol(":", "':' after " + name);
    const bool alternative = at_keyword(second.c_str());
    if (!alternative && !at_keyword(first.c_str()))
      unexpected(first + " or " + second + " after " + name + " :");
    take();
    expect_symbol(";", "';' after the " + name + " method");
    if (which == 0) rb.and_method = alternative ? AndMethod::product : AndMethod::min;
    if (which == 1) rb.or_method = alternative ? OrMethod::probabilistic_sum : OrMethod::max;
    if (which == 2) rb.activation = alternative ? Activation::product : Activation::min;
    if (which == 3) rb.accumulation = alternative ? Accumulation::sum : Accumulation::max;
    return true;
  }

  Rule rule(const RuleBlock& rb) {
    const Token head = take();
    if (!at_name() && peek().kind != TokenKind::number)
      unexpected("a rule label after RULE (a number or a name)");
    const Token label = take();
    Rule r;
    r.label = label.text;
    r.line = head.line;
    const std::string block_field = std::exchange(field_, "RULE " + r.label);
    for (const Rule& other : rb.rules)
      if (other.label == r.label)
        fail("duplicate rule label '" + r.label + "' in this RULEBLOCK (first at line " +
                 std::to_string(other.line) + ")",
             where(label));
    expect_symbol(":", "':' after the rule label");
    expect_keyword("IF", "IF");
    r.condition = disjunction();
    expect_keyword("THEN", "THEN, AND or OR after the condition");
    do
      r.consequents.push_back(consequent());
    while (accept_symbol(","));
    if (accept_keyword("WITH")) {
      const Token weight = peek();
      r.weight = expect_number("a weight after WITH (a number in [0, 1])");
      if (!(r.weight >= 0 && r.weight <= 1))
        fail("WITH weight must be in [0, 1], got " + weight.text, where(weight));
      expect_symbol(";", "';' after the rule");
    } else {
      expect_symbol(";", "',', WITH or ';' after the consequent");
    }
    field_ = block_field;
    return r;
  }

  // OR of ANDs: AND binds tighter. A chain "a AND b AND c" is one node; a
  // parenthesised group stays its own node, so the tree is exactly as written.
  Condition disjunction() { return chain(Condition::Kind::any, "OR"); }
  Condition conjunction() { return chain(Condition::Kind::all, "AND"); }

  Condition chain(Condition::Kind kind, const char* connective) {
    const bool any = kind == Condition::Kind::any;
    Condition first = any ? conjunction() : unary();
    if (!at_keyword(connective)) return first;
    Condition node;
    node.kind = kind;
    node.children.push_back(std::move(first));
    while (accept_keyword(connective))
      node.children.push_back(any ? conjunction() : unary());
    return node;
  }

  Condition unary() {
    if (accept_keyword("NOT")) {
      Condition node;
      node.kind = Condition::Kind::negation;
      node.children.push_back(unary());
      return node;
    }
    if (accept_symbol("(")) {
      Condition inner = disjunction();
      expect_symbol(")", "')' to close '(', or AND / OR");
      return inner;
    }
    return clause();
  }

  Condition clause() {
    const Token variable = expect_name("a variable name, NOT or '('");
    expect_keyword("IS", "IS after '" + variable.text + "'");
    Condition c;
    c.negated = accept_keyword("NOT");
    for (;;) {
      if (accept_keyword("VERY"))
        c.hedges.push_back(Hedge::very);
      else if (accept_keyword("SOMEWHAT"))
        c.hedges.push_back(Hedge::somewhat);
      else
        break;
    }
    const Token term = expect_name("a term name");
    c.variable = remember(variable, term);
    return c;
  }

  Consequent consequent() {
    const Token variable = expect_name("an output variable name");
    expect_keyword("IS", "IS after '" + variable.text + "'");
    const Token term = expect_name("a term name (a consequent takes no NOT or hedge)");
    Consequent c;
    c.variable = remember(variable, term);
    return c;
  }

  // Until resolve(), a rule's `variable` holds an index into refs_.
  int remember(const Token& variable, const Token& term) {
    refs_.push_back({variable.text, term.text, field_, where(variable), where(term)});
    return static_cast<int>(refs_.size()) - 1;
  }

  // ---- Names to indices, once everything is read -------------------------------

  FuzzySystem resolve() {
    for (const VariableBlock& b : blocks_)
      check_declared(b);
    for (const Declaration& d : declared_) {
      const VariableBlock* block = nullptr;
      for (const VariableBlock& b : blocks_)
        if (b.variable.name == d.name) block = &b;
      field_ = d.input ? "VAR_INPUT" : "VAR_OUTPUT";
      if (!block)
        fail((d.input ? "input '" : "output '") + d.name + "' has no " +
                 (d.input ? "FUZZIFY" : "DEFUZZIFY") + " block",
             d.at);
      (d.input ? system_.inputs : system_.outputs).push_back(block->variable);
    }
    for (const VariableBlock& b : blocks_)
      if (b.output) resolve_linear(b);
    std::size_t rules = 0;
    for (RuleBlock& rb : system_.blocks)
      for (Rule& r : rb.rules) {
        resolve(r.condition);
        for (Consequent& c : r.consequents) {
          const auto [v, t] = lookup(refs_[c.variable], true);
          c.variable = v;
          c.term = t;
        }
        ++rules;
      }
    field_ = outer_field_;
    if (rules == 0) fail("the function block has no rules (a RULEBLOCK with a RULE)", function_at_);
    return std::move(system_);
  }

  void check_declared(const VariableBlock& b) {
    field_ = b.field;
    for (const Declaration& d : declared_) {
      if (d.name != b.variable.name) continue;
      if (d.input == b.output)
        fail("'" + d.name + "' is declared in " + (d.input ? "VAR_INPUT" : "VAR_OUTPUT") +
                 ", so its block must be " + (d.input ? "FUZZIFY" : "DEFUZZIFY"),
             b.at);
      return;
    }
    fail("unknown variable '" + b.variable.name + "': declare it in " +
             (b.output ? "VAR_OUTPUT" : "VAR_INPUT"),
         b.at);
  }

  void resolve_linear(const VariableBlock& b) {
    LinguisticVariable& v = system_.outputs[system_.output_index(b.variable.name)];
    for (std::size_t i = 0; i < v.terms.size(); ++i) {
      MembershipFunction& f = v.terms[i].function;
      if (f.shape != Shape::linear) continue;
      field_ = "TERM " + v.terms[i].name;
      std::vector<double> params(1 + system_.inputs.size(), 0.0);
      params[0] = f.params[0];
      for (const LinearInput& in : b.terms[i].inputs) {
        const int k = system_.input_index(in.name);
        if (k < 0)
          fail("linear term names '" + in.name +
                   "', which is not an input (inputs: " + names(system_.inputs) + ")",
               in.at);
        params[1 + static_cast<std::size_t>(k)] = in.coefficient;
      }
      f.params = std::move(params);
    }
  }

  void resolve(Condition& c) {
    for (Condition& child : c.children)
      resolve(child);
    if (c.kind != Condition::Kind::term) return;
    const auto [v, t] = lookup(refs_[c.variable], false);
    c.variable = v;
    c.term = t;
  }

  // (variable, term): an input for a condition, an output for a consequent.
  std::pair<int, int> lookup(const Reference& ref, bool output) {
    field_ = ref.field;
    const auto& own = output ? system_.outputs : system_.inputs;
    const int v = output ? system_.output_index(ref.variable) : system_.input_index(ref.variable);
    if (v < 0) {
      if ((output ? system_.input_index(ref.variable) : system_.output_index(ref.variable)) >= 0)
        fail(output ? "consequent on input '" + ref.variable + "': a consequent sets an output"
                    : "condition on output '" + ref.variable + "': a condition tests an input",
             ref.variable_at);
      fail("unknown variable '" + ref.variable + "' (" + (output ? "outputs: " : "inputs: ") +
               names(own) + ")",
           ref.variable_at);
    }
    const int t = own[static_cast<std::size_t>(v)].term_index(ref.term);
    if (t < 0)
      fail("unknown term '" + ref.term + "' of '" + ref.variable +
               "' (its terms: " + names(own[static_cast<std::size_t>(v)].terms) + ")",
           ref.term_at);
    return {v, t};
  }

  Pos function_at_;
  std::vector<Declaration> declared_;
  std::vector<VariableBlock> blocks_;
  std::vector<Reference> refs_;
  FuzzySystem system_;
};

}  // namespace

FuzzySystem parse_fcl(const std::string& text, const std::string& path) {
  return Parser(text, path).parse();
}

FuzzySystem read_fcl(const std::string& path) {
  std::error_code ignored;
  if (std::filesystem::is_directory(path, ignored))
    throw InputError(path, "", "is a directory, not an FCL file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "", "cannot open FCL file");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw InputError(path, "", "cannot read FCL file");
  return parse_fcl(text.str(), path);
}

}  // namespace neurocloth::fuzzy
