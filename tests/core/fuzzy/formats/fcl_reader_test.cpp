// Reading FCL: every construct of the dialect (docs/fcl.md). What is refused,
// and how the error names it: fcl_reader_error_test.cpp.
#include "core/fuzzy/formats/fcl_reader.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "core/io/input_error.h"
#include "core/scene/scene.h"
#include "support/fcl_test_text.h"
#include "support/scratch_dir.h"

namespace neurocloth::fuzzy {
namespace {
namespace fs = std::filesystem;
using Kind = Condition::Kind;
using namespace fcl_test;

bool is_clause(const Condition& c, int variable, int term) {
  return c.kind == Kind::term && c.variable == variable && c.term == term;
}

TEST(FclReader, ReadsTheBaseSystem) {
  const FuzzySystem s = parse_fcl(kBase, kPath);
  EXPECT_EQ(s.name, "cloth");
  ASSERT_EQ(s.inputs.size(), 2u);
  ASSERT_EQ(s.outputs.size(), 2u);
  EXPECT_EQ(s.inputs[1].name, "force");
  EXPECT_EQ(s.inputs[1].min, -10.0);
  EXPECT_EQ(s.inputs[1].max, 10.0);
  const LinguisticVariable& mass = s.inputs[0];
  ASSERT_EQ(mass.terms.size(), 2u);
  EXPECT_EQ(mass.terms[1].name, "heavy");
  EXPECT_EQ(mass.terms[1].function.shape, Shape::trapezoid);
  EXPECT_EQ(mass.terms[1].function.params, (std::vector<double>{0.5, 1, 2, 2}));
  EXPECT_EQ(s.inputs[1].terms[1].function.shape, Shape::sigmoid);
  const LinguisticVariable& stiffness = s.outputs[0];
  EXPECT_EQ(stiffness.method, Defuzzification::centroid);
  EXPECT_EQ(stiffness.default_value, 100.0);
  const LinguisticVariable& damping = s.outputs[1];
  EXPECT_EQ(damping.method, Defuzzification::weighted_average);
  EXPECT_TRUE(std::isnan(damping.default_value));
  EXPECT_EQ(damping.terms[0].function.shape, Shape::singleton);
  EXPECT_EQ(damping.terms[0].function.params, (std::vector<double>{0}));
  // c0, then one coefficient per input in VAR_INPUT order; mass is not named.
  EXPECT_EQ(damping.terms[1].function.shape, Shape::linear);
  EXPECT_EQ(damping.terms[1].function.params, (std::vector<double>{0.1, 0, 0.01}));

  ASSERT_EQ(s.blocks.size(), 1u);
  const RuleBlock& b = s.blocks[0];
  EXPECT_EQ(b.name, "rules");
  ASSERT_EQ(b.rules.size(), 2u);
  EXPECT_TRUE(is_clause(b.rules[0].condition, 0, 1));
  EXPECT_EQ(b.rules[0].weight, 1.0);
  EXPECT_EQ(b.rules[0].label, "1");
  EXPECT_EQ(b.rules[0].line, 35);
  ASSERT_EQ(b.rules[0].consequents.size(), 1u);
  EXPECT_EQ(b.rules[0].consequents[0].variable, 0);
  EXPECT_EQ(b.rules[0].consequents[0].term, 1);
  const Rule& r2 = b.rules[1];
  EXPECT_TRUE(is_clause(r2.condition, 1, 0));
  EXPECT_TRUE(r2.condition.negated);
  EXPECT_EQ(r2.condition.hedges, (std::vector<Hedge>{Hedge::very}));
  EXPECT_EQ(r2.weight, 0.5);
  EXPECT_EQ(r2.consequents[0].variable, 1);
  EXPECT_EQ(r2.consequents[0].term, 1);
}

TEST(FclReader, ReadsEveryShapeAndTheRuleBlockSettings) {
  const std::string text = edited({
      {"TERM light := trian 0 0 1;",
       "TERM light := (0, 1) (0.3, 1) (0.6, 0);\n  TERM g := gauss 0.5 0.1;\n"
       "  TERM b := gbell 0.2 2 0.5;\n  TERM one := 0.5;\n  TERM two := singleton 1.5;"},
      {"DEFAULT := 100;", "DEFAULT := NC;"},
      {"linear 0.1 force 0.01", "linear -2.5e-1 force 3 mass +.5"},
      {"AND : MIN;", "and : prod;\n  Or : Asum;\n  ACT : PROD;\n  ACCU : SUM;"},
  });
  const FuzzySystem s = parse_fcl(text, kPath);
  const auto& terms = s.inputs[0].terms;
  ASSERT_EQ(terms.size(), 6u);
  EXPECT_EQ(terms[0].function.shape, Shape::points);
  EXPECT_EQ(terms[0].function.params, (std::vector<double>{0, 1, 0.3, 1, 0.6, 0}));
  EXPECT_EQ(terms[1].function.shape, Shape::gaussian);
  EXPECT_EQ(terms[1].function.params, (std::vector<double>{0.5, 0.1}));
  EXPECT_EQ(terms[2].function.shape, Shape::bell);
  EXPECT_EQ(terms[2].function.params, (std::vector<double>{0.2, 2, 0.5}));
  EXPECT_EQ(terms[3].function.shape, Shape::singleton);
  EXPECT_EQ(terms[3].function.params, (std::vector<double>{0.5}));
  EXPECT_EQ(terms[4].function.shape, Shape::singleton);
  EXPECT_EQ(terms[4].function.params, (std::vector<double>{1.5}));
  EXPECT_TRUE(std::isnan(s.outputs[0].default_value));
  EXPECT_EQ(s.outputs[1].terms[1].function.params, (std::vector<double>{-0.25, 0.5, 3}));
  const RuleBlock& b = s.blocks[0];
  EXPECT_EQ(b.and_method, AndMethod::product);
  EXPECT_EQ(b.or_method, OrMethod::probabilistic_sum);
  EXPECT_EQ(b.activation, Activation::product);
  EXPECT_EQ(b.accumulation, Accumulation::sum);
  const FuzzySystem defaults = parse_fcl(kBase, kPath);
  EXPECT_EQ(defaults.blocks[0].or_method, OrMethod::max);
  EXPECT_EQ(defaults.blocks[0].activation, Activation::min);
  EXPECT_EQ(defaults.blocks[0].accumulation, Accumulation::max);
}

TEST(FclReader, BuildsTheConditionTreeAsWritten) {
  const auto condition = [](const std::string& rule) {
    const std::string text = edited({{"IF mass IS heavy THEN", "IF " + rule + " THEN"}});
    return parse_fcl(text, kPath).blocks[0].rules[0].condition;
  };
  // AND binds tighter than OR.
  Condition c = condition("mass IS light OR force IS big AND mass IS heavy");
  ASSERT_EQ(c.kind, Kind::any);
  ASSERT_EQ(c.children.size(), 2u);
  EXPECT_TRUE(is_clause(c.children[0], 0, 0));
  ASSERT_EQ(c.children[1].kind, Kind::all);
  EXPECT_TRUE(is_clause(c.children[1].children[1], 0, 1));
  // A chain is one node; a parenthesised group stays a node of its own.
  c = condition("mass IS light AND force IS big AND mass IS heavy");
  EXPECT_EQ(c.kind, Kind::all);
  EXPECT_EQ(c.children.size(), 3u);
  c = condition("(mass IS light AND force IS big) AND mass IS heavy");
  ASSERT_EQ(c.children.size(), 2u);
  EXPECT_EQ(c.children[0].kind, Kind::all);
  // The example of the brief: NOT on a group, hedges in source order.
  c = condition("(mass IS light OR force IS NOT somewhat very small) AND NOT (mass IS heavy)");
  ASSERT_EQ(c.kind, Kind::all);
  ASSERT_EQ(c.children[0].kind, Kind::any);
  const Condition& hedged = c.children[0].children[1];
  EXPECT_TRUE(is_clause(hedged, 1, 0));
  EXPECT_TRUE(hedged.negated);
  EXPECT_EQ(hedged.hedges, (std::vector<Hedge>{Hedge::somewhat, Hedge::very}));
  ASSERT_EQ(c.children[1].kind, Kind::negation);
  ASSERT_EQ(c.children[1].children.size(), 1u);
  EXPECT_TRUE(is_clause(c.children[1].children[0], 0, 1));
  EXPECT_FALSE(c.children[1].children[0].negated);
  // NOT on a single clause, and parentheses around one clause add no node.
  c = condition("NOT mass IS heavy");
  ASSERT_EQ(c.kind, Kind::negation);
  EXPECT_TRUE(is_clause(c.children[0], 0, 1));
  c = condition("((mass IS heavy))");
  EXPECT_TRUE(is_clause(c, 0, 1));
}

// '(' and NOT nest up to 32 levels (deeper is refused: fcl_reader_error_test.cpp).
TEST(FclReader, ReadsAConditionNestedToTheLimit) {
  std::string rule = "mass IS heavy";
  for (int level = 0; level < 32; ++level)
    rule = level % 2 ? "NOT " + rule : "(" + rule + ")";
  const Condition c = parse_fcl(edited({{"IF mass IS heavy THEN", "IF " + rule + " THEN"}}), kPath)
                          .blocks[0]
                          .rules[0]
                          .condition;
  int depth = 0;
  const Condition* at = &c;
  for (; at->kind == Kind::negation; at = &at->children[0])
    ++depth;
  EXPECT_EQ(depth, 16);  // the 16 parentheses around single clauses add no node
  EXPECT_TRUE(is_clause(*at, 0, 1));
}

TEST(FclReader, RulesWithSeveralConsequentsAndBlocks) {
  const std::string text = edited({
      {"THEN stiffness IS high;", "THEN stiffness IS high, damping IS none WITH 1;"},
      {"END_RULEBLOCK\n",
       "END_RULEBLOCK\nRULEBLOCK empty\nEND_RULEBLOCK\nRULEBLOCK\n"
       "  RULE r_x : IF mass IS light THEN damping IS none WITH 0;\nEND_RULEBLOCK\n"},
  });
  const FuzzySystem s = parse_fcl(text, kPath);
  ASSERT_EQ(s.blocks.size(), 3u);
  const Rule& r = s.blocks[0].rules[0];
  ASSERT_EQ(r.consequents.size(), 2u);
  EXPECT_EQ(r.consequents[1].variable, 1);
  EXPECT_EQ(r.consequents[1].term, 0);
  EXPECT_EQ(r.weight, 1.0);
  EXPECT_EQ(s.blocks[1].name, "empty");
  EXPECT_TRUE(s.blocks[1].rules.empty());
  EXPECT_EQ(s.blocks[2].name, "");
  EXPECT_EQ(s.blocks[2].rules[0].label, "r_x");
  EXPECT_EQ(s.blocks[2].rules[0].weight, 0.0);
}

TEST(FclReader, VariableBlocksMayComeInAnyOrder) {
  // Outputs declared first, DEFUZZIFY before FUZZIFY, force's block before
  // mass's: variables keep their declaration order, linear coefficients follow it.
  const std::string text =
      "FUNCTION_BLOCK cloth\n" + section("VAR_OUTPUT", "END_VAR\n") +
      section("VAR_INPUT", "END_VAR\n") + section("DEFUZZIFY damping", "END_DEFUZZIFY\n") +
      section("DEFUZZIFY stiffness", "END_DEFUZZIFY\n") +
      section("FUZZIFY force", "END_FUZZIFY\n") + section("FUZZIFY mass", "END_FUZZIFY\n") +
      section("RULEBLOCK", "END_FUNCTION_BLOCK\n");
  const FuzzySystem s =
      parse_fcl(edited({{"linear 0.1 force 0.01", "linear 0.1 force 0.01 mass 7"}}, text), kPath);
  EXPECT_EQ(s.inputs[0].name, "mass");
  EXPECT_EQ(s.inputs[0].terms[1].name, "heavy");
  EXPECT_EQ(s.inputs[1].name, "force");
  EXPECT_EQ(s.outputs[0].name, "stiffness");
  EXPECT_EQ(s.outputs[0].default_value, 100.0);
  EXPECT_EQ(s.outputs[1].terms[1].function.params, (std::vector<double>{0.1, 7, 0.01}));
  EXPECT_TRUE(is_clause(s.blocks[0].rules[0].condition, 0, 1));
}

TEST(FclReader, InfersRangeFromTheTermsWhenAbsent) {
  const std::string text = edited({{"  RANGE := (0 .. 2);\n", ""},
                                   {"  RANGE := (-10 .. 10);\n", ""},
                                   {"gauss 0 2", "gauss -3 2"},
                                   {"TERM big := sigm 1 5;", "TERM big := gbell 1 2 4;"}});
  const FuzzySystem s = parse_fcl(text, kPath);
  EXPECT_EQ(s.inputs[0].min, 0.0);  // trian 0 0 1, trape 0.5 1 2 2
  EXPECT_EQ(s.inputs[0].max, 2.0);
  EXPECT_EQ(s.inputs[1].min, -3.0);  // gauss mean, gbell centre
  EXPECT_EQ(s.inputs[1].max, 4.0);
}

TEST(FclReader, ReadsAHandWrittenFileWithCommentsOddSpacingAndCase) {
  const std::string text =
      "\xEF\xBB\xBF(* a rule base\r\n   written by hand *)\r\n"
      "function_block   Cloth // trailing comment\r\n"
      "Var_Input Mass:real; mass : REAL ; end_var\r\n"
      "VAR_OUTPUT\tk:REAL;END_VAR\r\n"
      "fuzzify Mass range:=(0..2);term Big:=TRIAN 0 1 2;END_FUZZIFY\r\n"
      "FUZZIFY mass\r\n  TERM big := (0,0)(2,1); (*)*) END_FUZZIFY\r\n"
      "Defuzzify k\r\n  Term Lo := Trian 0 .5 1 ; Method:Cog; "
      "Default:=-1.5e+0;\r\nend_defuzzify\r\n"
      "RuleBlock R // no settings: the defaults\r\n"
      "(* comment\r\n over lines *) Rule 7:if Mass is Big and(mass is not Very SOMEWHAT big)"
      "then k is Lo with .25;\r\n"
      "End_RuleBlock end_function_block // done\r\n";
  const FuzzySystem s = parse_fcl(text, kPath);
  EXPECT_EQ(s.name, "Cloth");
  ASSERT_EQ(s.inputs.size(), 2u);
  EXPECT_EQ(s.inputs[0].name, "Mass");
  EXPECT_EQ(s.inputs[1].name, "mass");
  EXPECT_EQ(s.inputs[0].terms[0].function.params, (std::vector<double>{0, 1, 2}));
  EXPECT_EQ(s.inputs[1].terms[0].function.shape, Shape::points);
  EXPECT_EQ(s.inputs[1].min, 0.0);
  EXPECT_EQ(s.inputs[1].max, 2.0);
  EXPECT_EQ(s.outputs[0].terms[0].function.params, (std::vector<double>{0, 0.5, 1}));
  EXPECT_EQ(s.outputs[0].default_value, -1.5);
  const Rule& r = s.blocks.at(0).rules.at(0);
  EXPECT_EQ(r.label, "7");
  EXPECT_EQ(r.line, 14);
  EXPECT_EQ(r.weight, 0.25);
  ASSERT_EQ(r.condition.kind, Kind::all);
  EXPECT_TRUE(is_clause(r.condition.children[0], 0, 0));
  const Condition& second = r.condition.children[1];
  EXPECT_TRUE(is_clause(second, 1, 0));
  EXPECT_TRUE(second.negated);
  EXPECT_EQ(second.hedges, (std::vector<Hedge>{Hedge::very, Hedge::somewhat}));
}

TEST(FclReader, NumbersReadExactly) {
  const std::string text = edited({{"trape 0.5 1 2 2", "trape 0.1 1e-0 1.999999999999999 2."}});
  const FuzzySystem s = parse_fcl(text, kPath);
  EXPECT_EQ(s.inputs[0].terms[1].function.params,
            (std::vector<double>{0.1, 1, 1.999999999999999, 2}));
}

// The example in docs/fcl.md reads, so the documentation cannot drift from the code.
TEST(FclReader, ReadsTheExampleInTheDocumentation) {
  const std::string path = assets_directory() + "/../docs/fcl.md";
  std::ifstream in(path);
  ASSERT_TRUE(in) << path;
  std::stringstream doc;
  doc << in.rdbuf();
  const std::string md = doc.str();
  const auto begin = md.find("```fcl\n");
  ASSERT_NE(begin, std::string::npos);
  const auto end = md.find("```", begin + 7);
  const FuzzySystem s = parse_fcl(md.substr(begin + 7, end - begin - 7), path);
  EXPECT_EQ(s.name, "cloth");
  ASSERT_EQ(s.inputs.size(), 2u);
  ASSERT_EQ(s.outputs.size(), 2u);
  EXPECT_EQ(s.inputs[0].terms.size(), 7u);
  EXPECT_EQ(s.blocks.at(0).rules.size(), 2u);
}

TEST(FclReader, ReadsAFileAndNamesItInErrors) {
  const fs::path dir = neurocloth::test::scratch_dir();
  const std::string good = (dir / "good.fcl").string();
  std::ofstream(good, std::ios::binary) << kBase;
  EXPECT_EQ(read_fcl(good).outputs[1].name, "damping");
  const std::string bad = (dir / "bad.fcl").string();
  std::ofstream(bad, std::ios::binary) << edited({{"mass IS heavy", "mass IS huge"}});
  try {
    read_fcl(bad);
    ADD_FAILURE() << "bad.fcl was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), bad);
    EXPECT_EQ(e.line(), 35);
  }
  const std::string missing = (dir / "missing.fcl").string();
  for (const std::string& path : {missing, dir.string()}) {
    try {
      read_fcl(path);
      ADD_FAILURE() << path << " was accepted";
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), path);
      EXPECT_EQ(e.line(), 0);
      EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace neurocloth::fuzzy
