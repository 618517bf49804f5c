// `neurocloth-cli tune-rules` run as a user would: bad input refused with the
// file, line and field named and nothing written; a tuning that writes a
// rule base the reader takes back.
#include "support/cli_fixture.h"

#include "core/fuzzy/formats/fcl_reader.h"
#include "core/fuzzy/formats/rule_file.h"

namespace neurocloth::cli_test {
namespace {

// A Sugeno output (singletons) over one input: least squares is exact.
const char* kTunedRules = R"(FUNCTION_BLOCK t
VAR_INPUT x : REAL; END_VAR
VAR_OUTPUT y : REAL; END_VAR
FUZZIFY x
  RANGE := (0 .. 10);
  TERM low := trian 0 0 10;
  TERM high := trian 0 10 10;
END_FUZZIFY
DEFUZZIFY y
  RANGE := (0 .. 100);
  TERM a := 10;
  TERM b := 90;
  METHOD : COGS;
END_DEFUZZIFY
RULEBLOCK r
  RULE 1 : IF x IS low THEN y IS a;
  RULE 2 : IF x IS high THEN y IS b;
END_RULEBLOCK
END_FUNCTION_BLOCK
)";

class CliTuneRules : public Cli {
 protected:
  std::string out() const { return (out_dir() / "tuned.fcl").string(); }
  std::string rules() const { return write("rules.fcl", kTunedRules); }
  std::vector<std::string> args(const std::string& examples) const {
    return {"tune-rules", "--rules", rules(), "--examples", examples, "--out", out()};
  }
};

TEST_F(CliTuneRules, BadExamplesAreRefusedNamingFileLineAndField) {
  expect_input_error(args(write("a.csv", "x,y,z\n1,2,3\n")), {"a.csv:1:3", "'z'"});
  expect_input_error(args(write("b.csv", "y\n1\n")), {"b.csv:1", "'x'", "missing"});
  expect_input_error(args(write("c.csv", "x,y\n1,2\n3,nan\n")), {"c.csv:3:2", "'y'", "NaN"});
  expect_input_error(args(write("d.csv", "x,y\n1,abc\n")), {"d.csv:2:2", "not a number"});
  expect_input_error(args(write("e.csv", "x,y\n")), {"e.csv", "no examples"});
  expect_input_error(args(write("f.csv", "x,y\n11,2\n")), {"f.csv:2:1", "'x'", "RANGE"});
  expect_input_error(args(write("g.csv", "x,y\n1,2\n")), {"g.csv", "at least 8 are needed"});
  expect_input_error(args(write("h.csv", "x\n1\n")), {"h.csv:1", "no output"});
}

// A header name that is no variable is the file's bytes: a terminal escape or a
// carriage return is shown as \xNN and a long one cut, so the error stays one
// short line.
TEST_F(CliTuneRules, AnUnknownHeaderNameIsShownSafely) {
  const std::string name = "a\rb" + std::string(100000, '\x1b');
  const Outcome o = run(args(write("a.csv", "x,y," + name + "\n1,2,3\n")));
  EXPECT_EQ(o.code, kInputError) << o.err;
  EXPECT_NE(o.err.find("a.csv:1:3"), std::string::npos) << o.err;
  EXPECT_NE(o.err.find("a\\x0db"), std::string::npos) << o.err;
  EXPECT_EQ(o.err.find('\r'), std::string::npos);
  EXPECT_EQ(o.err.find('\x1b'), std::string::npos);
  EXPECT_LT(o.err.size(), 400u);
  EXPECT_TRUE(files_in_out_dir().empty());
}

TEST_F(CliTuneRules, AnOutputOverAnInputIsRefused) {
  const std::string examples = write("ex.csv", "x,y\n1,20\n9,80\n");
  const std::string r = rules();
  expect_input_error({"tune-rules", "--rules", r, "--examples", examples, "--out", r},
                     {"--out", "reads"});
  const Outcome o = run({"tune-rules", "--rules", r, "--examples", examples, "--out", examples});
  EXPECT_EQ(o.code, kInputError) << o.err;
  EXPECT_EQ(read_text(examples), "x,y\n1,20\n9,80\n");
}

TEST_F(CliTuneRules, BadOptionsAreRefused) {
  const std::string examples = write("ex.csv", "x,y\n1,20\n9,80\n");
  auto a = args(examples);
  a.insert(a.end(), {"--what", "everything"});
  expect_input_error(a, {"--what", "everything"});
  a = args(examples);
  a.insert(a.end(), {"--iterations", "0"});
  expect_input_error(a, {"--iterations"});
}

TEST_F(CliTuneRules, RecoversConsequentsAndWritesAReadableRuleBase) {
  // y = (10 (10 - x) + 90 x) / 10 with a = 10, b = 90; the examples say a = 20, b = 70.
  std::string csv = "# y from a = 20, b = 70\r\nx,y\r\n";
  for (double x : {0.5, 2.0, 4.0, 6.5, 9.0})
    csv += std::to_string(x) + "," + std::to_string((20 * (10 - x) + 70 * x) / 10) + "\r\n";
  auto a = args(write("ex.csv", csv));
  a.insert(a.end(), {"--what", "consequents"});
  const Outcome r = run(a);
  ASSERT_EQ(r.code, kOk) << r.out << r.err;
  EXPECT_NE(r.out.find("y.a: singleton 10 -> singleton 20"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("y.b: singleton 90 -> singleton 70"), std::string::npos) << r.out;
  const fuzzy::FuzzySystem tuned = fuzzy::read_fcl(out());
  EXPECT_NEAR(tuned.outputs[0].terms[0].function.params[0], 20, 1e-6);
  EXPECT_NEAR(tuned.outputs[0].terms[1].function.params[0], 70, 1e-6);
  EXPECT_NE(read_text(out()).find("(* Tuned by neurocloth-cli tune-rules"), std::string::npos);
  const std::string per_example = read_text((out_dir() / "tuned.examples.csv").string());
  EXPECT_EQ(per_example.rfind("line,x,y_target,y_before,y_after,rmse_before,rmse_after\n", 0), 0u)
      << per_example;
}

// A MATLAB .fis in, a .fis out: the same tuning, the summary as % comments.
TEST_F(CliTuneRules, ReadsAndWritesAFis) {
  const std::string fis = write("rules.fis", R"([System]
Name='t'
Type='sugeno'
NumInputs=1
NumOutputs=1
NumRules=2
AndMethod='min'
OrMethod='max'
ImpMethod='prod'
AggMethod='sum'
DefuzzMethod='wtaver'

[Input1]
Name='x'
Range=[0 10]
NumMFs=2
MF1='low':'trimf',[0 0 10]
MF2='high':'trimf',[0 10 10]

[Output1]
Name='y'
Range=[0 100]
NumMFs=2
MF1='a':'constant',[10]
MF2='b':'constant',[90]

[Rules]
1, 1 (1) : 1
2, 2 (1) : 1
)");
  std::string csv = "x,y\n";
  for (double x : {0.5, 2.0, 4.0, 6.5, 9.0})
    csv += std::to_string(x) + "," + std::to_string((20 * (10 - x) + 70 * x) / 10) + "\n";
  const std::string tuned = (out_dir() / "tuned.fis").string();
  const Outcome r = run({"tune-rules", "--rules", fis, "--examples", write("ex.csv", csv), "--out",
                         tuned, "--what", "consequents"});
  ASSERT_EQ(r.code, kOk) << r.out << r.err;
  const fuzzy::FuzzySystem back = fuzzy::read_rule_file(tuned);
  EXPECT_NEAR(back.outputs[0].terms[0].function.params[0], 20, 1e-6);
  EXPECT_NEAR(back.outputs[0].terms[1].function.params[0], 70, 1e-6);
  EXPECT_EQ(read_text(tuned).rfind("% Tuned by neurocloth-cli tune-rules", 0), 0u);
  EXPECT_TRUE(fs::exists(out_dir() / "tuned.examples.csv"));
  fs::remove(tuned);
  fs::remove(out_dir() / "tuned.examples.csv");
  // A rule base a .fis cannot hold (a DEFAULT) is refused before the
  // search, naming --out.
  const std::string defaulted =
      write("default.fcl", with(kTunedRules, "METHOD : COGS;", "METHOD : COGS;\n  DEFAULT := 50;"));
  expect_input_error({"tune-rules", "--rules", defaulted, "--examples", write("ex2.csv", csv),
                      "--out", (out_dir() / "p.fis").string(), "--what", "consequents"},
                     {"--out", ".fis", "DEFAULT 50"});
}

TEST_F(CliTuneRules, TunesTermsWithAProgressLine) {
  std::string csv = "x,y\n";
  for (int i = 0; i < 12; ++i) {
    const double x = 0.4 + 0.8 * i;
    csv += std::to_string(x) + "," + std::to_string(10 + 80 * std::min(1.0, x / 8)) + "\n";
  }
  auto a = args(write("ex.csv", csv));
  a.insert(a.end(), {"--what", "mf", "--iterations", "30"});
  const Outcome r = run(a);
  ASSERT_EQ(r.code, kOk) << r.out << r.err;
  EXPECT_NE(r.out.find("iteration 0/30"), std::string::npos) << r.out;  // plain lines: no tty
  EXPECT_NE(r.out.find("RMSE before"), std::string::npos) << r.out;
  EXPECT_NO_THROW(fuzzy::read_fcl(out()));
}

}  // namespace
}  // namespace neurocloth::cli_test
