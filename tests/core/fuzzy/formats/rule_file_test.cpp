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
#include "core/io/asset_paths.h"
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

// Inputs on a grid over each input's range (steps + 1 points each, ends included).
std::vector<std::vector<double>> grid(const FuzzySystem& s, int steps) {
  std::vector<std::vector<double>> points{{}};
  for (const LinguisticVariable& v : s.inputs) {
    std::vector<std::vector<double>> next;
    for (const auto& p : points)
      for (int k = 0; k <= steps; ++k) {
        auto q = p;
        q.push_back(v.min + (v.max - v.min) * k / steps);
        next.push_back(q);
      }
    points = next;
  }
  return points;
}

// Same outputs (to `tolerance`) and same "no rule fired" flags at every grid
// point of `a`'s inputs; `b` names its inputs and outputs alike, maybe in
// another order. The outputs must vary over the grid, so agreement means
// something.
void expect_same_inference(const FuzzySystem& a, const FuzzySystem& b, const std::string& what,
                           double tolerance = 1e-12, int steps = 6) {
  ASSERT_EQ(a.inputs.size(), b.inputs.size()) << what;
  ASSERT_EQ(a.outputs.size(), b.outputs.size()) << what;
  std::vector<double> lo(a.outputs.size(), 1e300), hi(a.outputs.size(), -1e300);
  for (const std::vector<double>& x : grid(a, steps)) {
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
      EXPECT_NEAR(ra.outputs[o], rb.outputs[static_cast<std::size_t>(k)], tolerance)
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

// fuzzylite's FisExporter (6.0) output of each FCL rule base here that it
// exports without changing what it infers: the shipped material rule base and
// the test data's, point lists included (as 'discretemf'). Each .fis is written
// by hand as FisExporter writes it (its '#Code' line, Version=6.0, every number
// fixed to fuzzylite's decimals, rule entries as "1.000 -2.050 , 3.000", one
// '# RuleBlock' line per block when there are several, Type='hybrid' when
// Mamdani and Sugeno outputs meet). cloth is written as `-decimals 5` writes
// it: at the default 3, node_mass's coefficient 0.0025 would become 0.003.
// fuzzylite_drape.fcl is left out: FisExporter would give both its blocks the
// first one's AND/OR and keep one of the two conclusions its RULE 3 draws on
// damping, so its .fis would infer other numbers. No DEFAULT is written; the
// grid meets no input where one of these systems leaves an output unset.
struct FuzzyliteExport {
  const char* name;
  std::string fcl;   // the rule base, as we read it
  const char* fis;   // FisExporter's text of it, in tests/data/rule_files
  double tolerance;  // on every output: 0, as measured (the same bits)
};

void PrintTo(const FuzzyliteExport& e, std::ostream* os) {
  *os << e.fcl << " as " << e.fis;
}

class FuzzyliteFisExport : public ::testing::TestWithParam<FuzzyliteExport> {};

TEST_P(FuzzyliteFisExport, InfersWhatTheFclInfers) {
  const FuzzySystem fcl = read_fcl(GetParam().fcl);
  const FuzzySystem fis = read_rule_file(data(GetParam().fis));
  // 11 points per input: every term's slopes are sampled (cloth's 1331
  // inputs took 7.5 s on a loaded 2-core machine).
  expect_same_inference(fcl, fis, GetParam().fis, GetParam().tolerance, 10);
}

// What fuzzylite wrote, written back by write_fis and read again: the same
// numbers, and a fixed point.
TEST_P(FuzzyliteFisExport, WritesBackAndReadsToTheSameInference) {
  const FuzzySystem fis = read_rule_file(data(GetParam().fis));
  const std::string text = write_fis(fis);
  const FuzzySystem back = parse_fis(text, "written.fis");
  expect_same_inference(fis, back, std::string(GetParam().fis) + " written back");
  EXPECT_EQ(write_fis(back), text) << "the written .fis is not a fixed point";
}

INSTANTIATE_TEST_SUITE_P(
    Fcl, FuzzyliteFisExport,
    ::testing::Values(FuzzyliteExport{"cloth", assets_directory() + "/materials/cloth.fcl",
                                      "cloth.fuzzylite.fis", 0.0},
                      FuzzyliteExport{"jfuzzylogic_drape", data("jfuzzylogic_drape.fcl"),
                                      "jfuzzylogic_drape.fuzzylite.fis", 0.0},
                      FuzzyliteExport{"jfuzzylogic_drape_standard",
                                      data("jfuzzylogic_drape.standard.fcl"),
                                      "jfuzzylogic_drape.fuzzylite.fis", 0.0},
                      FuzzyliteExport{"matlab_defaults", data("matlab_defaults.standard.fcl"),
                                      "matlab_defaults.fuzzylite.fis", 0.0},
                      FuzzyliteExport{"matlab_drape", data("matlab_drape.standard.fcl"),
                                      "matlab_drape.fuzzylite.fis", 0.0},
                      FuzzyliteExport{"octave_damping", data("octave_damping.standard.fcl"),
                                      "octave_damping.fuzzylite.fis", 0.0}),
    [](const auto& info) { return std::string(info.param.name); });

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
  // Two rule blocks with different AND and OR, which one [System] cannot say.
  const FuzzySystem s = read_rule_file(data("fuzzylite_drape.fcl"));
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
