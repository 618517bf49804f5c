// The examples CSV of tune-rules (src/learn/rule_examples.h): what it
// tolerates and what it refuses, with the file, line, column and field named.
#include <gtest/gtest.h>

#include <string>

#include "core/fuzzy/formats/fcl_reader.h"
#include "core/io/input_error.h"
#include "learn/rules/rule_examples.h"

namespace neurocloth {
namespace {

const char* kExampleRules = R"(
FUNCTION_BLOCK b
VAR_INPUT mass : REAL; force : REAL; END_VAR
VAR_OUTPUT k : REAL; c : REAL; END_VAR
FUZZIFY mass RANGE := (0 .. 2); TERM light := trian 0 0 1; TERM heavy := trian 1 2 2; END_FUZZIFY
FUZZIFY force RANGE := (0 .. 10); TERM any := trape 0 0 10 10; END_FUZZIFY
DEFUZZIFY k RANGE := (0 .. 100); TERM lo := trian 0 10 50; TERM hi := trian 40 90 100; METHOD : COG; END_DEFUZZIFY
DEFUZZIFY c RANGE := (0 .. 1); TERM v := 0.5; METHOD : COGS; END_DEFUZZIFY
RULEBLOCK r
  RULE 1 : IF mass IS light THEN k IS lo, c IS v;
  RULE 2 : IF mass IS heavy AND force IS any THEN k IS hi;
END_RULEBLOCK
END_FUNCTION_BLOCK
)";

fuzzy::FuzzySystem rules() {
  return fuzzy::parse_fcl(kExampleRules, "b.fcl");
}

TEST(RuleExamples, ReadsWithABomCrlfCommentsAndBlankLines) {
  const RuleExamples e = parse_rule_examples(
      "\xEF\xBB\xBF# made by hand\r\nforce, k ,mass\r\n\r\n3,20,0.5\r\n# another\r\n7.5,80,1.5\r\n",
      "ex.csv", rules());
  ASSERT_EQ(e.size(), 2u);
  ASSERT_EQ(e.outputs, std::vector<int>{0});
  EXPECT_EQ(e.inputs[0], (std::vector<double>{0.5, 3}));  // the rule base's input order
  EXPECT_EQ(e.targets[1], std::vector<double>{80});
  EXPECT_EQ(e.lines, (std::vector<int>{4, 6}));
}

// The error's text names everything in `mentions`.
void expect_refused(const std::string& text, const std::vector<std::string>& mentions) {
  try {
    parse_rule_examples(text, "ex.csv", rules());
    ADD_FAILURE() << "accepted: " << text;
  } catch (const InputError& e) {
    for (const auto& m : mentions)
      EXPECT_NE(std::string(e.what()).find(m), std::string::npos) << m << " not in " << e.what();
  }
}

TEST(RuleExamples, RefusesWhatItCannotUse) {
  expect_refused("mass,force,k,speed\n1,2,3,4\n",
                 {"ex.csv:1:4", "speed", "not an input or output"});
  expect_refused("mass,k\n1,2\n", {"ex.csv:1", "force", "missing"});
  expect_refused("mass,force\n1,2\n", {"ex.csv:1", "no output"});
  expect_refused("mass,force,k,mass\n1,2,3,1\n", {"ex.csv:1:4", "twice"});
  expect_refused("mass,force,k\n1,2,nan\n", {"ex.csv:2:3", "'k'", "NaN"});
  expect_refused("mass,force,k\n1,2,1e999\n", {"ex.csv:2:3", "infinite"});
  expect_refused("mass,force,k\n1,two,3\n", {"ex.csv:2:2", "'force'", "not a number"});
  expect_refused("mass,force,k\n1,2\n", {"ex.csv:2", "expected 3 fields"});
  expect_refused("mass,force,k\n2.5,2,3\n", {"ex.csv:2:1", "'mass'", "RANGE"});
  expect_refused("mass,force,k\n1,2,300\n", {"ex.csv:2:3", "'k'", "RANGE"});
  expect_refused("mass,force,k\n# nothing\n", {"ex.csv", "no examples"});
  expect_refused("", {"ex.csv", "empty"});
}

}  // namespace
}  // namespace neurocloth
