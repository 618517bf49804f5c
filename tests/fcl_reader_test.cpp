// Reading FCL: every construct of the dialect (docs/fcl.md), and every error
// with the file, field, line and column it must name.
#include "fuzzy/fcl_reader.h"

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

#include "input_error.h"
#include "scene.h"

namespace neurocloth::fuzzy {
namespace {
namespace fs = std::filesystem;
using Kind = Condition::Kind;

const std::string kPath = "base.fcl";

// One thing per line, so an edit knows the line and column its error must name.
const std::string kBase = R"(FUNCTION_BLOCK cloth
VAR_INPUT
  mass : REAL;
  force : REAL;
END_VAR
VAR_OUTPUT
  stiffness : REAL;
  damping : REAL;
END_VAR
FUZZIFY mass
  RANGE := (0 .. 2);
  TERM light := trian 0 0 1;
  TERM heavy := trape 0.5 1 2 2;
END_FUZZIFY
FUZZIFY force
  RANGE := (-10 .. 10);
  TERM small := gauss 0 2;
  TERM big := sigm 1 5;
END_FUZZIFY
DEFUZZIFY stiffness
  RANGE := (1 .. 1000);
  TERM low := trian 1 50 200;
  TERM high := trian 100 500 1000;
  METHOD : COG;
  DEFAULT := 100;
END_DEFUZZIFY
DEFUZZIFY damping
  RANGE := (0 .. 1);
  TERM none := 0;
  TERM lin := linear 0.1 force 0.01;
  METHOD : COGS;
END_DEFUZZIFY
RULEBLOCK rules
  AND : MIN;
  RULE 1 : IF mass IS heavy THEN stiffness IS high;
  RULE 2 : IF force IS NOT very small THEN damping IS lin WITH 0.5;
END_RULEBLOCK
END_FUNCTION_BLOCK
)";

using Edits = std::vector<std::pair<std::string, std::string>>;

std::string edited(const Edits& edits, std::string text = kBase) {
  for (const auto& [from, to] : edits) {
    const auto at = text.find(from);
    EXPECT_NE(at, std::string::npos) << "test bug: '" << from << "' is not in the text";
    if (at != std::string::npos) text.replace(at, from.size(), to);
  }
  return text;
}

// 1-based line and column of the only occurrence of `needle`.
std::pair<int, int> position_of(const std::string& text, const std::string& needle) {
  const auto at = text.find(needle);
  EXPECT_NE(at, std::string::npos) << "test bug: '" << needle << "' is not in the text";
  EXPECT_EQ(text.find(needle, at + 1), std::string::npos)
      << "test bug: '" << needle << "' is not unique";
  if (at == std::string::npos) return {0, 0};
  const auto line_start = text.rfind('\n', at);
  const int line = 1 + static_cast<int>(std::count(text.begin(), text.begin() + at, '\n'));
  const auto column = line_start == std::string::npos ? at + 1 : at - line_start;
  return {line, static_cast<int>(column)};
}

std::optional<InputError> parse_error(const std::string& text) {
  try {
    parse_fcl(text, kPath);
  } catch (const InputError& e) {
    return e;
  } catch (const std::exception& e) {
    ADD_FAILURE() << "expected InputError, got: " << e.what();
    return std::nullopt;
  }
  ADD_FAILURE() << "expected InputError, the text was accepted:\n" << text;
  return std::nullopt;
}

// The error is at the start of `at` in `text`, names `field`, and says `message`.
void expect_error(const std::string& text, const std::string& field, const std::string& at,
                  const std::string& message) {
  const auto e = parse_error(text);
  if (!e) return;
  const auto [line, column] = position_of(text, at);
  EXPECT_EQ(e->file(), kPath);
  EXPECT_EQ(e->field(), field) << e->what();
  EXPECT_EQ(e->line(), line) << e->what();
  EXPECT_EQ(e->column(), column) << e->what();
  EXPECT_NE(e->message().find(message), std::string::npos) << e->what();
  const std::string where = kPath + ":" + std::to_string(line) + ":" + std::to_string(column);
  EXPECT_EQ(std::string(e->what()).rfind(where, 0), 0u) << e->what();
}

// kBase from the first `begin` through the next `end`, inclusive.
std::string section(const std::string& begin, const std::string& end) {
  const auto from = kBase.find(begin);
  const auto to = kBase.find(end, from);
  return kBase.substr(from, to + end.size() - from);
}

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
  const fs::path dir = fs::path(NEUROCLOTH_TEST_TMP) / "fcl_reader_test";
  fs::create_directories(dir);
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

// ---- Errors ----------------------------------------------------------------

struct ErrorCase {
  const char* name;
  Edits edits;          // applied to kBase
  const char* field;    // InputError::field()
  const char* at;       // the error's line and column: where this (unique) text starts
  const char* message;  // a part of InputError::message()
};

void PrintTo(const ErrorCase& c, std::ostream* os) {
  *os << c.name;
}

class FclReaderError : public ::testing::TestWithParam<ErrorCase> {};

TEST_P(FclReaderError, NamesFieldLineColumnAndProblem) {
  const ErrorCase& c = GetParam();
  expect_error(edited(c.edits), c.field, c.at, c.message);
}

// clang-format off
const ErrorCase kErrors[] = {
    // Sections out of the IEC order.
    {"VarAfterFuzzify",
     {{"END_VAR\nVAR_OUTPUT", "END_VAR\n(*"}, {"damping : REAL;\nEND_VAR\n", "*)"},
      {"FUZZIFY force", "VAR_OUTPUT stiffness : REAL; damping : REAL; END_VAR\nFUZZIFY force"}},
     "FUNCTION_BLOCK cloth", "VAR_OUTPUT stiffness",
     "VAR_OUTPUT must come before the FUZZIFY and DEFUZZIFY blocks"},
    {"FuzzifyAfterRuleBlock", {{"END_RULEBLOCK\n", "END_RULEBLOCK\nFUZZIFY extra\n"}},
     "FUNCTION_BLOCK cloth", "FUZZIFY extra", "FUZZIFY must come before the RULEBLOCKs"},
    {"VarAfterRuleBlock", {{"END_RULEBLOCK\n", "END_RULEBLOCK\nVAR_INPUT\n"}},
     "FUNCTION_BLOCK cloth", "VAR_INPUT\nEND_F", "VAR_INPUT must come before the RULEBLOCKs"},
    // Unknown, misplaced or missing variables.
    {"UnknownVariableInFuzzify", {{"FUZZIFY force", "FUZZIFY forse"}},
     "FUZZIFY forse", "forse", "unknown variable 'forse'"},
    {"UnknownVariableInDefuzzify", {{"DEFUZZIFY damping", "DEFUZZIFY dumping"}},
     "DEFUZZIFY dumping", "dumping", "unknown variable 'dumping'"},
    {"FuzzifyOnAnOutput",
     {{"  force : REAL;\n", ""}, {"damping : REAL;", "damping : REAL; force : REAL;"}},
     "FUZZIFY force", "force\n  RANGE", "declared in VAR_OUTPUT, so its block must be DEFUZZIFY"},
    {"DefuzzifyOnAnInput",
     {{"  damping : REAL;\n", ""}, {"force : REAL;", "force : REAL; damping : REAL;"}},
     "DEFUZZIFY damping", "damping\n  RANGE",
     "declared in VAR_INPUT, so its block must be FUZZIFY"},
    {"DeclaredVariableWithoutBlock", {{"DEFUZZIFY damping", "(*"}, {"COGS;\nEND_DEFUZZIFY", "*)"}},
     "VAR_OUTPUT", "damping : REAL", "output 'damping' has no DEFUZZIFY block"},
    {"UnknownVariableInCondition", {{"IF mass IS heavy", "IF mess IS heavy"}},
     "RULE 1", "mess", "unknown variable 'mess' (inputs: mass, force)"},
    {"UnknownVariableInConsequent", {{"THEN stiffness IS high", "THEN stifness IS high"}},
     "RULE 1", "stifness", "unknown variable 'stifness' (outputs: stiffness, damping)"},
    {"UnknownTermInCondition", {{"mass IS heavy", "mass IS huge"}},
     "RULE 1", "huge", "unknown term 'huge' of 'mass' (its terms: light, heavy)"},
    {"UnknownTermInConsequent", {{"damping IS lin", "damping IS linn"}},
     "RULE 2", "linn", "unknown term 'linn' of 'damping'"},
    {"ConditionOnAnOutput", {{"IF mass IS heavy", "IF stiffness IS low"}},
     "RULE 1", "stiffness IS low", "condition on output 'stiffness'"},
    {"ConsequentOnAnInput", {{"THEN stiffness IS high", "THEN mass IS light"}},
     "RULE 1", "mass IS light", "consequent on input 'mass'"},
    // Terms outside RANGE, shape by shape.
    {"PointOutOfRange", {{"trian 0 0 1;", "(0, 1) (2.5, 0);"}},
     "TERM light", "light :=",
     "term out of range: x = 2.5 lies outside the RANGE (0 .. 2) of 'mass'"},
    {"TrianOutOfRange", {{"trian 0 0 1;", "trian 0 0 3;"}},
     "TERM light", "light :=", "term out of range: x = 3"},
    {"TrapeOutOfRange", {{"trape 0.5 1 2 2", "trape -1 1 2 2"}},
     "TERM heavy", "heavy :=", "term out of range: x = -1"},
    {"SingletonOutOfRange", {{"TERM none := 0;", "TERM none := 1.5;"}},
     "TERM none", "none :=", "term out of range: x = 1.5"},
    {"SingletonKeywordOutOfRange", {{"TERM none := 0;", "TERM none := singleton -2;"}},
     "TERM none", "none :=", "term out of range: x = -2"},
    {"GaussMeanOutOfRange", {{"gauss 0 2", "gauss -11 2"}},
     "TERM small", "small :=", "term out of range: x = -11"},
    {"GbellCentreOutOfRange", {{"sigm 1 5", "gbell 20 2 11"}},
     "TERM big", "big :=", "term out of range: x = 11"},
    {"SigmCentreOutOfRange", {{"sigm 1 5", "sigm 1 10.5"}},
     "TERM big", "big :=", "term out of range: x = 10.5"},
    {"RangeAfterTheTerms",
     {{"  RANGE := (0 .. 2);\n", ""}, {"END_FUZZIFY", "RANGE := (0 .. 1.5); END_FUZZIFY"}},
     "TERM heavy", "heavy :=", "term out of range: x = 2"},
    // MembershipFunction::validate().
    {"TrianOrder", {{"trian 0 0 1", "trian 1 0 0"}},
     "TERM light", "light :=", "trian needs a <= b <= c"},
    {"TrapeOrder", {{"trape 0.5 1 2 2", "trape 0.5 1 0.8 2"}},
     "TERM heavy", "heavy :=", "trape needs a <= b <= c <= d"},
    {"GaussSigma", {{"gauss 0 2", "gauss 0 0"}},
     "TERM small", "small :=", "gauss needs sigma > 0"},
    {"GbellWidth", {{"sigm 1 5", "gbell 0 2 5"}},
     "TERM big", "big :=", "gbell needs a != 0"},
    {"PointDegree", {{"trian 0 0 1", "(0, 1.5) (1, 0)"}},
     "TERM light", "light :=", "membership degrees must be in [0, 1]"},
    {"PointOrder", {{"trian 0 0 1", "(1, 1) (0, 0)"}},
     "TERM light", "light :=", "point x values must not decrease"},
    // Missing pieces.
    {"VariableWithoutTerms", {{"  TERM small := gauss 0 2;\n  TERM big := sigm 1 5;\n", ""}},
     "FUZZIFY force", "force\n  RANGE", "'force' has no TERM"},
    {"RangeCannotBeInferred", {{"  RANGE := (0 .. 1);\n", ""}},
     "DEFUZZIFY damping", "damping\n  TERM", "no RANGE given"},
    {"NoRules", {{"  RULE 1 :", "(*"}, {"WITH 0.5;", "*)"}},
     "FUNCTION_BLOCK cloth", "FUNCTION_BLOCK cloth", "no rules"},
    {"NoRuleBlock", {{"RULEBLOCK rules\n", "(*"}, {"END_RULEBLOCK\n", "*)"}},
     "FUNCTION_BLOCK cloth", "FUNCTION_BLOCK cloth", "no rules"},
    {"NoMethod", {{"  METHOD : COG;\n", ""}},
     "DEFUZZIFY stiffness", "stiffness\n  RANGE", "no METHOD given"},
    // Bad numbers.
    {"WordForNumber", {{"trian 0 0 1", "trian 0.2 x 1"}},
     "TERM light", "x 1", "expected a number (trian takes 3 parameters), got 'x'"},
    {"TwoDecimalPoints", {{"trian 0 0 1", "trian 0 1.2.3 1"}},
     "TERM light", "1.2.3", "bad number '1.2.3'"},
    {"ExponentWithoutDigits", {{"(0 .. 2)", "(0 .. 2e)"}},
     "FUZZIFY mass", "2e)", "bad number '2e'"},
    {"NumberWithUnit", {{"DEFAULT := 100", "DEFAULT := 100kg"}},
     "DEFUZZIFY stiffness", "100kg", "bad number '100kg'"},
    {"NumberOverflows", {{"WITH 0.5", "WITH 1e999"}},
     "RULE 2", "1e999", "bad number '1e999': not representable"},
    {"TooFewParameters", {{"trian 0 0 1;", "trian 0 1;"}},
     "TERM light", ";\n  TERM heavy", "expected a number (trian takes 3 parameters), got ';'"},
    // Duplicates.
    {"DuplicateInput", {{"  force : REAL;\n", "  force : REAL;\n  mass : REAL;\n"}},
     "VAR_INPUT", "mass : REAL;\nEND", "duplicate variable 'mass' (the first is at line 3)"},
    {"InputAndOutputShareAName", {{"  stiffness : REAL;", "  force : REAL;\n  stiffness : REAL;"}},
     "VAR_OUTPUT", "force : REAL;\n  stiffness", "duplicate variable 'force'"},
    {"DuplicateTerm", {{"TERM heavy :=", "TERM light :="}},
     "TERM light", "light := trape", "duplicate term 'light' in FUZZIFY mass"},
    {"DuplicateBlock", {{"RULEBLOCK", "FUZZIFY mass\n  TERM x := 1;\nEND_FUZZIFY\nRULEBLOCK"}},
     "FUZZIFY mass", "mass\n  TERM x",
     "duplicate block for variable 'mass' (the first is at line 10)"},
    {"DuplicateRuleLabel", {{"RULE 2", "RULE 1"}},
     "RULE 1", "1 : IF force", "duplicate rule label '1' (the first is at line 35)"},
    {"DuplicateRuleBlock", {{"END_RULEBLOCK\n", "END_RULEBLOCK\nRULEBLOCK rules\nEND_RULEBLOCK\n"}},
     "RULEBLOCK rules", "rules\nEND_RULEBLOCK\nEND_F", "duplicate RULEBLOCK name 'rules'"},
    {"RangeTwice", {{"  TERM small", "  RANGE := (-1 .. 1);\n  TERM small"}},
     "FUZZIFY force", "RANGE := (-1 ..", "RANGE given twice"},
    {"MethodTwice", {{"METHOD : COGS;", "METHOD : COGS; METHOD : COGS;"}},
     "DEFUZZIFY damping", "METHOD : COGS;\n", "METHOD given twice"},
    {"DefaultTwice", {{"DEFAULT := 100;", "DEFAULT := 100; DEFAULT := NC;"}},
     "DEFUZZIFY stiffness", "DEFAULT := NC", "DEFAULT given twice"},
    {"SettingTwice", {{"AND : MIN;", "AND : MIN;\n  AND : PROD;"}},
     "RULEBLOCK rules", "AND : PROD", "AND given twice"},
    // Values out of their domain.
    {"RangeEmpty", {{"(0 .. 2)", "(2 .. 2)"}},
     "FUZZIFY mass", "RANGE := (2", "RANGE needs min < max, got (2 .. 2)"},
    {"RangeReversed", {{"(-10 .. 10)", "(10 .. -10)"}},
     "FUZZIFY force", "RANGE := (10", "RANGE needs min < max"},
    {"WeightAboveOne", {{"WITH 0.5", "WITH 1.5"}},
     "RULE 2", "1.5;", "WITH weight must be in [0, 1], got 1.5"},
    {"WeightNegative", {{"WITH 0.5", "WITH -0.1"}},
     "RULE 2", "-0.1", "WITH weight must be in [0, 1], got -0.1"},
    {"DefaultNotANumber", {{"DEFAULT := 100", "DEFAULT := high"}},
     "DEFUZZIFY stiffness", "high;\nEND", "expected a number or NC after DEFAULT :=, got 'high'"},
    // METHOD against the terms.
    {"CogWithSingleton", {{"METHOD : COGS", "METHOD : COG"}},
     "DEFUZZIFY damping", "METHOD : COG;\nEND",
     "METHOD COG needs membership functions, but term 'none' (line 29) is singleton; use COGS"},
    {"CogWithLinear", {{"  TERM none := 0;\n", ""}, {"METHOD : COGS", "METHOD : COG"}},
     "DEFUZZIFY damping", "METHOD : COG;\nEND", "term 'lin' (line 29) is linear"},
    {"CogsWithTriangle", {{"METHOD : COG;", "METHOD : COGS;"}},
     "DEFUZZIFY stiffness", "METHOD : COGS;\n  DEFAULT",
     "METHOD COGS needs every term to be singleton or linear, but term 'low' (line 22) is trian"},
    {"UnsupportedMethod", {{"METHOD : COGS", "METHOD : COA"}},
     "DEFUZZIFY damping", "COA",
     "expected COG or COGS (the supported defuzzification methods), got 'COA'"},
    // Linear terms.
    {"LinearUnknownInput", {{"force 0.01", "forse 0.01"}},
     "TERM lin", "forse", "linear term names 'forse', which is not an input (inputs: mass, force)"},
    {"LinearNamesAnOutput", {{"force 0.01", "stiffness 0.01"}},
     "TERM lin", "stiffness 0.01", "which is not an input"},
    {"LinearInputTwice", {{"force 0.01", "force 0.01 force 2"}},
     "TERM lin", "force 2", "input 'force' appears twice"},
    {"LinearInFuzzify", {{"sigm 1 5", "linear 1 mass 5"}},
     "TERM big", "linear 1", "allowed only in DEFUZZIFY"},
    // Unexpected tokens.
    {"MissingSemicolonAfterTerm", {{"trian 0 0 1;", "trian 0 0 1"}},
     "TERM light", "TERM heavy", "expected ';' after TERM definition, got 'TERM'"},
    {"MissingThen", {{"heavy THEN stiffness", "heavy stiffness"}},
     "RULE 1", "stiffness IS high",
     "expected THEN, AND or OR after the condition, got 'stiffness'"},
    {"MissingIs", {{"IF mass IS heavy", "IF mass heavy"}},
     "RULE 1", "heavy THEN", "expected IS after 'mass', got 'heavy'"},
    {"HedgeInConsequent", {{"damping IS lin", "damping IS very lin"}},
     "RULE 2", "very lin", "NOT and hedges shape a Mamdani output set; 'damping' is Takagi-Sugeno (METHOD : COGS), whose terms are values"},
    {"HedgeBeforeNot", {{"IS NOT very small", "IS very NOT small"}},
     "RULE 2", "NOT small", "expected a term name, got 'NOT'"},
    {"UnclosedParenthesis", {{"IF force IS", "IF (force IS"}},
     "RULE 2", "THEN damping", "expected ')' to close '(', or AND / OR, got 'THEN'"},
    {"KeywordAsName", {{"  force : REAL;", "  Then : REAL;"}},
     "VAR_INPUT", "Then", "expected a variable name or END_VAR, got 'Then'"},
    {"TypeNotReal", {{"mass : REAL", "mass : INT"}},
     "VAR_INPUT", "INT", "expected REAL (the only variable type), got 'INT'"},
    {"MethodInFuzzify", {{"  RANGE := (0 .. 2);", "  METHOD : COG;"}},
     "FUZZIFY mass", "METHOD : COG;\n  TERM light",
     "expected TERM, RANGE or END_FUZZIFY, got 'METHOD'"},
    {"EndFuzzifyMissingBeforeNextBlock", {{"END_FUZZIFY\nFUZZIFY force", "FUZZIFY force"}},
     "FUZZIFY mass", "FUZZIFY force", "expected TERM, RANGE or END_FUZZIFY, got 'FUZZIFY'"},
    {"WrongSettingValue", {{"AND : MIN", "AND : MAX"}},
     "RULEBLOCK rules", "MAX", "expected MIN or PROD after AND :, got 'MAX'"},
    {"UnknownStatementInRuleBlock", {{"AND : MIN;", "METHOD : COG;"}},
     "RULEBLOCK rules", "METHOD : COG;\n  RULE",
     "expected RULE, AND, OR, ACT, ACCU or END_RULEBLOCK, got 'METHOD'"},
    {"TextAfterTheFunctionBlock", {{"END_FUNCTION_BLOCK\n", "END_FUNCTION_BLOCK FUNCTION_BLOCK x"}},
     "FUNCTION_BLOCK cloth", "FUNCTION_BLOCK x", "expected end of file after END_FUNCTION_BLOCK"},
    {"NothingBeforeTheFunctionBlock", {{"FUNCTION_BLOCK cloth", "junk FUNCTION_BLOCK cloth"}},
     "FUNCTION_BLOCK", "junk", "expected FUNCTION_BLOCK, got 'junk'"},
    {"UnclosedComment", {{"END_FUNCTION_BLOCK\n", "END_FUNCTION_BLOCK\n(* never closed"}},
     "FUNCTION_BLOCK cloth", "(*", "comment '(*' is never closed by '*)'"},
    {"StrayCharacter", {{"AND : MIN;", "AND : MIN; #"}},
     "RULEBLOCK rules", "#", "unexpected character '#'"},
};
// clang-format on

INSTANTIATE_TEST_SUITE_P(Fcl, FclReaderError, ::testing::ValuesIn(kErrors),
                         [](const ::testing::TestParamInfo<ErrorCase>& info) {
                           return std::string(info.param.name);
                         });

// At the end of the file the error names the block left open, where it began.
TEST(FclReader, MissingEndAtEndOfFileNamesTheOpenBlock) {
  const struct {
    const char* cut_at;  // the text is kBase up to (not including) this
    const char* field;
    const char* block;  // where the open block begins
    const char* message;
  } cases[] = {
      {"END_VAR\nVAR_OUTPUT", "VAR_INPUT", "VAR_INPUT", "missing END_VAR"},
      {"END_FUZZIFY\nFUZZIFY force", "FUZZIFY mass", "FUZZIFY mass", "missing END_FUZZIFY"},
      {"END_DEFUZZIFY\nDEFUZZIFY damping", "DEFUZZIFY stiffness", "DEFUZZIFY stiffness",
       "missing END_DEFUZZIFY"},
      {"END_RULEBLOCK", "RULEBLOCK rules", "RULEBLOCK", "missing END_RULEBLOCK"},
      {"THEN stiffness", "RULEBLOCK rules", "RULEBLOCK", "missing END_RULEBLOCK"},
      {"END_FUNCTION_BLOCK", "FUNCTION_BLOCK cloth", "FUNCTION_BLOCK",
       "missing END_FUNCTION_BLOCK"},
      {"TERM big := sigm", "FUZZIFY force", "FUZZIFY force", "missing END_FUZZIFY"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.cut_at);
    const std::string text = kBase.substr(0, kBase.find(c.cut_at));
    expect_error(text, c.field, c.block, c.message);
  }
  expect_error("", "FUNCTION_BLOCK", "", "expected FUNCTION_BLOCK, got end of file");
}

}  // namespace
}  // namespace neurocloth::fuzzy
