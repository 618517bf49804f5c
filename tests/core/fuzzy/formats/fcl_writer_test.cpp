// Writing FCL: the text is canonical, and reading it back gives the same
// system bit for bit (every shape, hedge, negation, tree, weight and default).
#include "core/fuzzy/formats/fcl_writer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/fuzzy/formats/fcl_reader.h"
#include "support/fuzzy_builders.h"

namespace neurocloth::fuzzy {
namespace {
using Kind = Condition::Kind;
using test::is;

const double kNaN = std::numeric_limits<double>::quiet_NaN();

std::uint64_t bits(double v) {
  std::uint64_t b;
  std::memcpy(&b, &v, sizeof b);
  return b;
}

// ---- Building systems in code ------------------------------------------------

Condition node(Kind kind, std::vector<Condition> children) {
  return test::combine(kind, std::move(children));
}
Condition all(std::vector<Condition> c) {
  return node(Kind::all, std::move(c));
}
Condition any(std::vector<Condition> c) {
  return node(Kind::any, std::move(c));
}
Condition no(Condition c) {
  return node(Kind::negation, {std::move(c)});
}

Rule labelled_rule(std::string label, Condition c, std::vector<Consequent> then,
                   double weight = 1.0) {
  Rule r;
  r.label = std::move(label);
  r.condition = std::move(c);
  r.consequents = std::move(then);
  r.weight = weight;
  return r;
}

// Input indices: mass 0, force 1. Terms of mass: light 0, medium 1, heavy 2,
// g 3, b 4, s 5, one 6; of force: tiny 0, small 1, big 2.
FuzzySystem rich_system() {
  FuzzySystem s;
  s.name = "cloth";
  s.inputs.push_back({"mass",
                      0.05,
                      2.0,
                      {{"light", {Shape::points, {0.05, 1, 0.3, 1, 0.6, 0}}},
                       {"medium", {Shape::triangle, {0.1 + 0.2, 0.6, 1.0 / 3.0 + 0.7}}},
                       {"heavy", {Shape::trapezoid, {0.6, 1.0, 2.0, 2.0}}},
                       {"g", {Shape::gaussian, {0.5, 0.1}}},
                       {"b", {Shape::bell, {-0.2, 2, 0.5}}},
                       {"s", {Shape::sigmoid, {10, 0.5}}},
                       {"one", {Shape::singleton, {0.5}}}}});
  // Extremes of the format: a subnormal, minus zero, tiny magnitudes, and the
  // largest the reader takes (beyond +-1e15 the engine's centroids overflow).
  s.inputs.push_back({"force",
                      -1.0 / 3.0,
                      1e15,
                      {{"tiny", {Shape::singleton, {4.9406564584124654e-324}}},
                       {"small", {Shape::gaussian, {-0.0, 1e-300}}},
                       {"big", {Shape::sigmoid, {-7.25, 9.8765432109876543e14}}}}});
  LinguisticVariable k{"spring_constant",
                       1,
                       1000,
                       {{"low", {Shape::triangle, {1, 50, 200}}},
                        {"high", {Shape::trapezoid, {100, 500, 1000, 1000}}}}};
  k.method = Defuzzification::centroid;
  k.default_value = 100.5;
  LinguisticVariable d{
      "damping",
      0,
      1,
      {{"zero", {Shape::singleton, {0}}}, {"lin", {Shape::linear, {0.5, 2.0, -1.0}}}}};
  d.method = Defuzzification::weighted_average;  // default_value stays NaN: not given
  LinguisticVariable f{"friction", -1, 1, {{"flat", {Shape::linear, {0.25, 0, 1e-5}}}}};
  f.method = Defuzzification::weighted_average;
  f.default_value = -0.0;
  s.outputs = {k, d, f};

  RuleBlock main;
  main.name = "main";
  main.and_method = AndMethod::product;
  main.or_method = OrMethod::probabilistic_sum;
  main.activation = Activation::product;
  main.accumulation = Accumulation::sum;
  main.rules = {
      labelled_rule("1", is(0, 2, {Hedge::very, Hedge::somewhat}, true), {{0, 0}}, 0.8),
      labelled_rule("2", all({any({is(0, 0), is(1, 1, {Hedge::somewhat}, true)}), no(is(0, 1))}),
                    {{0, 0}, {1, 1}}),
      labelled_rule("3", any({all({is(0, 0), is(1, 2)}), is(0, 2)}), {{0, 1}}, 0.1),
      labelled_rule("4", all({all({is(0, 3), is(0, 4)}), is(0, 5)}), {{1, 0}}, 0.0),
      labelled_rule("5", any({is(0, 6), any({is(1, 0), is(1, 2, {Hedge::very})})}), {{2, 0}},
                    1e-17),
      labelled_rule("six", no(no(is(1, 1))), {{0, 1}}),
      labelled_rule("007", no(all({is(0, 0), any({is(1, 0), is(1, 1)})})), {{2, 0}, {0, 0}}),
  };
  RuleBlock spare;  // empty: allowed
  spare.name = "spare";
  RuleBlock unnamed;
  unnamed.or_method = OrMethod::probabilistic_sum;
  unnamed.rules = {labelled_rule("1", is(1, 2), {{1, 0}})};
  s.blocks = {main, spare, unnamed};
  return s;
}

// ---- Structural comparison -----------------------------------------------------

std::string same_number(double a, double b, const std::string& what) {
  return bits(a) == bits(b)
             ? ""
             : what + ": " + std::to_string(a) + " vs " + std::to_string(b) + " (bits differ)";
}

std::string difference(const Condition& a, const Condition& b, const std::string& at) {
  if (a.kind != b.kind) return at + ": kind";
  if (a.variable != b.variable || a.term != b.term) return at + ": variable or term";
  if (a.hedges != b.hedges || a.negated != b.negated) return at + ": hedges or IS NOT";
  if (a.children.size() != b.children.size()) return at + ": child count";
  for (std::size_t i = 0; i < a.children.size(); ++i) {
    const std::string d = difference(a.children[i], b.children[i], at + "/" + std::to_string(i));
    if (!d.empty()) return d;
  }
  return "";
}

std::string difference(const LinguisticVariable& a, const LinguisticVariable& b, bool output) {
  const std::string at = "variable " + a.name;
  if (a.name != b.name) return at + ": name " + b.name;
  std::string d = same_number(a.min, b.min, at + " min") + same_number(a.max, b.max, at + " max");
  if (output) {
    if (a.method != b.method) d += at + ": method";
    const bool both_nan = std::isnan(a.default_value) && std::isnan(b.default_value);
    if (!both_nan) d += same_number(a.default_value, b.default_value, at + " default");
  }
  if (a.terms.size() != b.terms.size()) return d + at + ": term count";
  for (std::size_t i = 0; i < a.terms.size() && d.empty(); ++i) {
    const Term& x = a.terms[i];
    const Term& y = b.terms[i];
    if (x.name != y.name || x.function.shape != y.function.shape) return at + " term " + x.name;
    if (x.function.params.size() != y.function.params.size()) return at + " params of " + x.name;
    for (std::size_t p = 0; p < x.function.params.size(); ++p)
      d += same_number(x.function.params[p], y.function.params[p], at + " term " + x.name);
  }
  return d;
}

// Empty when a and b are the same system, bit for bit; otherwise the first difference.
std::string difference(const FuzzySystem& a, const FuzzySystem& b) {
  if (a.name != b.name) return "name";
  if (a.inputs.size() != b.inputs.size() || a.outputs.size() != b.outputs.size())
    return "variable count";
  for (std::size_t i = 0; i < a.inputs.size(); ++i)
    if (auto d = difference(a.inputs[i], b.inputs[i], false); !d.empty()) return d;
  for (std::size_t i = 0; i < a.outputs.size(); ++i)
    if (auto d = difference(a.outputs[i], b.outputs[i], true); !d.empty()) return d;
  if (a.blocks.size() != b.blocks.size()) return "block count";
  for (std::size_t k = 0; k < a.blocks.size(); ++k) {
    const RuleBlock& x = a.blocks[k];
    const RuleBlock& y = b.blocks[k];
    const std::string at = "block '" + x.name + "'";
    if (x.name != y.name || x.and_method != y.and_method || x.or_method != y.or_method ||
        x.activation != y.activation || x.accumulation != y.accumulation)
      return at + " settings";
    if (x.rules.size() != y.rules.size()) return at + " rule count";
    for (std::size_t r = 0; r < x.rules.size(); ++r) {
      const Rule& p = x.rules[r];
      const Rule& q = y.rules[r];
      const std::string rule_at = at + " RULE " + p.label;
      if (p.label != q.label) return rule_at + ": label " + q.label;
      if (auto d = same_number(p.weight, q.weight, rule_at + " weight"); !d.empty()) return d;
      if (p.consequents.size() != q.consequents.size()) return rule_at + ": consequents";
      for (std::size_t c = 0; c < p.consequents.size(); ++c)
        if (p.consequents[c].variable != q.consequents[c].variable ||
            p.consequents[c].term != q.consequents[c].term)
          return rule_at + ": consequent " + std::to_string(c);
      if (auto d = difference(p.condition, q.condition, rule_at); !d.empty()) return d;
    }
  }
  return "";
}

// ---- Tests ---------------------------------------------------------------------

TEST(FclWriter, RoundTripsEveryConstructBitExactly) {
  const FuzzySystem s = rich_system();
  const std::string text = write_fcl(s);
  const FuzzySystem back = parse_fcl(text, "written.fcl");
  EXPECT_EQ(difference(s, back), "") << text;
  EXPECT_TRUE(std::isnan(back.outputs[1].default_value));
  EXPECT_TRUE(std::signbit(back.outputs[2].default_value));
}

TEST(FclWriter, WritingWhatWasReadGivesTheSameText) {
  const std::string once = write_fcl(rich_system());
  const std::string twice = write_fcl(parse_fcl(once, "once.fcl"));
  EXPECT_EQ(once, twice);
}

// The comparison the round trip relies on must see each kind of change.
TEST(FclWriter, TheComparisonSeesEveryDifference) {
  const FuzzySystem s = rich_system();
  std::vector<FuzzySystem> changed(8, s);
  changed[0].inputs[0].terms[1].function.params[0] = std::nextafter(0.1 + 0.2, 1.0);
  changed[1].outputs[2].default_value = 0.0;  // was -0.0
  changed[2].blocks[0].rules[0].condition.hedges = {Hedge::somewhat, Hedge::very};
  changed[3].blocks[0].rules[0].condition.negated = false;
  changed[4].blocks[0].rules[3].condition = all({is(0, 3), is(0, 4), is(0, 5)});
  changed[5].blocks[0].rules[1].weight = std::nextafter(1.0, 0.0);
  changed[6].outputs[1].default_value = 0.0;  // was NaN
  changed[7].blocks[2].or_method = OrMethod::max;
  for (std::size_t i = 0; i < changed.size(); ++i)
    EXPECT_NE(difference(s, changed[i]), "") << "change " << i;
}

TEST(FclWriter, WritesCanonicalText) {
  FuzzySystem s;
  s.name = "tiny";
  s.inputs.push_back(
      {"x", 0, 1, {{"lo", {Shape::points, {0, 1, 1, 0}}}, {"hi", {Shape::gaussian, {1, 0.25}}}}});
  LinguisticVariable y{
      "y", -1, 1, {{"a", {Shape::singleton, {0.1}}}, {"b", {Shape::linear, {0, 2}}}}};
  y.method = Defuzzification::weighted_average;
  LinguisticVariable z{"z", 0, 10, {{"mid", {Shape::triangle, {0, 5, 10}}}}};
  z.default_value = 5;
  s.outputs = {y, z};
  RuleBlock b;
  b.name = "r";
  b.and_method = AndMethod::product;
  b.rules = {
      labelled_rule("1", all({is(0, 0, {Hedge::very}), no(is(0, 1))}), {{0, 0}, {1, 0}}, 0.5),
      labelled_rule("", is(0, 1, {}, true), {{0, 1}})};
  s.blocks = {b};
  EXPECT_EQ(write_fcl(s),
            "FUNCTION_BLOCK tiny\n"
            "\n"
            "VAR_INPUT\n"
            "  x : REAL;\n"
            "END_VAR\n"
            "\n"
            "VAR_OUTPUT\n"
            "  y : REAL;\n"
            "  z : REAL;\n"
            "END_VAR\n"
            "\n"
            "FUZZIFY x\n"
            "  RANGE := (0 .. 1);\n"
            "  TERM lo := (0, 1) (1, 0);\n"
            "  TERM hi := GAUSS 1 0.25;\n"
            "END_FUZZIFY\n"
            "\n"
            "DEFUZZIFY y\n"
            "  RANGE := (-1 .. 1);\n"
            "  TERM a := 0.10000000000000001;\n"
            "  TERM b := LINEAR 0 x 2;\n"
            "  METHOD : COGS;\n"
            "END_DEFUZZIFY\n"
            "\n"
            "DEFUZZIFY z\n"
            "  RANGE := (0 .. 10);\n"
            "  TERM mid := TRIAN 0 5 10;\n"
            "  METHOD : COG;\n"
            "  DEFAULT := 5;\n"
            "END_DEFUZZIFY\n"
            "\n"
            "RULEBLOCK r\n"
            "  AND : PROD;\n"
            "  OR : MAX;\n"
            "  ACT : MIN;\n"
            "  ACCU : MAX;\n"
            "  RULE 1 : IF x IS VERY lo AND NOT (x IS hi) THEN y IS a, z IS mid WITH 0.5;\n"
            "  RULE 2 : IF x IS NOT hi THEN y IS b;\n"
            "END_RULEBLOCK\n"
            "\n"
            "END_FUNCTION_BLOCK\n");
}

// Parentheses appear exactly where the reader needs them to rebuild the tree.
TEST(FclWriter, ParenthesesFollowTheTree) {
  const std::string text = write_fcl(rich_system());
  for (const char* expected : {
           "RULE 1 : IF mass IS NOT VERY SOMEWHAT heavy THEN spring_constant IS low WITH "
           "0.80000000000000004;",
           "RULE 2 : IF (mass IS light OR force IS NOT SOMEWHAT small) AND NOT (mass IS medium) "
           "THEN spring_constant IS low, damping IS lin;",
           "RULE 3 : IF mass IS light AND force IS big OR mass IS heavy THEN",
           "RULE 4 : IF (mass IS g AND mass IS b) AND mass IS s THEN damping IS zero WITH 0;",
           "RULE 5 : IF mass IS one OR (force IS tiny OR force IS VERY big) THEN",
           "RULE six : IF NOT (NOT (force IS small)) THEN",
           "RULE 007 : IF NOT (mass IS light AND (force IS tiny OR force IS small)) THEN",
       })
    EXPECT_NE(text.find(expected), std::string::npos) << expected << "\nnot in:\n" << text;
}

TEST(FclWriter, WritesEveryShapeAndNumberExactly) {
  const std::string text = write_fcl(rich_system());
  for (const char* expected : {
           "RANGE := (0.050000000000000003 .. 2);",
           "TERM light := (0.050000000000000003, 1) (0.29999999999999999, 1) (0.59999999999999998, "
           "0);",
           "TERM medium := TRIAN 0.30000000000000004 0.59999999999999998 1.0333333333333332;",
           "TERM heavy := TRAPE 0.59999999999999998 1 2 2;",
           "TERM b := GBELL -0.20000000000000001 2 0.5;",
           "TERM s := SIGM 10 0.5;",
           "TERM one := 0.5;",
           "RANGE := (-0.33333333333333331 .. 1000000000000000);",
           "TERM tiny := 4.9406564584124654e-324;",
           "TERM small := GAUSS -0 1e-300;",
           "TERM lin := LINEAR 0.5 mass 2 force -1;",
           "DEFAULT := 100.5;",
           "DEFAULT := -0;",
           "RULEBLOCK\n  AND : MIN;\n  OR : ASUM;",
           "RULEBLOCK main\n  AND : PROD;\n  OR : ASUM;\n  ACT : PROD;\n  ACCU : SUM;",
           "RULEBLOCK spare\n  AND : MIN;\n  OR : MAX;\n  ACT : MIN;\n  ACCU : MAX;\nEND_RULEBLOCK",
       })
    EXPECT_NE(text.find(expected), std::string::npos) << expected << "\nnot in:\n" << text;
  // damping's default is NaN ("not given"): no DEFAULT line in its block.
  const auto damping = text.find("DEFUZZIFY damping");
  EXPECT_EQ(text.find("DEFAULT", damping), text.find("DEFAULT := -0;"));
}

TEST(FclWriter, RefusesWhatCannotBeReadBack) {
  const FuzzySystem good = rich_system();
  ASSERT_NO_THROW(write_fcl(good));
  std::vector<std::pair<const char*, FuzzySystem>> bad(13, {"", good});
  bad[0] = {"keyword as name", good};
  bad[0].second.inputs[0].name = "Then";
  bad[1] = {"space in a term name", good};
  bad[1].second.inputs[0].terms[0].name = "very light";
  bad[2] = {"name starting with a digit", good};
  bad[2].second.outputs[0].name = "2k";
  bad[3] = {"rule label that is two tokens", good};
  bad[3].second.blocks[0].rules[0].label = "1 a";
  bad[4] = {"non-finite parameter", good};
  bad[4].second.inputs[0].terms[3].function.params[1] = std::numeric_limits<double>::infinity();
  bad[5] = {"infinite default", good};
  bad[5].second.outputs[0].default_value = -std::numeric_limits<double>::infinity();
  bad[6] = {"NaN weight", good};
  bad[6].second.blocks[0].rules[0].weight = kNaN;
  bad[7] = {"linear without one coefficient per input", good};
  bad[7].second.outputs[1].terms[1].function.params = {0.5, 2.0};
  bad[8] = {"AND of one child", good};
  bad[8].second.blocks[0].rules[0].condition = all({is(0, 0)});
  bad[9] = {"term index out of range", good};
  bad[9].second.blocks[0].rules[0].condition.term = 7;
  bad[10] = {"consequent on a missing output", good};
  bad[10].second.blocks[0].rules[0].consequents[0].variable = 3;
  bad[11] = {"rule without consequent", good};
  bad[11].second.blocks[0].rules[0].consequents.clear();
  bad[12] = {"invalid membership function", good};
  bad[12].second.inputs[0].terms[1].function.params = {1, 0, 0};
  for (const auto& [what, system] : bad)
    EXPECT_THROW(write_fcl(system), std::invalid_argument) << what;
}

TEST(FclWriter, UnlabelledRulesAreNumberedByPosition) {
  FuzzySystem s = rich_system();
  s.blocks[0].rules[1].label = "";
  const FuzzySystem back = parse_fcl(write_fcl(s), "numbered.fcl");
  EXPECT_EQ(back.blocks[0].rules[1].label, "2");
  EXPECT_EQ(back.blocks[0].rules[2].label, "3");
}

// A hand-written file, read and written, is the canonical form of itself.
TEST(FclWriter, CanonicalFormOfAHandWrittenFileIsStable) {
  const std::string hand =
      "function_block f (* c *) var_input a:real; end_var var_output b:real; end_var\n"
      "fuzzify a term x:=trian 0 1 2; term y:=(0,0)(2,1); end_fuzzify\n"
      "defuzzify b range:=(0..1); term u:=singleton 0.3; term v:=.7; method:cogs; "
      "default:=nc; end_defuzzify\n"
      "ruleblock rb and:min; or:asum; rule 1: if not (a is x or a is not y) and a is somewhat y "
      "then b is u with 0.25; end_ruleblock end_function_block\n";
  const FuzzySystem first = parse_fcl(hand, "hand.fcl");
  const std::string canonical = write_fcl(first);
  EXPECT_EQ(difference(first, parse_fcl(canonical, "canonical.fcl")), "") << canonical;
  EXPECT_EQ(write_fcl(parse_fcl(canonical, "canonical.fcl")), canonical);
  EXPECT_NE(canonical.find("RULE 1 : IF NOT (a IS x OR a IS NOT y) AND a IS SOMEWHAT y THEN b IS u "
                           "WITH 0.25;"),
            std::string::npos)
      << canonical;
}

}  // namespace
}  // namespace neurocloth::fuzzy
