#include "core/fuzzy/formats/fcl_reader.h"

#include <algorithm>
#include <limits>
#include <utility>

#include "core/fuzzy/formats/fcl_parser.h"
#include "core/io/input_error.h"
#include "core/io/text_file.h"

namespace neurocloth::fuzzy {
namespace fcl {

void Parser::function_block() {
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
  resolve_accumulation();
  field_ = outer_field_;

  if (peek().kind != TokenKind::end)
    fail("expected end of file after END_FUNCTION_BLOCK (one function block per file), got '" +
             peek().text + "'",
         where(peek()));
}

// Moves on to `next`; leaving the variable blocks, every declared variable
// must have had its block.
void Parser::enter(Part next, const Token& head) {
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

void Parser::declarations(bool input) {
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
    if (!input) output_notes_.emplace_back();
    (input ? input_slots_ : output_slots_).push_back({where(name), {}, false});
  }
  close();
}

void Parser::variable_block(bool output) {
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
    else if (output && at_keyword("ACCU"))
      output_accumulation(b);
    else if (output && at_keyword("LOCK"))
      lock(b);
    else if (at_keyword("ENABLED"))
      enabled();

    else
      unexpected(output ? "TERM, RANGE, METHOD, DEFAULT or END_DEFUZZIFY"
                        : "TERM, RANGE or END_FUZZIFY");
  }
  finish(b);
  close();
  const int i = output ? system_.output_index(name.text) : system_.input_index(name.text);
  if (output)
    output_notes_[static_cast<std::size_t>(i)] = {b.has_accu, b.accu,
                                                  b.has_accu ? b.accu_at : b.at};
  (output ? system_.outputs : system_.inputs)[static_cast<std::size_t>(i)] = std::move(b.variable);
}

Slot& Parser::declared_slot(const VariableBlock& b) {
  const std::string& name = b.variable.name;
  const int i = b.output ? system_.output_index(name) : system_.input_index(name);
  if (i >= 0) return (b.output ? output_slots_ : input_slots_)[static_cast<std::size_t>(i)];
  if ((b.output ? system_.input_index(name) : system_.output_index(name)) >= 0)
    fail("'" + name + "' is declared in " + (b.output ? "VAR_INPUT" : "VAR_OUTPUT") +
             ", so its block must be " + (b.output ? "FUZZIFY" : "DEFUZZIFY"),
         b.at);
  fail("unknown variable '" + name + "': declare it in " + (b.output ? "VAR_OUTPUT" : "VAR_INPUT"),
       b.at);
}

void Parser::range(VariableBlock& b) {
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
    fail(
        "RANGE needs min < max, got (" + show(b.variable.min) + " .. " + show(b.variable.max) + ")",
        where(head));
}

void Parser::term(VariableBlock& b) {
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
MembershipFunction Parser::membership(const VariableBlock& b) {
  if (peek().kind == TokenKind::number) return {Shape::singleton, {take().value}};
  if (at_symbol("(")) return points();
  MembershipFunction f{Shape::points, {}};
  for (Shape s : {Shape::triangle, Shape::trapezoid, Shape::gaussian, Shape::bell, Shape::sigmoid,
                  Shape::singleton, Shape::linear})
    if (at_keyword(to_string(s))) f.shape = s;
  // Not ours: another tool's class name (fcl_dialect.cpp), or an error.
  if (f.shape == Shape::points)
    return foreign_term(
        "a membership function (a number, '(x, y) ...', trian, trape, gauss, "
        "gbell, sigm, singleton or linear)");
  const Token head = take();
  if (f.shape == Shape::linear) return linear(b, head);
  const int n = parameter_count(f.shape);
  for (int i = 0; i < n; ++i)
    f.params.push_back(
        expect_number("a number (" + head.text + " takes " + std::to_string(n) + " parameters)"));
  return f;
}

MembershipFunction Parser::points() {
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
MembershipFunction Parser::linear(const VariableBlock& b, const Token& head) {
  if (!b.output)
    fail("linear terms are Takagi-Sugeno consequents, allowed only in DEFUZZIFY", where(head));
  MembershipFunction f{Shape::linear, std::vector<double>(1 + system_.inputs.size(), 0.0)};
  f.params[0] = expect_number("the constant c0 after linear");
  // fuzzylite's "Linear a1 .. an c": numbers only (fcl_dialect.cpp). Ours names
  // each input; a lone number is ours unless spelt as fuzzylite's class.
  if (peek().kind == TokenKind::number || (head.text == "Linear" && !at_name()))
    return foreign_linear(head, f.params[0]);
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

void Parser::method(VariableBlock& b) {
  const Token head = take();
  once(b.has_method, head);
  b.method_at = where(head);
  expect_symbol(":", "':' after METHOD");
  b.variable.method = defuzzifier();

  expect_symbol(";", "';' after METHOD");
}

void Parser::default_value(VariableBlock& b) {
  once(b.has_default, take());
  expect_symbol(":=", "':=' after DEFAULT");
  // fuzzylite writes "nan" for "none given" and "| NC" for "keep the previous
  // value", which a one-shot inference reads as its first evaluation does:
  // the DEFAULT (docs/fcl.md).
  b.variable.default_value = accept_keyword("NC") || accept_keyword("NAN")
                                 ? std::numeric_limits<double>::quiet_NaN()
                                 : expect_number("a number or NC after DEFAULT :=");
  if (accept_symbol("|")) expect_keyword("NC", "NC after '|'");

  expect_symbol(";", "';' after DEFAULT");
}

// Checks that need the whole block: RANGE (given or inferred), METHOD.
void Parser::finish(VariableBlock& b) {
  LinguisticVariable& v = b.variable;
  if (v.terms.empty()) fail("'" + v.name + "' has no TERM", b.at);
  if (!b.has_range) infer_range(b);
  for (std::size_t i = 0; i < v.terms.size(); ++i)
    for (double x : v.terms[i].function.axis_positions())
      if (x < v.min || x > v.max) {
        field_ = "TERM " + v.terms[i].name;
        fail("term out of range: x = " + show(x) + " lies outside the RANGE (" + show(v.min) +
                 " .. " + show(v.max) + ") of '" + v.name + "'",
             b.term_at[i]);
      }
  if (!b.output) return;
  check_method(b);
  const bool cogs = v.method == Defuzzification::weighted_average;
  if (b.accu_none && !cogs)
    fail("ACCU : NONE (fuzzylite: each rule's set on its own) has no centroid here; use MAX or SUM",
         b.accu_at);
  if (b.accu_none) b.accu = Accumulation::sum;  // a weighted average over every rule
  if (b.lock_range)
    for (const Term& t : v.terms)
      if (t.function.shape == Shape::linear)
        fail("LOCK : RANGE clamps the output, which a linear term can leave ('" + t.name +
                 "'); this engine does not clamp outputs",
             b.lock_at);
}

void Parser::infer_range(VariableBlock& b) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const Term& t : b.variable.terms)
    for (double x : t.function.axis_positions()) {
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
void Parser::check_method(const VariableBlock& b) {
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
}  // namespace fcl

FuzzySystem parse_fcl(const std::string& text, const std::string& path) {
  return fcl::Parser(text, path).parse();
}

FuzzySystem read_fcl(const std::string& path) {
  return parse_fcl(read_text_file(path, "FCL file", kMaxRuleBaseBytes), path);
}

}  // namespace neurocloth::fuzzy
