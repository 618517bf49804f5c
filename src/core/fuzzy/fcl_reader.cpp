#include "fcl_reader.h"

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <system_error>
#include <tuple>
#include <utility>

#include "fcl_lexer.h"
#include "input_error.h"
#include "text_file.h"

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

// A FUZZIFY or DEFUZZIFY block while it is read.
struct VariableBlock {
  LinguisticVariable variable;
  bool output = false;
  std::string field;  // "FUZZIFY mass"
  Pos at;             // the variable's name
  std::vector<Pos> term_at;
  bool has_range = false, has_method = false, has_default = false;
  Pos method_at;
};

// Where a declared variable was declared and (once read) defined.
struct Slot {
  Pos declared, defined;
  bool has_block = false;
};

// Reads in one pass, in the order IEC 61131-7 prescribes: every VAR section
// before the FUZZIFY / DEFUZZIFY blocks (in any order among themselves), and
// those before the RULEBLOCKs. So every name is known when it is used and
// errors come in file order.
class Parser : fcl::Cursor {
 public:
  Parser(const std::string& text, const std::string& path) : Cursor(text, path) {}

  FuzzySystem parse() {
    function_block();
    return std::move(system_);
  }

 private:
  enum class Part { declarations, variables, rules };

  // ---- FUNCTION_BLOCK and VAR -----------------------------------------------

  void function_block() {
    const Token head = expect_keyword("FUNCTION_BLOCK", "FUNCTION_BLOCK");
    if (at_name()) system_.name = take().text;
    outer_field_ = "FUNCTION_BLOCK" + (system_.name.empty() ? "" : " " + system_.name);
    open(head, outer_field_, "END_FUNCTION_BLOCK");
    while (!at_keyword("END_FUNCTION_BLOCK")) {
      if (at_keyword("VAR_INPUT") || at_keyword("VAR_OUTPUT"))
        declarations(at_keyword("VAR_INPUT"));
      else if (at_keyword("FUZZIFY") || at_keyword("DEFUZZIFY"))
        variable_block(at_keyword("DEFUZZIFY"));
      else if (at_keyword("RULEBLOCK"))
        rule_block();
      else
        unexpected("VAR_INPUT, VAR_OUTPUT, FUZZIFY, DEFUZZIFY, RULEBLOCK or END_FUNCTION_BLOCK");
    }
    const Token end = take();
    enter(Part::rules, end);
    close();
    std::size_t rules = 0;
    for (const RuleBlock& b : system_.blocks)
      rules += b.rules.size();
    if (rules == 0) fail("the function block has no rules (a RULEBLOCK with a RULE)", where(head));
    if (peek().kind != TokenKind::end)
      fail("expected end of file after END_FUNCTION_BLOCK (one function block per file), got '" +
               peek().text + "'",
           where(peek()));
  }

  // Moves on to `next`; leaving the variable blocks, every declared variable
  // must have had its block.
  void enter(Part next, const Token& head) {
    if (next < part_)
      fail(head.text + " must come before " +
               (part_ == Part::rules ? "the RULEBLOCKs" : "the FUZZIFY and DEFUZZIFY blocks"),
           where(head));
    if (next == Part::rules && part_ != Part::rules) {
      for (bool input : {true, false}) {
        const auto& slots = input ? input_slots_ : output_slots_;
        for (std::size_t i = 0; i < slots.size(); ++i) {
          if (slots[i].has_block) continue;
          field_ = input ? "VAR_INPUT" : "VAR_OUTPUT";
          fail((input ? "input '" + system_.inputs[i].name + "' has no FUZZIFY block"
                      : "output '" + system_.outputs[i].name + "' has no DEFUZZIFY block"),
               slots[i].declared);
        }
      }
    }
    part_ = next;
  }

  void declarations(bool input) {
    const Token head = take();
    enter(Part::declarations, head);
    open(head, input ? "VAR_INPUT" : "VAR_OUTPUT", "END_VAR");
    while (!accept_keyword("END_VAR")) {
      const Token name = expect_name("a variable name or END_VAR");
      expect_symbol(":", "':' after the variable name");
      expect_keyword("REAL", "REAL (the only variable type)");
      expect_symbol(";", "';' after REAL");
      const int i = system_.input_index(name.text), o = system_.output_index(name.text);
      if (i >= 0 || o >= 0)
        fail("duplicate variable '" + name.text + "'" +
                 first_at(i >= 0 ? input_slots_[i].declared : output_slots_[o].declared),
             where(name));
      LinguisticVariable v;
      v.name = name.text;
      (input ? system_.inputs : system_.outputs).push_back(std::move(v));
      (input ? input_slots_ : output_slots_).push_back({where(name), {}, false});
    }
    close();
  }

  static std::string first_at(Pos p) {
    return " (the first is at line " + std::to_string(p.line) + ")";
  }

  // For items a block may hold only once.
  void once(bool& given, const Token& head) {
    if (std::exchange(given, true)) fail(head.text + " given twice", where(head));
  }

  // ---- FUZZIFY and DEFUZZIFY --------------------------------------------------

  void variable_block(bool output) {
    const Token head = take();
    enter(Part::variables, head);
    const std::string keyword = output ? "DEFUZZIFY" : "FUZZIFY";
    const Token name = expect_name("a variable name after " + keyword);
    VariableBlock b;
    b.output = output;
    b.variable.name = name.text;
    b.field = keyword + " " + name.text;
    b.at = where(name);
    open(head, b.field, output ? "END_DEFUZZIFY" : "END_FUZZIFY");
    Slot& slot = declared_slot(b);
    if (slot.has_block)
      fail("duplicate block for variable '" + name.text + "'" + first_at(slot.defined), b.at);
    slot = {slot.declared, b.at, true};
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
    const int i = output ? system_.output_index(name.text) : system_.input_index(name.text);
    (output ? system_.outputs : system_.inputs)[static_cast<std::size_t>(i)] =
        std::move(b.variable);
  }

  Slot& declared_slot(const VariableBlock& b) {
    const std::string& name = b.variable.name;
    const int i = b.output ? system_.output_index(name) : system_.input_index(name);
    if (i >= 0) return (b.output ? output_slots_ : input_slots_)[static_cast<std::size_t>(i)];
    if ((b.output ? system_.input_index(name) : system_.output_index(name)) >= 0)
      fail("'" + name + "' is declared in " + (b.output ? "VAR_INPUT" : "VAR_OUTPUT") +
               ", so its block must be " + (b.output ? "FUZZIFY" : "DEFUZZIFY"),
           b.at);
    fail(
        "unknown variable '" + name + "': declare it in " + (b.output ? "VAR_OUTPUT" : "VAR_INPUT"),
        b.at);
  }

  void range(VariableBlock& b) {
    const Token head = take();
    once(b.has_range, head);
    expect_symbol(":=", "':=' after RANGE");
    expect_symbol("(", "'(' to open the RANGE");
    b.variable.min = expect_number("the RANGE minimum (a number)");
    expect_symbol("..", "'..' between the RANGE bounds");
    b.variable.max = expect_number("the RANGE maximum (a number)");
    expect_symbol(")", "')' to close the RANGE");
    expect_symbol(";", "';' after RANGE");
    if (!(b.variable.min < b.variable.max))
      fail("RANGE needs min < max, got (" + show(b.variable.min) + " .. " + show(b.variable.max) +
               ")",
           where(head));
  }

  void term(VariableBlock& b) {
    take();
    const Token name = expect_name("a term name after TERM");
    field_ = "TERM " + name.text;
    if (b.variable.term_index(name.text) >= 0)
      fail("duplicate term '" + name.text + "' in " + b.field, where(name));
    expect_symbol(":=", "':=' after the term name");
    Term t{name.text, membership(b)};
    expect_symbol(";", "';' after TERM definition");
    const std::string problem = t.function.validate();
    if (!problem.empty()) fail(problem, where(name));
    b.variable.terms.push_back(std::move(t));
    b.term_at.push_back(where(name));
    field_ = b.field;
  }

  // Shape names are to_string(Shape), as the writer writes them.
  MembershipFunction membership(const VariableBlock& b) {
    if (peek().kind == TokenKind::number) return {Shape::singleton, {take().value}};
    if (at_symbol("(")) return points();
    MembershipFunction f{Shape::points, {}};
    for (Shape s : {Shape::triangle, Shape::trapezoid, Shape::gaussian, Shape::bell, Shape::sigmoid,
                    Shape::singleton, Shape::linear})
      if (at_keyword(to_string(s))) f.shape = s;
    if (f.shape == Shape::points)
      unexpected(
          "a membership function (a number, '(x, y) ...', trian, trape, gauss, gbell, sigm, "
          "singleton or linear)");
    const Token head = take();
    if (f.shape == Shape::linear) return linear(b, head);
    const int n = parameter_count(f.shape);
    for (int i = 0; i < n; ++i)
      f.params.push_back(
          expect_number("a number (" + head.text + " takes " + std::to_string(n) + " parameters)"));
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

  // c0, then one coefficient per input in VAR_INPUT order (0 when not named).
  MembershipFunction linear(const VariableBlock& b, const Token& head) {
    if (!b.output)
      fail("linear terms are Takagi-Sugeno consequents, allowed only in DEFUZZIFY", where(head));
    MembershipFunction f{Shape::linear, std::vector<double>(1 + system_.inputs.size(), 0.0)};
    f.params[0] = expect_number("the constant c0 after linear");
    std::vector<char> named(system_.inputs.size(), 0);
    while (at_name()) {
      const Token input = take();
      const int k = system_.input_index(input.text);
      if (k < 0)
        fail("linear term names '" + input.text +
                 "', which is not an input (inputs: " + names(system_.inputs) + ")",
             where(input));
      if (std::exchange(named[static_cast<std::size_t>(k)], 1))
        fail("input '" + input.text + "' appears twice in this linear term", where(input));
      f.params[1 + static_cast<std::size_t>(k)] =
          expect_number("a coefficient after '" + input.text + "'");
    }
    return f;
  }

  void method(VariableBlock& b) {
    const Token head = take();
    once(b.has_method, head);
    b.method_at = where(head);
    expect_symbol(":", "':' after METHOD");
    const bool cogs = at_keyword("COGS");
    if (!cogs && !at_keyword("COG"))
      unexpected("COG or COGS (the supported defuzzification methods)");
    take();
    b.variable.method = cogs ? Defuzzification::weighted_average : Defuzzification::centroid;
    expect_symbol(";", "';' after METHOD");
  }

  void default_value(VariableBlock& b) {
    once(b.has_default, take());
    expect_symbol(":=", "':=' after DEFAULT");
    b.variable.default_value = accept_keyword("NC")
                                   ? std::numeric_limits<double>::quiet_NaN()
                                   : expect_number("a number or NC after DEFAULT :=");
    expect_symbol(";", "';' after DEFAULT");
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
               b.term_at[i]);
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
      fail("no RANGE given, and the terms' x positions span no interval to infer one from", b.at);
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
      const Shape shape = t.function.shape;
      if ((shape == Shape::singleton || shape == Shape::linear) == sugeno) continue;
      const std::string term = "term '" + t.name + "' (line " + std::to_string(b.term_at[i].line) +
                               ") is " + to_string(shape);
      fail(sugeno ? "METHOD COGS needs every term to be singleton or linear, but " + term
                  : "METHOD COG needs membership functions, but " + term + "; use COGS",
           b.method_at);
    }
  }

  // ---- RULEBLOCK ------------------------------------------------------------

  void rule_block() {
    const Token head = take();
    enter(Part::rules, head);
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
    once(given[static_cast<std::size_t>(which)], head);
    const std::string name = head.text, first = kSetting[which][1], second = kSetting[which][2];
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
        fail("duplicate rule label '" + r.label + "'" + first_at({other.line, 0}), where(label));
    expect_symbol(":", "':' after the rule label");
    expect_keyword("IF", "IF");
    r.condition = disjunction();
    expect_keyword("THEN", "THEN, AND or OR after the condition");
    do
      r.consequents.push_back(consequent());
    while (accept_symbol(","));
    const bool with = accept_keyword("WITH");
    if (with) {
      const Token weight = peek();
      r.weight = expect_number("a weight after WITH (a number in [0, 1])");
      if (!(r.weight >= 0 && r.weight <= 1))
        fail("WITH weight must be in [0, 1], got " + weight.text, where(weight));
    }
    expect_symbol(";", with ? "';' after the rule" : "',', WITH or ';' after the consequent");
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

  // Each '(' and NOT nests one level, here and again in inference and in the
  // writer, which all recurse: a hostile file could nest until the stack runs
  // out. No rule a person writes comes near this depth.
  static constexpr int kMaxConditionDepth = 32;

  Condition unary() {
    if (!at_keyword("NOT") && !at_symbol("(")) return clause();
    if (depth_ == kMaxConditionDepth)
      fail("the condition nests '(' and NOT more than " + std::to_string(kMaxConditionDepth) +
               " levels deep",
           where(peek()));
    ++depth_;
    Condition c = nested();
    --depth_;
    return c;
  }

  // A NOT or a '(' group, one level deeper.
  Condition nested() {
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
    while (at_keyword("VERY") || at_keyword("SOMEWHAT"))
      c.hedges.push_back(fcl::same_keyword(take().text, "VERY") ? Hedge::very : Hedge::somewhat);
    const Token term = expect_name("a term name");
    std::tie(c.variable, c.term) = lookup(variable, term, false);
    return c;
  }

  Consequent consequent() {
    const Token variable = expect_name("an output variable name");
    expect_keyword("IS", "IS after '" + variable.text + "'");
    Consequent c;
    const Token first = peek();
    c.negated = accept_keyword("NOT");
    while (at_keyword("VERY") || at_keyword("SOMEWHAT"))
      c.hedges.push_back(fcl::same_keyword(take().text, "VERY") ? Hedge::very : Hedge::somewhat);
    const Token term = expect_name("a term name");
    std::tie(c.variable, c.term) = lookup(variable, term, true);
    if ((c.negated || !c.hedges.empty()) &&
        system_.outputs[static_cast<std::size_t>(c.variable)].method ==
            Defuzzification::weighted_average)
      fail("NOT and hedges shape a Mamdani output set; '" + variable.text +
               "' is Takagi-Sugeno (METHOD : COGS), whose terms are values",
           where(first));
    return c;
  }

  // (variable, term) indices: an input for a condition, an output for a consequent.
  std::pair<int, int> lookup(const Token& variable, const Token& term, bool output) {
    const std::string& name = variable.text;
    const auto& own = output ? system_.outputs : system_.inputs;
    const int v = output ? system_.output_index(name) : system_.input_index(name);
    if (v < 0) {
      if ((output ? system_.input_index(name) : system_.output_index(name)) >= 0)
        fail(output ? "consequent on input '" + name + "': a consequent sets an output"
                    : "condition on output '" + name + "': a condition tests an input",
             where(variable));
      fail("unknown variable '" + name + "' (" + (output ? "outputs: " : "inputs: ") + names(own) +
               ")",
           where(variable));
    }
    const LinguisticVariable& var = own[static_cast<std::size_t>(v)];
    const int t = var.term_index(term.text);
    if (t < 0)
      fail("unknown term '" + term.text + "' of '" + name + "' (its terms: " + names(var.terms) +
               ")",
           where(term));
    return {v, t};
  }

  Part part_ = Part::declarations;
  int depth_ = 0;                                 // of the condition being read
  std::vector<Slot> input_slots_, output_slots_;  // parallel to system_.inputs / outputs
  FuzzySystem system_;
};

}  // namespace

FuzzySystem parse_fcl(const std::string& text, const std::string& path) {
  return Parser(text, path).parse();
}

FuzzySystem read_fcl(const std::string& path) {
  return parse_fcl(read_text_file(path, "FCL file", kMaxRuleBaseBytes), path);
}

}  // namespace neurocloth::fuzzy
