// Rule files from other tools (docs/fcl.md, "Rule files from other tools"):
// each dialect's file, written by hand in that tool's style, infers what its
// IEC 61131-7 text infers, and survives being written back and read again.
#include "core/fuzzy/formats/rule_file.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "core/fuzzy/formats/fcl_reader.h"
#include "core/fuzzy/formats/fcl_writer.h"
#include "core/fuzzy/formats/fis_reader.h"
#include "core/fuzzy/formats/fis_writer.h"
#include "core/fuzzy/inference.h"
#include "core/io/input_error.h"
#include "core/io/text_file.h"
#include "core/scene/fuzzy_material.h"
#include "support/scratch_dir.h"

namespace neurocloth::fuzzy {
namespace {
namespace fs = std::filesystem;

std::string data(const std::string& name) {
  return (fs::path(NEUROCLOTH_TEST_DATA) / "rule_files" / name).string();
}

// Inputs on a grid over each input's range (7 points each, ends included).
std::vector<std::vector<double>> grid(const FuzzySystem& s) {
  std::vector<std::vector<double>> points{{}};
  for (const LinguisticVariable& v : s.inputs) {
    std::vector<std::vector<double>> next;
    for (const auto& p : points)
      for (int k = 0; k <= 6; ++k) {
        auto q = p;
        q.push_back(v.min + (v.max - v.min) * k / 6.0);
        next.push_back(q);
      }
    points = next;
  }
  return points;
}

// Same outputs (to 1e-12) and same "no rule fired" flags at every grid point
// of `a`'s inputs; `b` names its inputs and outputs alike, maybe in another
// order. The outputs must vary over the grid, so agreement means something.
void expect_same_inference(const FuzzySystem& a, const FuzzySystem& b, const std::string& what) {
  ASSERT_EQ(a.inputs.size(), b.inputs.size()) << what;
  ASSERT_EQ(a.outputs.size(), b.outputs.size()) << what;
  std::vector<double> lo(a.outputs.size(), 1e300), hi(a.outputs.size(), -1e300);
  for (const std::vector<double>& x : grid(a)) {
    std::vector<double> xb(x.size());
    for (std::size_t i = 0; i < x.size(); ++i) {
      const int j = b.input_index(a.inputs[i].name);
      ASSERT_GE(j, 0) << what << ": no input " << a.inputs[i].name;
      xb[static_cast<std::size_t>(j)] = x[i];
    }
    const InferenceReport ra = infer(a, x), rb = infer(b, xb);
    for (std::size_t o = 0; o < a.outputs.size(); ++o) {
      const int k = b.output_index(a.outputs[o].name);
      ASSERT_GE(k, 0) << what << ": no output " << a.outputs[o].name;
      EXPECT_NEAR(ra.outputs[o], rb.outputs[static_cast<std::size_t>(k)], 1e-12)
          << what << ": output " << a.outputs[o].name << " at input " << x[0];
      EXPECT_EQ(ra.defaulted[o], rb.defaulted[static_cast<std::size_t>(k)]) << what;
      lo[o] = std::min(lo[o], ra.outputs[o]);
      hi[o] = std::max(hi[o], ra.outputs[o]);
    }
  }
  for (std::size_t o = 0; o < a.outputs.size(); ++o)
    EXPECT_GT(hi[o] - lo[o], 1e-3)
        << what << ": output " << a.outputs[o].name << " does not vary over the grid";
}

struct Dialect {
  const char* file;      // in the tool's own style
  const char* standard;  // the same rule base in IEC 61131-7 FCL
};

class RuleFileDialect : public ::testing::TestWithParam<Dialect> {};

TEST_P(RuleFileDialect, InfersWhatItsStandardTextInfers) {
  const FuzzySystem dialect = read_rule_file(data(GetParam().file));
  const FuzzySystem standard = read_fcl(data(GetParam().standard));
  expect_same_inference(dialect, standard, GetParam().file);
}

// Written in our FCL, and (for .fis) in .fis again, then read: the same numbers.
TEST_P(RuleFileDialect, WritesBackAndReadsToTheSameInference) {
  const FuzzySystem s = read_rule_file(data(GetParam().file));
  const fs::path dir = neurocloth::test::scratch_dir();
  const std::string stem = fs::path(GetParam().file).stem().string();
  const std::string fcl = (dir / (stem + ".fcl")).string();
  write_rule_file(s, fcl);
  expect_same_inference(s, read_rule_file(fcl), std::string(GetParam().file) + " as FCL");
  if (rule_format(GetParam().file) == RuleFormat::fis) {
    const std::string fis = (dir / (stem + ".fis")).string();
    write_rule_file(s, fis);
    const FuzzySystem back = read_rule_file(fis);
    expect_same_inference(s, back, std::string(GetParam().file) + " as .fis");
    EXPECT_EQ(write_fis(back), write_fis(s)) << "the written .fis is not a fixed point";
  }
}

INSTANTIATE_TEST_SUITE_P(
    Tools, RuleFileDialect,
    ::testing::Values(Dialect{"fuzzylite_drape.fcl", "fuzzylite_drape.standard.fcl"},
                      Dialect{"jfuzzylogic_drape.fcl", "jfuzzylogic_drape.standard.fcl"},
                      Dialect{"matlab_drape.fis", "matlab_drape.standard.fcl"},
                      Dialect{"octave_damping.fis", "octave_damping.standard.fcl"},
                      // MATLAB's default terms, reaching beyond Range.
                      Dialect{"matlab_defaults.fis", "matlab_defaults.standard.fcl"}),
    [](const auto& info) { return fs::path(info.param.file).stem().string(); });

TEST(RuleFile, PicksTheReaderByExtension) {
  EXPECT_EQ(rule_format("a/b.fcl"), RuleFormat::fcl);
  EXPECT_EQ(rule_format("a/b.FIS"), RuleFormat::fis);
  EXPECT_EQ(rule_format("/dev/stdin"), RuleFormat::fcl);  // as before .fis was read
  // A .fis file is read as .fis: its error names a .fis field.
  const fs::path path = neurocloth::test::scratch_dir() / "empty.fis";
  write_file_atomically(path.string(), std::string("[System]\n"));
  try {
    read_rule_file(path.string());
    FAIL() << "an empty .fis was read";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), path.string());
    EXPECT_EQ(e.field(), "[System] Type") << e.what();
  }
}

// A system .fis cannot hold is refused before anything is written.
TEST(RuleFile, RefusesToWriteWhatTheFormatCannotHoldAndLeavesNoFile) {
  const FuzzySystem s = read_rule_file(data("fuzzylite_drape.fcl"));  // COG and COGS outputs
  const fs::path path = neurocloth::test::scratch_dir() / "refused.fis";
  EXPECT_THROW(write_rule_file(s, path.string()), std::invalid_argument);
  EXPECT_FALSE(fs::exists(path));
}

// A scene's "rules" and `neurocloth-cli material` load through FuzzyMaterial.
TEST(RuleFile, MaterialLoadsAFisRuleBase) {
  const FuzzyMaterial m = FuzzyMaterial::load(data("material.fis"));
  // Weighted average of the two rules' constants, light 0.75 and heavy 0.25.
  const DerivedMaterial d = m.derive({{"weight", 0.25}});
  const int k = m.system().output_index("spring_constant");
  ASSERT_GE(k, 0);
  EXPECT_NEAR(d.report.outputs[static_cast<std::size_t>(k)], 0.75 * 50 + 0.25 * 800, 1e-9);
  const int f = m.system().output_index("friction");
  EXPECT_NEAR(d.report.outputs[static_cast<std::size_t>(f)], 0.75 * 0.2 + 0.25 * 0.6, 1e-12);
  EXPECT_NEAR(d.material.friction, 0.75 * 0.2 + 0.25 * 0.6, 1e-12);
}

}  // namespace
}  // namespace neurocloth::fuzzy
