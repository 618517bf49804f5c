// What fuzzylite (its FclExporter) and jFuzzyLogic write that IEC 61131-7 does
// not: their class and method names, ACCU inside DEFUZZIFY, ENABLED, LOCK and
// the like (docs/fcl.md, "Rule files from other tools"). A name that maps onto
// this engine is read as ours; one that does not is refused by name, so a file
// never loads with a meaning its author did not give it.
#include <string>

#include "core/fuzzy/formats/fcl_parser.h"

namespace neurocloth::fuzzy::fcl {
namespace {

struct Alias {
  const char* name;
  int value;  // the setting's first (0) or second (1) method
};

// Norms and defuzzifiers other tools offer and this engine does not have, by
// the names fuzzylite, jFuzzyLogic and IEC 61131-7 write.
struct Foreign {
  const char* name;
  const char* meaning;
};

const Foreign kForeignNorms[] = {
    {"BDIF", "bounded difference"},
    {"BDIFF", "bounded difference"},
    {"BoundedDifference", "bounded difference"},
    {"DPROD", "drastic product"},
    {"DMIN", "drastic product"},
    {"DrasticProduct", "drastic product"},
    {"EPROD", "Einstein product"},
    {"EinsteinProduct", "Einstein product"},
    {"HPROD", "Hamacher product"},
    {"HAMACHER", "Hamacher product"},
    {"HamacherProduct", "Hamacher product"},
    {"NMIN", "nilpotent minimum"},
    {"NIPMIN", "nilpotent minimum"},
    {"NilpotentMinimum", "nilpotent minimum"},
    {"BSUM", "bounded sum"},
    {"BoundedSum", "bounded sum"},
    {"NSUM", "normalised sum"},
    {"NormalizedSum", "normalised sum"},
    {"DSUM", "drastic sum"},
    {"DMAX", "drastic sum"},
    {"DrasticSum", "drastic sum"},
    {"ESUM", "Einstein sum"},
    {"EINSTEIN", "Einstein sum"},
    {"EinsteinSum", "Einstein sum"},
    {"HSUM", "Hamacher sum"},
    {"HamacherSum", "Hamacher sum"},
    {"NMAX", "nilpotent maximum"},
    {"NIPMAX", "nilpotent maximum"},
    {"NilpotentMaximum", "nilpotent maximum"},
    {"PROBOR", "probabilistic OR"},
    {"NONE", "no method"},
};

const Foreign kForeignDefuzzifiers[] = {
    {"COA", "centre of area"},
    {"BOA", "bisector of area"},
    {"BIS", "bisector of area"},
    {"Bisector", "bisector of area"},
    {"LM", "leftmost maximum"},
    {"SOM", "smallest of maximum"},
    {"SmallestOfMaximum", "smallest of maximum"},
    {"RM", "rightmost maximum"},
    {"LOM", "largest of maximum"},
    {"LargestOfMaximum", "largest of maximum"},
    {"MM", "mean of maximum"},
    {"MOM", "mean of maximum"},
    {"MeanOfMaximum", "mean of maximum"},
    {"COGSS", "weighted sum"},
    {"WeightedSum", "weighted sum"},
    {"COGF", "centre of gravity of functions"},
    {"NONE", "no defuzzifier"},
};

// Membership functions of fuzzylite and jFuzzyLogic with no shape here.
const char* const kForeignShapes[] = {
    "Rectangle",      "Cosine",     "Concave", "SShape",   "ZShape",
    "PiShape",        "Spike",      "Binary",  "Function", "SigmoidDifference",
    "SigmoidProduct", "SINGLETONS", "DSIGM",   "GAUSS2",   "FREEFORM",
    "Activated",      "Aggregated"};

const char* meaning(const Foreign* first, const Foreign* last, const std::string& word) {
  for (const Foreign* f = first; f != last; ++f)
    if (same_keyword(word, f->name)) return f->meaning;
  return nullptr;
}

}  // namespace

int Parser::norm(int which, bool none_allowed) {
  static const char* const kKey[4] = {"AND", "OR", "ACT", "ACCU"};
  static const Alias kAliases[4][4] = {
      {{"MIN", 0}, {"Minimum", 0}, {"PROD", 1}, {"AlgebraicProduct", 1}},
      {{"MAX", 0}, {"Maximum", 0}, {"ASUM", 1}, {"AlgebraicSum", 1}},
      {{"MIN", 0}, {"Minimum", 0}, {"PROD", 1}, {"AlgebraicProduct", 1}},
      {{"MAX", 0}, {"Maximum", 0}, {"SUM", 1}, {"UnboundedSum", 1}}};
  const std::string key = kKey[which];
  const std::string ours = which == 1 ? "MAX or ASUM" : which == 3 ? "MAX or SUM" : "MIN or PROD";
  if (peek().kind == TokenKind::word) {
    const Token name = peek();
    for (const Alias& a : kAliases[which])
      if (same_keyword(name.text, a.name)) {
        take();
        return a.value;
      }
    if (none_allowed && same_keyword(name.text, "NONE")) {
      take();
      return -1;
    }
    if (const char* m = meaning(std::begin(kForeignNorms), std::end(kForeignNorms), name.text))
      fail(key + " : " + name.text + " (" + m + ") is not supported: this engine's " + key +
               " is " + ours,
           where(name));
  }
  unexpected(ours + " after " + key + " :");
}

Defuzzification Parser::defuzzifier() {
  const Token name = peek();
  if (name.kind == TokenKind::word) {
    const bool cog = same_keyword(name.text, "COG") || same_keyword(name.text, "Centroid");
    const bool cogs = same_keyword(name.text, "COGS") || same_keyword(name.text, "WeightedAverage");
    if (cog || cogs) {
      take();
      return cogs ? Defuzzification::weighted_average : Defuzzification::centroid;
    }
    const char* m =
        meaning(std::begin(kForeignDefuzzifiers), std::end(kForeignDefuzzifiers), name.text);
    if (m)
      fail("METHOD : " + name.text + " (" + m +
               ") is not supported: this engine defuzzifies by COG (centre of gravity) or COGS "
               "(weighted average)",
           where(name));
  }
  unexpected("COG or COGS (the supported defuzzification methods)");
}

// fuzzylite's term classes, parameters in its order; a trailing height other
// than 1 is refused (every term here peaks at 1).
MembershipFunction Parser::foreign_term(const std::string& expected) {
  struct Class {
    const char* name;
    Shape shape;
    int count;
    int order[4];  // our parameter i is fuzzylite's parameter order[i]
  };
  static const Class kClasses[] = {
      {"Triangle", Shape::triangle, 3, {0, 1, 2, 0}},
      {"Trapezoid", Shape::trapezoid, 4, {0, 1, 2, 3}},
      {"Gaussian", Shape::gaussian, 2, {0, 1, 0, 0}},   // mean deviation
      {"Bell", Shape::bell, 3, {1, 2, 0, 0}},           // center width slope -> width slope center
      {"Sigmoid", Shape::sigmoid, 2, {1, 0, 0, 0}},     // inflection slope -> slope inflection
      {"Constant", Shape::singleton, 1, {0, 0, 0, 0}},  // no height
  };
  const Token head = peek();
  if (head.kind != TokenKind::word) unexpected(expected);
  for (const char* s : kForeignShapes)
    if (same_keyword(head.text, s))
      fail("membership function '" + head.text +
               "' has no equivalent in this engine (it has triangles, trapezoids, Gaussians, "
               "bells, sigmoids, point lists, singletons and linear consequents)",
           where(head));
  if (same_keyword(head.text, "Discrete")) return discrete(take());
  if (same_keyword(head.text, "Ramp")) return ramp(take());
  for (const Class& c : kClasses) {
    if (!same_keyword(head.text, c.name)) continue;
    take();
    std::vector<double> given;
    for (int i = 0; i < c.count; ++i)
      given.push_back(expect_number("a number (" + head.text + " takes " + std::to_string(c.count) +
                                    " parameters)"));
    MembershipFunction f{c.shape, given};
    for (int i = 0; i < c.count; ++i)
      f.params[static_cast<std::size_t>(i)] = given[static_cast<std::size_t>(c.order[i])];
    if (c.shape != Shape::singleton) height(head);
    return f;
  }
  unexpected(expected);
}

void Parser::height(const Token& head) {
  if (peek().kind != TokenKind::number) return;
  const Token h = take();
  if (h.value != 1.0)
    fail(head.text + " with height " + h.text +
             ": scaled terms are not supported (every term here peaks at 1)",
         where(h));
}

// fuzzylite: one coefficient per input in VAR_INPUT order, then the constant
// (optional; 0 when left out).
MembershipFunction Parser::foreign_linear(const Token& head, double first) {
  const std::size_t n = system_.inputs.size();
  std::vector<double> given{first};
  while (peek().kind == TokenKind::number && given.size() <= n)
    given.push_back(take().value);
  if (given.size() < n)
    fail("Linear takes one coefficient per input (" + std::to_string(n) +
             ") and an optional constant last, got " + std::to_string(given.size()),
         where(head));
  MembershipFunction f{Shape::linear, std::vector<double>(1 + n, 0.0)};
  for (std::size_t i = 0; i < n; ++i)
    f.params[1 + i] = given[i];
  if (given.size() > n) f.params[0] = given[n];
  return f;
}

// fuzzylite "Discrete x0 y0 x1 y1 ...": linear between the points, as ours.
MembershipFunction Parser::discrete(const Token& head) {
  MembershipFunction f{Shape::points, {}};
  while (peek().kind == TokenKind::number)
    f.params.push_back(take().value);
  if (f.params.size() < 2 || f.params.size() % 2)
    fail("Discrete needs x y pairs, got " + std::to_string(f.params.size()) + " numbers",
         where(head));
  return f;
}

// fuzzylite "Ramp start end": 0 at start rising (or falling) to 1 at end.
MembershipFunction Parser::ramp(const Token& head) {
  const double start = expect_number("the Ramp start (a number)");
  const double end = expect_number("the Ramp end (a number)");
  height(head);
  if (start == end) fail("Ramp needs start != end", where(head));
  return fuzzy::ramp(start, end);
}

// ENABLED : TRUE; (fuzzylite). A disabled variable or rule block would change
// what the file computes, so it is refused rather than dropped.
void Parser::enabled() {
  take();
  expect_symbol(":", "':' after ENABLED");
  if (accept_keyword("TRUE")) {
    expect_symbol(";", "';' after ENABLED : TRUE");
    return;
  }
  if (at_keyword("FALSE"))
    fail(
        "ENABLED : FALSE (fuzzylite's switch for a variable or rule block) is not supported: "
        "remove what is disabled, or enable it",
        where(peek()));
  unexpected("TRUE or FALSE after ENABLED :");
}

// LOCK : PREVIOUS, RANGE; (fuzzylite). PREVIOUS is its "| NC"; RANGE clamps the
// output to its range, which only a linear consequent can leave.
void Parser::lock(VariableBlock& b) {
  const Token head = take();
  b.lock_at = where(head);
  expect_symbol(":", "':' after LOCK");
  do {
    if (accept_keyword("PREVIOUS")) continue;
    if (!accept_keyword("RANGE")) unexpected("PREVIOUS or RANGE after LOCK :");
    b.lock_range = true;
  } while (accept_symbol(","));
  expect_symbol(";", "';' after LOCK");
}

// ACCU inside DEFUZZIFY (fuzzylite): per output, where this engine accumulates
// per rule block; resolve_accumulation() reconciles the two.
void Parser::output_accumulation(VariableBlock& b) {
  const Token head = take();
  once(b.has_accu, head);
  b.accu_at = where(head);
  expect_symbol(":", "':' after ACCU");
  const int v = norm(3, true);
  b.accu_none = v < 0;
  b.accu = v == 1 ? Accumulation::sum : Accumulation::max;
  expect_symbol(";", "';' after the ACCU method");
}

namespace {

const char* accu_name(Accumulation a) {
  return a == Accumulation::sum ? "SUM" : "MAX";
}

bool uses(const Condition& c, Condition::Kind kind) {
  if (c.kind == kind) return true;
  for (const Condition& child : c.children)
    if (uses(child, kind)) return true;
  return false;
}

}  // namespace

// IEC 61131-7 pairs AND and OR (MIN with MAX, PROD with ASUM) and jFuzzyLogic
// sets one from the other; this reader's default for the one not given is MIN
// or MAX. When only PROD or ASUM is given and the rules use the other
// connective, the two readings differ: the file must say which it means.
void Parser::check_pairing(const RuleBlock& rb, const std::array<bool, 4>& given) {
  const bool and_alone = given[0] && !given[1] && rb.and_method == AndMethod::product;
  const bool or_alone = given[1] && !given[0] && rb.or_method == OrMethod::probabilistic_sum;
  for (const Rule& r : rb.rules) {
    if (and_alone && uses(r.condition, Condition::Kind::any))
      fail("AND : PROD without OR, and RULE " + r.label +
               " uses OR: jFuzzyLogic and IEC 61131-7 pair PROD with OR : ASUM, this reader "
               "defaults to OR : MAX; say which with OR : ASUM; or OR : MAX;",
           setting_at_[0]);
    if (or_alone && uses(r.condition, Condition::Kind::all))
      fail("OR : ASUM without AND, and RULE " + r.label +
               " uses AND: jFuzzyLogic and IEC 61131-7 pair ASUM with AND : PROD, this reader "
               "defaults to AND : MIN; say which with AND : PROD; or AND : MIN;",
           setting_at_[1]);
  }
}

// Each rule block takes the accumulation its outputs' DEFUZZIFY blocks ask
// for (fuzzylite), which must agree with one another and with the block's own
// ACCU. A fuzzylite file (rules without ';') leaves ACCU out of a COGS output
// when every rule counts on its own: SUM here.
void Parser::resolve_accumulation() {
  for (std::size_t bi = 0; bi < system_.blocks.size(); ++bi) {
    RuleBlock& rb = system_.blocks[bi];
    const BlockNote& note = block_notes_[bi];
    int decided = -1;  // the output whose ACCU set the block's
    for (const Rule& r : rb.rules)
      for (const Consequent& c : r.consequents) {
        const OutputNote& on = output_notes_[static_cast<std::size_t>(c.variable)];
        const bool cogs = system_.outputs[static_cast<std::size_t>(c.variable)].method ==
                          Defuzzification::weighted_average;
        const bool implied = !on.has_accu && cogs && unterminated_rules_;
        if (!on.has_accu && !implied) continue;
        const Accumulation a = implied ? Accumulation::sum : on.accu;
        const std::string said = implied ? "no ACCU (fuzzylite: every rule counts, SUM here)"
                                         : std::string("ACCU : ") + accu_name(a);
        field_ = "DEFUZZIFY " + system_.outputs[static_cast<std::size_t>(c.variable)].name;
        if (note.has_accu) {
          if (a != rb.accumulation)
            fail(said + " disagrees with ACCU : " + accu_name(rb.accumulation) + " of " +
                     note.field +
                     ", whose rules set this output (this engine accumulates per "
                     "RULEBLOCK)",
                 on.at);
          continue;
        }
        if (decided < 0) {
          decided = c.variable;
          rb.accumulation = a;
        } else if (a != rb.accumulation) {
          fail(said + ", but '" + system_.outputs[static_cast<std::size_t>(decided)].name +
                   "' accumulates by " + accu_name(rb.accumulation) + " and both are set in " +
                   note.field +
                   " (this engine accumulates per RULEBLOCK): move one output's rules into a "
                   "RULEBLOCK of their own",
               on.at);
        }
      }
  }
}

}  // namespace neurocloth::fuzzy::fcl
