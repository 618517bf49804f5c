// Writing .fis: MATLAB's layout and parameter orders, and a refusal, saying
// what, for every system .fis cannot express. Round trips of whole files:
// rule_file_test.cpp.
#include "core/fuzzy/formats/fis_writer.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <limits>
#include <stdexcept>
#include <string>

#include "core/fuzzy/formats/fcl_reader.h"
#include "core/fuzzy/formats/fis_reader.h"

namespace neurocloth::fuzzy {
namespace {
namespace fs = std::filesystem;

FuzzySystem matlab() {
  return read_fis((fs::path(NEUROCLOTH_TEST_DATA) / "rule_files" / "matlab_drape.fis").string());
}

TEST(FisWriter, WritesMatlabsLayoutAndParameterOrders) {
  const std::string text = write_fis(matlab());
  for (const char* line :
       {"[System]\nName='drape'\nType='mamdani'\n", "NumInputs=2\nNumOutputs=1\nNumRules=4\n",
        "AndMethod='min'\nOrMethod='max'\nImpMethod='min'\nAggMethod='max'\n"
        "DefuzzMethod='centroid'\n",
        "[Input1]\nName='weight'\nRange=[0 1]\nNumMFs=3\n",
        "MF3='heavy':'gaussmf',[0.14999999999999999 1]\n",  // [sigma c]
        "MF2='high':'gbellmf',[2 3 8]\n", "[Rules]\n1 1, 1 (1) : 1\n2 0, 2 (1) : 1\n",
        "3 -2, 3 (0.5) : 1\n2 2, -1 (1) : 2\n"})
    EXPECT_NE(text.find(line), std::string::npos) << "no '" << line << "' in\n" << text;
}

TEST(FisWriter, WritesOneHedgeAsOctavesCode) {
  FuzzySystem s = matlab();
  s.blocks[0].rules[1].condition.hedges = {Hedge::very};
  s.blocks[0].rules[0].condition.children[1].hedges = {Hedge::somewhat};
  const std::string text = write_fis(s);
  EXPECT_NE(text.find("1 1.05, 1 (1) : 1\n2.20 0, 2 (1) : 1\n"), std::string::npos) << text;
  const FuzzySystem back = parse_fis(text, "back.fis");
  EXPECT_EQ(back.blocks[0].rules[1].condition.hedges, (std::vector<Hedge>{Hedge::very}));
}

// Each edit makes the system one .fis cannot hold; the message says what.
TEST(FisWriter, RefusesWhatFisCannotExpress) {
  const struct {
    const char* what;
    void (*edit)(FuzzySystem&);
    const char* message;
  } kCases[] = {
      {"stacked hedges",
       [](FuzzySystem& s) {
         s.blocks[0].rules[1].condition.hedges = {Hedge::very, Hedge::very};
       },
       "stacks hedges"},
      {"nested condition",
       [](FuzzySystem& s) {
         Condition inner = s.blocks[0].rules[0].condition;
         s.blocks[0].rules[0].condition.children[0] = inner;
       },
       "nests AND, OR or NOT"},
      {"default value", [](FuzzySystem& s) { s.outputs[0].default_value = 50; }, "DEFAULT 50"},
      {"two rule blocks with different methods",
       [](FuzzySystem& s) {
         s.blocks.push_back(s.blocks[0]);
         s.blocks[1].and_method = AndMethod::product;
       },
       "different AND/OR/ACT/ACCU methods"},
      {"an input tested twice",
       [](FuzzySystem& s) { s.blocks[0].rules[0].condition.children[1].variable = 0; },
       "tests one input twice"},
      {"a quote in a name", [](FuzzySystem& s) { s.inputs[0].name = "it's"; }, "holds a quote"},
      {"a non-finite parameter",
       [](FuzzySystem& s) {
         s.outputs[0].terms[0].function.params[0] = std::numeric_limits<double>::infinity();
       },
       "parameters must be finite"},
  };
  for (const auto& c : kCases) {
    FuzzySystem s = matlab();
    c.edit(s);
    try {
      write_fis(s);
      ADD_FAILURE() << c.what << ": written";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(c.message), std::string::npos)
          << c.what << ": " << e.what();
    }
  }
}

// A point list as fuzzylite writes a Discrete term: 'discretemf', its x y
// pairs in one list; read back to the same term.
TEST(FisWriter, WritesAPointListAsDiscretemf) {
  FuzzySystem s = matlab();
  s.inputs[0].terms[0].function = {Shape::points, {0, 1, 0.2, 1, 0.6, 0}};
  const std::string text = write_fis(s);
  EXPECT_NE(text.find("MF1='light':'discretemf',[0 1 0.20000000000000001 1 "
                      "0.59999999999999998 0]\n"),
            std::string::npos)
      << text;
  const FuzzySystem back = parse_fis(text, "back.fis");
  EXPECT_EQ(back.inputs[0].terms[0].function.shape, Shape::points);
  EXPECT_EQ(back.inputs[0].terms[0].function.params, s.inputs[0].terms[0].function.params);
}

// Mamdani and Sugeno outputs together: fuzzylite's Type='hybrid', whose
// DefuzzMethod is the first output's.
TEST(FisWriter, WritesMixedOutputsAsFuzzylitesHybrid) {
  FuzzySystem s = read_fcl(
      (fs::path(NEUROCLOTH_TEST_DATA) / "rule_files" / "jfuzzylogic_drape.standard.fcl").string());
  s.outputs[1].default_value = std::numeric_limits<double>::quiet_NaN();  // .fis has no DEFAULT
  const std::string text = write_fis(s);
  EXPECT_NE(text.find("Type='hybrid'\n"), std::string::npos) << text;
  EXPECT_NE(text.find("DefuzzMethod='wtaver'\n"), std::string::npos) << text;  // damping's
  const FuzzySystem back = parse_fis(text, "back.fis");
  EXPECT_EQ(back.outputs[0].method, Defuzzification::weighted_average);
  EXPECT_EQ(back.outputs[1].method, Defuzzification::centroid);
}

// fuzzylite_drape's two rule blocks differ in AND and OR, which one
// [System] cannot say.
TEST(FisWriter, RefusesRuleBlocksWithDifferentMethods) {
  const FuzzySystem s = read_fcl(
      (fs::path(NEUROCLOTH_TEST_DATA) / "rule_files" / "fuzzylite_drape.standard.fcl").string());
  try {
    write_fis(s);
    FAIL() << "written";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("use different AND/OR/ACT/ACCU methods"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace neurocloth::fuzzy
