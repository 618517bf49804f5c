// Reading FCL, what is refused: every error names the file, the field, the
// line and the column, and says what is wrong (docs/fcl.md).
#include <gtest/gtest.h>

#include <cstdio>
#include <ostream>
#include <string>

#include "core/fuzzy/membership_function.h"
#include "support/fcl_test_text.h"

namespace neurocloth::fuzzy {
namespace {
using namespace fcl_test;

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
     "METHOD : COA (centre of area) is not supported: this engine defuzzifies by COG"},
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
    // Hostile depth: each '(' and NOT is a level of recursion (here, in
    // inference and in the writer); 32 are read (fcl_reader_test.cpp), 33 not.
    {"NestedTooDeep", {{"IF mass IS heavy", "IF (((((((((((((((((((((((((((((((((mass IS heavy)))))))))))))))))))))))))))))))))"}},
     "RULE 1", "(mass IS heavy", "the condition nests '(' and NOT more than 32 levels deep"},
    {"NegatedTooDeep", {{"IF mass IS heavy", "IF NOT NOT NOT NOT NOT NOT NOT NOT NOT NOT NOT NOT NOT NOT NOT NOT NOT NOT NOT NOT NOT NOT NOT NOT NOT NOT NOT NOT NOT NOT NOT NOT NOT mass IS heavy"}},
     "RULE 1", "NOT mass IS heavy", "the condition nests '(' and NOT more than 32 levels deep"},
    {"NumberBeyondTheEnginesRange", {{"TERM high := trian 100 500 1000", "TERM high := trian 100 500 1e16"}},
     "TERM high", "1e16", "number '1e16' is beyond +-1e15"},
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

// A point list is read whole, then held to kMaxPoints (10000) points: the
// most is read, one more is refused, naming the term.
TEST(FclReader, APointListOfMoreThanTheMostPointsIsRefused) {
  auto with_points = [](std::size_t n) {
    std::string list;
    for (std::size_t i = 0; i < n; ++i) {
      char point[48];
      std::snprintf(point, sizeof point, "(%.17g, %d) ", 2.0 * double(i) / double(n), int(i % 2));
      list += point;
    }
    return edited({{"trian 0 0 1;", list + ";"}});
  };
  const FuzzySystem most = parse_fcl(with_points(kMaxPoints), kPath);
  EXPECT_EQ(most.inputs[0].terms[0].function.shape, Shape::points);
  EXPECT_EQ(most.inputs[0].terms[0].function.params.size(), 2 * kMaxPoints);
  expect_error(with_points(kMaxPoints + 1), "TERM light",
               "light :=", "a point list holds at most 10000 points, got 10001");
}

}  // namespace
}  // namespace neurocloth::fuzzy
