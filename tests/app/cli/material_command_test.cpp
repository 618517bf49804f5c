// `neurocloth-cli material`, run as a user would.
#include "support/cli_fixture.h"

namespace neurocloth::cli_test {
namespace {

// material: a rule base and linguistic inputs -> every output and rule activation.
TEST_F(Cli, MaterialFromRulesAndInputs) {
  const std::string fcl = assets_directory() + "/materials/cloth.fcl";
  const Outcome r = run({"material", "--rules", fcl, "--input", "mass=0.2", "--input",
                         "elasticity=0.3", "--input", "force=3", "--json"});
  ASSERT_EQ(r.code, kOk) << r.err;
  const json doc = json::parse(r.out);
  for (const char* out : {"spring_constant", "node_mass", "viscosity", "friction", "bend_constant"})
    EXPECT_TRUE(doc.at("outputs").contains(out)) << out;
  // Sugeno node mass: density x 0.0025 m^2.
  EXPECT_NEAR(doc.at("outputs").at("node_mass").get<double>(), 0.2 * 0.0025, 1e-12);
  EXPECT_EQ(doc.at("rule_activations").size(), 22u);  // paper 3, coverage 14, bending 5
  EXPECT_EQ(doc.at("rule_activations")[0].at("rule"), "1");
  // The preset with the same inputs gives the same outputs.
  const Outcome p = run({"material", "--preset", "cotton", "--json"});
  ASSERT_EQ(p.code, kOk) << p.err;
  EXPECT_EQ(json::parse(p.out).at("outputs"), doc.at("outputs"));
  // Text output names every output and rule.
  const Outcome t = run({"material", "--preset", "silk"});
  ASSERT_EQ(t.code, kOk);
  EXPECT_NE(t.out.find("spring_constant"), std::string::npos);
  EXPECT_NE(t.out.find("bend_constant"), std::string::npos);
  EXPECT_NE(t.out.find("RULE 22"), std::string::npos);
}

TEST_F(Cli, MaterialReportsClampedInputs) {
  const Outcome r =
      run({"material", "--rules", assets_directory() + "/materials/cloth.fcl", "--input", "mass=7",
           "--input", "elasticity=0.3", "--input", "force=3", "--json"});
  ASSERT_EQ(r.code, kOk) << r.err;
  const json doc = json::parse(r.out);
  EXPECT_EQ(doc.at("clamped")[0], "mass");
  EXPECT_NE(doc.at("notes")[0].get<std::string>().find("clamped"), std::string::npos);
}

TEST_F(Cli, MaterialBadInputs) {
  const std::string fcl = assets_directory() + "/materials/cloth.fcl";
  auto expect_error = [&](const std::vector<std::string>& args,
                          const std::vector<std::string>& mentions) {
    const Outcome r = run(args);
    EXPECT_EQ(r.code, kInputError) << r.err;
    for (const auto& m : mentions)
      EXPECT_NE(r.err.find(m), std::string::npos) << m << " not in: " << r.err;
  };
  expect_error({"material", "--rules", fcl, "--input", "mass=0.2", "--input", "elasticity=0.3"},
               {"force", "missing"});
  expect_error({"material", "--rules", fcl, "--input", "mass=0.2", "--input", "elasticity=0.3",
                "--input", "force=3", "--input", "colour=1"},
               {"colour"});
  expect_error({"material", "--rules", fcl, "--input", "mass=heavy", "--input", "elasticity=0.3",
                "--input", "force=3"},
               {"mass", "heavy"});
  expect_error({"material", "--rules", fcl, "--input", "mass"}, {"NAME=VALUE"});
  expect_error({"material", "--preset", "velvet"}, {"velvet", "silk"});
  expect_error({"material", "--rules", (dir_ / "missing.fcl").string(), "--input", "x=1"},
               {"missing.fcl"});
  const std::string broken = write("broken.fcl",
                                   "FUNCTION_BLOCK b\nVAR_INPUT\n  x : REAL;\nEND_VAR\nFUZZIFY x\n "
                                   " RANGE := (0 .. 1);\n  TERM t := trian 0 oops 1;\n");
  expect_error({"material", "--rules", broken, "--input", "x=0.5"}, {broken + ":7:"});
  EXPECT_EQ(run({"material", "--preset", "silk", "--rules", fcl}).code, kUsage);
}

// A MATLAB .fis rule base serves as well as FCL (docs/fcl.md, "Rule files from
// other tools"); a broken one names its file, line and field.
TEST_F(Cli, MaterialFromAFisRuleBase) {
  std::string fis =
      "[System]\nName='tiny'\nType='sugeno'\nNumInputs=1\nNumOutputs=4\nNumRules=2\n"
      "AndMethod='prod'\nOrMethod='probor'\nImpMethod='prod'\nAggMethod='sum'\n"
      "DefuzzMethod='wtaver'\n\n[Input1]\nName='weight'\nRange=[0 1]\nNumMFs=2\n"
      "MF1='light':'trimf',[0 0 1]\nMF2='heavy':'trimf',[0 1 1]\n";
  const char* outputs[4][3] = {{"spring_constant", "[10 1000]", "50 800"},
                               {"node_mass", "[0.001 0.1]", "0.002 0.02"},
                               {"viscosity", "[0 1]", "0.01 0.1"},
                               {"friction", "[0 1]", "0.2 0.6"}};
  for (int k = 0; k < 4; ++k) {
    const std::string values = outputs[k][2];
    const auto space = values.find(' ');
    fis += "\n[Output" + std::to_string(k + 1) + "]\nName='" + outputs[k][0] +
           "'\nRange=" + outputs[k][1] + "\nNumMFs=2\nMF1='a':'constant',[" +
           values.substr(0, space) + "]\nMF2='b':'constant',[" + values.substr(space + 1) + "]\n";
  }
  const std::string good =
      write("tiny.fis", fis + "\n[Rules]\n1, 1 1 1 1 (1) : 1\n2, 2 2 2 2 (1) : 1\n");
  const Outcome r = run({"material", "--rules", good, "--input", "weight=0.25", "--json"});
  ASSERT_EQ(r.code, kOk) << r.err;
  const json doc = json::parse(r.out);
  EXPECT_NEAR(doc.at("outputs").at("spring_constant").get<double>(), 0.75 * 50 + 0.25 * 800, 1e-9);
  const std::string broken =
      write("broken.fis", fis + "\n[Rules]\n1, 1 1 1 1 (1) : 1\n3, 2 2 2 2 (1) : 1\n");
  const Outcome b = run({"material", "--rules", broken, "--input", "weight=0.25"});
  EXPECT_EQ(b.code, kInputError) << b.err;
  EXPECT_NE(b.err.find(broken + ":"), std::string::npos) << b.err;
  EXPECT_NE(b.err.find("[Rules] rule 2"), std::string::npos) << b.err;
  EXPECT_NE(b.err.find("membership function 3 of input 'weight', which has 2"), std::string::npos)
      << b.err;
}

}  // namespace
}  // namespace neurocloth::cli_test
