// The RULEBLOCK half of the FCL parser (fcl_parser.h): settings, rules and
// their condition trees.
#include <array>
#include <tuple>
#include <utility>

#include "core/fuzzy/formats/fcl_parser.h"

namespace neurocloth::fuzzy::fcl {

void Parser::rule_block() {
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
    else if (at_keyword("ENABLED"))
      enabled();
    else if (!setting(rb, given))
      unexpected("RULE, AND, OR, ACT, ACCU or END_RULEBLOCK");
  }
  check_pairing(rb, given);
  block_notes_.push_back({given[3], field_});
  close();
  system_.blocks.push_back(std::move(rb));
}

// AND : MIN; OR : MAX; ACT : MIN; ACCU : MAX; and their alternatives (also by
// fuzzylite's class names, fcl_dialect.cpp). False when the next token starts
// none of them.
bool Parser::setting(RuleBlock& rb, std::array<bool, 4>& given) {
  static const char* const kSetting[4] = {"AND", "OR", "ACT", "ACCU"};
  int which = -1;
  for (int i = 0; i < 4; ++i)
    if (at_keyword(kSetting[i])) which = i;
  if (which < 0) return false;
  const Token head = take();
  once(given[static_cast<std::size_t>(which)], head);
  setting_at_[static_cast<std::size_t>(which)] = where(head);
  const std::string name = head.text;
  expect_symbol(":", "':' after " + name);
  const bool alternative = norm(which) == 1;
  expect_symbol(";", "';' after the " + name + " method");
  if (which == 0) rb.and_method = alternative ? AndMethod::product : AndMethod::min;
  if (which == 1) rb.or_method = alternative ? OrMethod::probabilistic_sum : OrMethod::max;
  if (which == 2) rb.activation = alternative ? Activation::product : Activation::min;
  if (which == 3) rb.accumulation = alternative ? Accumulation::sum : Accumulation::max;
  return true;
}

Rule Parser::rule(const RuleBlock& rb) {
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
  // fuzzylite joins consequents with "and".
  do
    r.consequents.push_back(consequent());
  while (accept_symbol(",") || accept_keyword("AND"));
  const bool with = accept_keyword("WITH");
  if (with) {
    const Token weight = peek();
    r.weight = expect_number("a weight after WITH (a number in [0, 1])");
    if (!(r.weight >= 0 && r.weight <= 1))
      fail("WITH weight must be in [0, 1], got " + weight.text, where(weight));
  }
  // fuzzylite ends a rule with the line, without ';'.
  if (at_keyword("RULE") || at_keyword("END_RULEBLOCK"))
    unterminated_rules_ = true;
  else
    expect_symbol(";", with ? "';' after the rule" : "',', WITH or ';' after the consequent");
  field_ = block_field;
  return r;
}

Condition Parser::chain(Condition::Kind kind, const char* connective) {
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

Condition Parser::unary() {
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
Condition Parser::nested() {
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

Condition Parser::clause() {
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

Consequent Parser::consequent() {
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
std::pair<int, int> Parser::lookup(const Token& variable, const Token& term, bool output) {
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
  if (t < 0) {
    for (const char* hedge : {"any", "extremely", "seldom"})  // fuzzylite's other hedges
      if (same_keyword(term.text, hedge) && at_name())
        fail("hedge '" + term.text + "' is not supported: this engine has very and somewhat",
             where(term));
    fail("unknown term '" + term.text + "' of '" + name + "' (its terms: " + names(var.terms) + ")",
         where(term));
  }
  return {v, t};
}
}  // namespace neurocloth::fuzzy::fcl
