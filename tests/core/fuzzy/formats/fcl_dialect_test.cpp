// Reading the FCL that fuzzylite and jFuzzyLogic write (fcl_dialect.cpp): what
// maps onto this engine is read as ours, what does not is refused with one
// line naming file, line and field. Whole files in each tool's style, against
// their IEC 61131-7 text: rule_file_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "core/fuzzy/formats/fcl_reader.h"
#include "core/io/input_error.h"
#include "support/line_of.h"
#include "support/rule_file_data.h"

namespace neurocloth::fuzzy {
namespace {
namespace fs = std::filesystem;

using neurocloth::test::line_of;

struct DialectRefusal {
  const char* name;
  const char* file;
  std::vector<std::pair<std::string, std::string>> edits;  // replace first with second
  const char* field;
  const char* at;  // text on the line the error must name
  const char* message;
};

std::string dialect_edited(const DialectRefusal& r) {
  std::string text = neurocloth::test::rule_file_text(r.file);
  for (const auto& [from, to] : r.edits) {
    const auto pos = text.find(from);
    EXPECT_NE(pos, std::string::npos) << r.name << ": no '" << from << "'";
    if (pos != std::string::npos) text.replace(pos, from.size(), to);
  }
  return text;
}

class FclDialectRefusal : public ::testing::TestWithParam<DialectRefusal> {};

TEST_P(FclDialectRefusal, NamesFileLineFieldAndWhatIsUnsupported) {
  const DialectRefusal& r = GetParam();
  const std::string text = dialect_edited(r);
  try {
    parse_fcl(text, "dialect.fcl");
    FAIL() << r.name << ": read without error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "dialect.fcl");
    EXPECT_EQ(e.field(), r.field) << e.what();
    EXPECT_EQ(e.line(), line_of(text, r.at)) << e.what();
    EXPECT_NE(e.message().find(r.message), std::string::npos) << e.what();
  }
}

const char* const kLite = "fuzzylite_drape.fcl";
const char* const kJfl = "jfuzzylogic_drape.fcl";

const DialectRefusal kRefusals[] = {
    {"NormWeDoNotHave",
     kLite,
     {{"AND : AlgebraicProduct;", "AND : EPROD;"}},
     "RULEBLOCK shape",
     "AND : EPROD",
     "AND : EPROD (Einstein product) is not supported"},
    {"AccumulationWeDoNotHave",
     kLite,
     {{"ACCU : UnboundedSum;", "ACCU : NormalizedSum;"}},
     "DEFUZZIFY stiffness",
     "NormalizedSum",
     "(normalised sum) is not supported"},
    {"DefuzzifierWeDoNotHave",
     kLite,
     {{"METHOD : COG;", "METHOD : MM;"}},
     "DEFUZZIFY stiffness",
     "METHOD : MM",
     "METHOD : MM (mean of maximum) is not supported"},
    {"DisabledVariable",
     kLite,
     {{"ENABLED : TRUE;", "ENABLED : FALSE;"}},
     "DEFUZZIFY damping",
     "ENABLED : FALSE",
     "ENABLED : FALSE"},
    {"TermWithHeight",
     kLite,
     {{"Triangle 0.200 0.500 0.800;", "Triangle 0.200 0.500 0.800 0.5;"}},
     "TERM medium",
     "0.800 0.5",
     "Triangle with height 0.5"},
    {"ShapeWeDoNotHave",
     kLite,
     {{"Triangle 0.200 0.500 0.800", "Rectangle 0.2 0.8"}},
     "TERM medium",
     "Rectangle",
     "membership function 'Rectangle' has no equivalent"},
    {"HedgeWeDoNotHave",
     kLite,
     {{"stretch is very low", "stretch is extremely low"}},
     "RULE 1",
     "extremely",
     "hedge 'extremely' is not supported"},
    {"LinearOutputLockedToItsRange",
     kLite,
     {{"LOCK : PREVIOUS;", "LOCK : PREVIOUS, RANGE;"}},
     "DEFUZZIFY damping",
     "LOCK : PREVIOUS, RANGE",
     "LOCK : RANGE clamps the output"},
    {"OneBlockTwoAccumulations",
     kLite,
     {{"then stiffness is rigid\n", "then stiffness is rigid and damping is some\n"},
      {"ACCU : UnboundedSum;", "ACCU : Maximum;"}},
     "DEFUZZIFY damping",
     "DEFUZZIFY damping",
     "move one output's rules into a RULEBLOCK"},
    {"BlockAccumulationAgainstOutputs",
     kLite,
     {{"  ACT : Minimum;", "  ACT : Minimum;\n  ACCU : MAX;"}},
     "DEFUZZIFY stiffness",
     "UnboundedSum",
     "disagrees with ACCU : MAX of RULEBLOCK shape"},
    {"AccumulationNoneOnACentroid",
     kLite,
     {{"ACCU : UnboundedSum;", "ACCU : NONE;"}},
     "DEFUZZIFY stiffness",
     "ACCU : NONE",
     "ACCU : NONE"},
    {"SingletonsOfJFuzzyLogic",
     kJfl,
     {{"TERM none :=  0.0;", "TERM none := SINGLETONS (0.0, 1.0);"}},
     "TERM none",
     "SINGLETONS",
     "'SINGLETONS' has no equivalent"},
    {"LeftmostMaximumOfJFuzzyLogic",
     kJfl,
     {{"METHOD : COG;", "METHOD : LM;"}},
     "DEFUZZIFY stiffness",
     "METHOD : LM",
     "METHOD : LM (leftmost maximum) is not supported"},
    {"ProductWithoutItsPairedOr",
     kJfl,
     {{"AND : MIN;", "AND : PROD;"}},
     "RULEBLOCK No1",
     "AND : PROD",
     "AND : PROD without OR, and RULE 2 uses OR"},
    {"BoundedDifferenceOfJFuzzyLogic",
     kJfl,
     {{"AND : MIN;", "AND : BDIF;"}},
     "RULEBLOCK No1",
     "AND : BDIF",
     "(bounded difference) is not supported"},
};

INSTANTIATE_TEST_SUITE_P(Dialects, FclDialectRefusal, ::testing::ValuesIn(kRefusals),
                         [](const auto& info) { return std::string(info.param.name); });

// fuzzylite's parameter orders become ours; its class names and "nan" read.
TEST(FclDialect, FuzzyliteTermsReadInOurParameterOrder) {
  const FuzzySystem s = parse_fcl(neurocloth::test::rule_file_text(kLite), kLite);
  const LinguisticVariable& stretch = s.inputs[1];
  EXPECT_EQ(stretch.terms[1].function.shape, Shape::bell);
  EXPECT_EQ(stretch.terms[1].function.params,
            (std::vector<double>{2, 3, 8}));  // width slope center
  EXPECT_EQ(stretch.terms[2].function.shape, Shape::sigmoid);
  EXPECT_EQ(stretch.terms[2].function.params, (std::vector<double>{1.2, 5}));  // slope inflection
  const LinguisticVariable& damping = s.outputs[1];
  EXPECT_EQ(damping.terms[1].function.shape, Shape::singleton);
  EXPECT_EQ(damping.terms[2].function.params, (std::vector<double>{0.1, 0.3, 0.02}));  // c first
  EXPECT_TRUE(std::isnan(damping.default_value));
  EXPECT_EQ(s.blocks[0].accumulation, Accumulation::sum);  // from DEFUZZIFY stiffness
  EXPECT_EQ(s.blocks[1].accumulation, Accumulation::sum);  // COGS without ACCU, fuzzylite rules
  EXPECT_EQ(s.blocks[0].and_method, AndMethod::product);
  EXPECT_EQ(s.blocks[1].rules[2].consequents.size(), 2u);  // "then ... and ..."
}

// The same COGS output without ACCU in an IEC file (rules end with ';') keeps
// the standard's MAX: only a fuzzylite file says "no aggregation" that way.
TEST(FclDialect, MissingAccuMeansSumOnlyInAFuzzyliteFile) {
  std::string text = neurocloth::test::rule_file_text("fuzzylite_drape.standard.fcl");
  const auto at = text.find("  ACCU : SUM;\n  RULE 1 : IF weight IS heavy");
  ASSERT_NE(at, std::string::npos);
  text.erase(at, std::string("  ACCU : SUM;\n").size());
  EXPECT_EQ(parse_fcl(text, "iec.fcl").blocks[1].accumulation, Accumulation::max);
}

}  // namespace
}  // namespace neurocloth::fuzzy
