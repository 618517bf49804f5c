// Reading MATLAB / Octave .fis files: what each field becomes, and every way a
// file can be wrong, named by file, line and field. Whole files against their
// FCL text: rule_file_test.cpp.
#include "core/fuzzy/formats/fis_reader.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "core/io/input_error.h"
#include "support/line_of.h"
#include "support/rule_file_data.h"

namespace neurocloth::fuzzy {
namespace {
namespace fs = std::filesystem;
using Kind = Condition::Kind;

using neurocloth::test::line_of;

TEST(FisReader, ReadsMatlabFieldsIntoTheSystem) {
  const FuzzySystem s = parse_fis(neurocloth::test::rule_file_text("matlab_drape.fis"), "m.fis");
  EXPECT_EQ(s.name, "drape");
  ASSERT_EQ(s.inputs.size(), 2u);
  EXPECT_EQ(s.inputs[1].name, "stretch");
  EXPECT_EQ(s.inputs[1].max, 10.0);
  // gaussmf [sigma c] is our gauss (mean, sigma).
  EXPECT_EQ(s.inputs[0].terms[2].function.shape, Shape::gaussian);
  EXPECT_EQ(s.inputs[0].terms[2].function.params, (std::vector<double>{1, 0.15}));
  EXPECT_EQ(s.outputs[0].method, Defuzzification::centroid);
  ASSERT_EQ(s.blocks.size(), 1u);
  const auto& rules = s.blocks[0].rules;
  ASSERT_EQ(rules.size(), 4u);
  EXPECT_EQ(rules[1].condition.kind, Kind::term);  // "2 0": input 2 does not matter
  EXPECT_EQ(rules[2].weight, 0.5);
  EXPECT_TRUE(rules[2].condition.children[1].negated);  // -2
  EXPECT_EQ(rules[3].condition.kind, Kind::any);        // connection 2
  EXPECT_TRUE(rules[3].consequents[0].negated);         // -1 on the output
}

TEST(FisReader, ReadsOctaveHedgesCommentsAndCrLf) {
  const FuzzySystem s = parse_fis(neurocloth::test::rule_file_text("octave_damping.fis"), "o.fis");
  EXPECT_EQ(s.outputs[0].method, Defuzzification::weighted_average);
  EXPECT_EQ(s.blocks[0].and_method, AndMethod::product);  // 'algebraic_product'
  EXPECT_EQ(s.blocks[0].accumulation, Accumulation::sum);
  const auto& rules = s.blocks[0].rules;
  EXPECT_EQ(rules[1].condition.hedges, (std::vector<Hedge>{Hedge::very}));                  // 2.20
  EXPECT_EQ(rules[2].condition.children[1].hedges, (std::vector<Hedge>{Hedge::somewhat}));  // 2.05
  // linear [a1 a2 c] is ours [c a1 a2].
  EXPECT_EQ(s.outputs[0].terms[2].function.params, (std::vector<double>{0.1, 0.3, 0.02}));
}

// fuzzylite's FisExporter: a Discrete term as 'discretemf' with its x y pairs
// in one list, read as the point list the FCL reader makes of "(x, y) ...".
TEST(FisReader, ReadsFuzzylitesDiscretemfAsAPointList) {
  const FuzzySystem s =
      parse_fis(neurocloth::test::rule_file_text("matlab_defaults.fuzzylite.fis"), "d.fis");
  const MembershipFunction& mf1 = s.inputs[0].terms[0].function;
  EXPECT_EQ(mf1.shape, Shape::points);
  EXPECT_EQ(mf1.params, (std::vector<double>{0, 1, 0.4, 0}));
  EXPECT_EQ(s.outputs[0].terms[2].function.shape, Shape::points);
  EXPECT_EQ(s.outputs[0].terms[2].function.params, (std::vector<double>{0.6, 0, 1, 1}));
  // Equal x is a step, as in FCL.
  std::string text = neurocloth::test::rule_file_text("matlab_drape.fis");
  const std::string from = "'trimf',[0.2 0.5 0.8]";
  text.replace(text.find(from), from.size(), "'discretemf',[0.2 0 0.5 0 0.5 1 0.8 1]");
  const MembershipFunction step = parse_fis(text, "s.fis").inputs[0].terms[1].function;
  EXPECT_EQ(step.params, (std::vector<double>{0.2, 0, 0.5, 0, 0.5, 1, 0.8, 1}));
  EXPECT_EQ(step(0.49), 0.0);
  EXPECT_EQ(step(0.51), 1.0);
}

// fuzzylite's Ramp ('rampmf',[start end]), read as the FCL reader reads Ramp.
TEST(FisReader, ReadsFuzzylitesRampmf) {
  std::string text = neurocloth::test::rule_file_text("matlab_drape.fis");
  const std::string from = "'trimf',[0.2 0.5 0.8]";
  text.replace(text.find(from), from.size(), "'rampmf',[0.6 0.1]");
  const MembershipFunction falling = parse_fis(text, "r.fis").inputs[0].terms[1].function;
  EXPECT_EQ(falling.shape, Shape::points);
  EXPECT_EQ(falling.params, (std::vector<double>{0.1, 1, 0.6, 0}));
}

// fuzzylite's Type='hybrid': each output is what its MFs are, its
// DefuzzMethod the first output's.
TEST(FisReader, ReadsFuzzylitesHybridOutputsByTheirMfs) {
  const FuzzySystem s = parse_fis(neurocloth::test::rule_file_text("cloth.fuzzylite.fis"), "c.fis");
  ASSERT_EQ(s.outputs.size(), 5u);
  for (const LinguisticVariable& v : s.outputs)
    EXPECT_EQ(v.method,
              v.name == "node_mass" ? Defuzzification::weighted_average : Defuzzification::centroid)
        << v.name;
  // MATLAB's order [a1 a2 a3 c] is ours [c a1 a2 a3].
  EXPECT_EQ(s.outputs[1].terms[0].function.params, (std::vector<double>{0, 0.0025, 0, 0}));
  // '# RuleBlock' lines are comments; the three blocks' rules are one block.
  ASSERT_EQ(s.blocks.size(), 1u);
  EXPECT_EQ(s.blocks[0].rules.size(), 22u);
  EXPECT_EQ(s.blocks[0].rules[1].consequents[0].hedges, (std::vector<Hedge>{Hedge::very}));
}

struct BadFis {
  const char* name;
  std::vector<std::pair<std::string, std::string>> edits;  // replace first with second
  const char* field;
  const char* at;  // text on the line the error must name ("" for none)
  const char* message;
};

class FisReaderError : public ::testing::TestWithParam<BadFis> {};

TEST_P(FisReaderError, NamesFileLineAndField) {
  const BadFis& b = GetParam();
  std::string text = neurocloth::test::rule_file_text("matlab_drape.fis");
  for (const auto& [from, to] : b.edits) {
    const auto pos = text.find(from);
    ASSERT_NE(pos, std::string::npos) << b.name << ": no '" << from << "'";
    text.replace(pos, from.size(), to);
  }
  try {
    parse_fis(text, "bad.fis");
    FAIL() << b.name << ": read without error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "bad.fis");
    EXPECT_EQ(e.field(), b.field) << e.what();
    EXPECT_EQ(e.line(), *b.at ? line_of(text, b.at) : 0) << e.what();
    EXPECT_NE(e.message().find(b.message), std::string::npos) << e.what();
  }
}

const std::string kInput2 =
    "[Input2]\nName='stretch'\nRange=[0 10]\nNumMFs=2\nMF1='low':'sigmf',[-1.5 4]\n"
    "MF2='high':'gbellmf',[2 3 8]\n";

// 10001 points: one more than a point list may hold.
std::string too_many_points() {
  std::string s = "'discretemf',[";
  for (std::size_t i = 0; i <= kMaxPoints; ++i)
    s += std::to_string(i) + " 0.5 ";
  return s + "]";
}

const BadFis kBad[] = {
    // Missing sections: named at the count that calls for them.
    {"MissingInputSection",
     {{kInput2, ""}},
     "[System] NumInputs",
     "NumInputs",
     "missing section [Input2]"},
    {"MissingRulesSection",
     {{"\n[Rules]\n1 1, 1 (1) : 1\n2 0, 2 (1) : 1\n3 -2, 3 (0.5) : 1\n2 2, -1 (1) : 2\n", "\n"}},
     "[System] NumRules",
     "NumRules",
     "missing section [Rules] (NumRules=4)"},
    {"RuleOutsideRules",
     {{"[Rules]", "%[Rules]"}},
     "[Output1]",
     "1 1, 1",
     "expected key=value, got '1 1, 1 (1) : 1'"},
    {"MissingSystemSection",
     {{"[System]\n", ""}},
     "[System]",
     "Name='drape'",
     "expected a [System] section"},
    {"SectionBeyondItsCount",
     {{"NumInputs=2", "NumInputs=1"}},
     "[Input2]",
     "[Input2]",
     "section beyond NumInputs=1"},
    // Counts against what is there.
    {"FewerMfsThanNumMfs",
     {{"MF3='heavy':'gaussmf',[0.15 1]\n", ""}},
     "[Input1] NumMFs",
     "NumMFs=3",
     "NumMFs=3 but MF3 is missing"},
    {"MfBeyondNumMfs",
     {{"MF2='high':'gbellmf',[2 3 8]", "MF2='high':'gbellmf',[2 3 8]\nMF3='x':'trimf',[1 2 3]"}},
     "[Input2] MF3",
     "MF3='x'",
     "MF3 beyond NumMFs=2"},
    {"FewerRulesThanNumRules",
     {{"2 2, -1 (1) : 2\n", ""}},
     "[System] NumRules",
     "NumRules",
     "NumRules=4 but [Rules] holds 3 rules"},
    {"RuleEntriesAgainstNumInputs",
     {{"2 0, 2 (1) : 1", "2 0 1, 2 (1) : 1"}},
     "[Rules] rule 2",
     "2 0 1,",
     "expected 2 input and 1 output entries"},
    // Rules against the membership functions.
    {"RuleNamesAMissingMf",
     {{"3 -2, 3 (0.5) : 1", "4 -2, 3 (0.5) : 1"}},
     "[Rules] rule 3",
     "4 -2",
     "membership function 4 of input 'weight', which has 3"},
    {"RuleNamesAMissingOutputMf",
     {{"2 0, 2 (1) : 1", "2 0, 7 (1) : 1"}},
     "[Rules] rule 2",
     "2 0, 7",
     "membership function 7 of output 'stiffness'"},
    {"RuleWeightAboveOne",
     {{"(0.5) : 1", "(1.5) : 1"}},
     "[Rules] rule 3",
     "(1.5)",
     "weight must be in [0, 1]"},
    {"RuleConnectionThree",
     {{"2 2, -1 (1) : 2", "2 2, -1 (1) : 3"}},
     "[Rules] rule 4",
     ": 3",
     "connection must be 1 (AND) or 2 (OR)"},
    {"RuleTestsNothing",
     {{"2 0, 2 (1) : 1", "0 0, 2 (1) : 1"}},
     "[Rules] rule 2",
     "0 0, 2",
     "tests no input"},
    {"UnsupportedHedgeCode",
     {{"2 0, 2 (1) : 1", "2.30 0, 2 (1) : 1"}},
     "[Rules] rule 2",
     "2.30",
     "hedge code 2.3 (power 3) is not supported"},
    // What this engine cannot evaluate.
    {"UnsupportedMfType",
     {{"'trimf',[0.2 0.5 0.8]", "'pimf',[0.2 0.4 0.6 0.8]"}},
     "[Input1] MF2",
     "pimf",
     "membership function type 'pimf' has no equivalent"},
    {"UnsupportedDefuzzifier",
     {{"'centroid'", "'bisector'"}},
     "[System] DefuzzMethod",
     "bisector",
     "DefuzzMethod 'bisector' is not supported"},
    {"UnsupportedAnd",
     {{"AndMethod='min'", "AndMethod='einstein_product'"}},
     "[System] AndMethod",
     "einstein",
     "this engine offers min, prod, algebraic_product"},
    {"UnsupportedType",
     {{"'mamdani'", "'type2'"}},
     "[System] Type",
     "type2",
     "Type 'type2' is not supported"},
    // fuzzylite's discretemf: pairs of finite numbers, x in order, y in [0, 1], not too many.
    {"DiscretemfOddCount",
     {{"'trimf',[0.2 0.5 0.8]", "'discretemf',[0.2 0 0.5 1 0.8]"}},
     "[Input1] MF2",
     "discretemf",
     "discretemf takes x y pairs ([x1 y1 x2 y2 ...]), got 5 numbers"},
    {"DiscretemfEmpty",
     {{"'trimf',[0.2 0.5 0.8]", "'discretemf',[]"}},
     "[Input1] MF2",
     "discretemf",
     "got 0 numbers"},
    {"DiscretemfNotFinite",
     {{"'trimf',[0.2 0.5 0.8]", "'discretemf',[0.2 0 inf 1]"}},
     "[Input1] MF2",
     "discretemf",
     "'inf' is not a finite number"},
    {"DiscretemfDecreasingX",
     {{"'trimf',[0.2 0.5 0.8]", "'discretemf',[0.5 0 0.2 1]"}},
     "[Input1] MF2",
     "discretemf",
     "point x values must not decrease"},
    {"DiscretemfDegreeAboveOne",
     {{"'trimf',[0.2 0.5 0.8]", "'discretemf',[0.2 0 0.5 1.5]"}},
     "[Input1] MF2",
     "discretemf",
     "membership degrees must be in [0, 1]"},
    {"DiscretemfTooManyPoints",
     {{"'trimf',[0.2 0.5 0.8]", too_many_points()}},
     "[Input1] MF2",
     "discretemf",
     "a point list holds at most 10000 points, got 10001"},
    {"DiscretemfInASugenoOutput",
     {{"'mamdani'", "'sugeno'"},
      {"DefuzzMethod='centroid'", "DefuzzMethod='wtaver'"},
      {"'soft':'trimf',[0 20 50]", "'soft':'discretemf',[0 1 50 0]"}},
     "[Output1] MF1",
     "'soft'",
     "a sugeno output's membership functions are constant or linear, got discretemf"},
    {"RampmfWithoutASlope",
     {{"'trimf',[0.2 0.5 0.8]", "'rampmf',[0.5 0.5]"}},
     "[Input1] MF2",
     "rampmf",
     "rampmf needs start != end"},
    // fuzzylite's hybrid: an output's MFs are all constant/linear or none are,
    // and DefuzzMethod names the first output's kind.
    {"HybridOutputMixingKinds",
     {{"'mamdani'", "'hybrid'"}, {"'firm':'trapmf',[30 60 80 100]", "'firm':'constant',[60]"}},
     "[Output1] MF2",
     "'firm'",
     "this output of a hybrid system is mamdani (its MF1 is neither constant nor linear)"},
    {"HybridDefuzzMethodNotTheFirstOutputs",
     {{"'mamdani'", "'hybrid'"}, {"DefuzzMethod='centroid'", "DefuzzMethod='wtaver'"}},
     "[System] DefuzzMethod",
     "DefuzzMethod",
     "a hybrid system's DefuzzMethod is its first output's, and 'stiffness' is mamdani"},
    {"HybridBisector",
     {{"'mamdani'", "'hybrid'"}, {"DefuzzMethod='centroid'", "DefuzzMethod='bisector'"}},
     "[System] DefuzzMethod",
     "DefuzzMethod",
     "DefuzzMethod 'bisector' is not supported for hybrid"},
    {"ConstantInAMamdaniOutput",
     {{"'soft':'trimf',[0 20 50]", "'soft':'constant',[20]"}},
     "[Output1] MF1",
     "'soft'",
     "this system is mamdani"},
    // Values.
    {"ParameterCount",
     {{"'trimf',[0.2 0.5 0.8]", "'trimf',[0.2 0.5]"}},
     "[Input1] MF2",
     "[0.2 0.5]",
     "trimf takes 3 parameters, got 2"},
    {"BadNumber",
     {{"Range=[0 10]", "Range=[0 1O]"}},
     "[Input2] Range",
     "1O",
     "expected a number, got '1O'"},
    {"HugeNumber",
     {{"Range=[0 10]", "Range=[0 1e300]"}},
     "[Input2] Range",
     "1e300",
     "beyond +-1e15"},
    {"NotANumber",
     {{"Range=[0 10]", "Range=[0 nan]"}},
     "[Input2] Range",
     "nan",
     "not a finite number"},
    {"ReversedRange", {{"Range=[0 10]", "Range=[10 0]"}}, "[Input2] Range", "[10 0]", "min < max"},
    {"InvalidTriangle",
     {{"[0.2 0.5 0.8]", "[0.8 0.5 0.2]"}},
     "[Input1] MF2",
     "[0.8 0.5 0.2]",
     "trian needs a <= b <= c"},
    {"HugeCount",
     {{"NumRules=4", "NumRules=4000000000"}},
     "[System] NumRules",
     "NumRules",
     "NumRules must be a whole number from 0 to 100000"},
    {"DuplicateKey",
     {{"Range=[0 10]", "Range=[0 10]\nRange=[0 9]"}},
     "[Input2] Range",
     "[0 9]",
     "Range given twice"},
    {"UnknownSection", {{"[Rules]", "[Rulez]"}}, "[Rulez]", "[Rulez]", "unknown section"},
    {"UnknownKey",
     {{"Version=2.0", "Versoin=2.0"}},
     "[System] Versoin",
     "Versoin",
     "unknown key 'Versoin'"},
    {"UnbalancedQuote",
     {{"Name='stretch'", "Name='stretch"}},
     "[Input2] Name",
     "Name='stretch",
     "unbalanced quote"},
    {"DuplicateVariable",
     {{"Name='stretch'", "Name='weight'"}},
     "[Input2] Name",
     "Name='weight'\nRange=[0 10]",
     "duplicate variable name 'weight'"},
};

INSTANTIATE_TEST_SUITE_P(Fis, FisReaderError, ::testing::ValuesIn(kBad),
                         [](const auto& info) { return std::string(info.param.name); });

TEST(FisReader, MissingFileIsAnInputError) {
  EXPECT_THROW(read_fis("/nonexistent/rules.fis"), InputError);
}

}  // namespace
}  // namespace neurocloth::fuzzy
