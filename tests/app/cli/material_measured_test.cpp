// `neurocloth-cli material --measured`: a fabric in lab units shown as the
// network's weights, and bad values refused with the key named.
#include "support/cli_fixture.h"

namespace neurocloth::cli_test {
namespace material_measured {

TEST_F(Cli, MeasuredFabricShowsItsWeightsAndSources) {
  const Outcome r = run({"material", "--measured", "denim", "--spacing", "0.02", "--json"});
  ASSERT_EQ(r.code, kOk) << r.err;
  const json doc = json::parse(r.out);
  EXPECT_EQ(doc.at("fabric"), "denim");
  // The grid's sheet has the measured tensile stiffness; a node its area's mass.
  EXPECT_NEAR(doc.at("grid").at("sheet_tensile_stiffness").get<double>(), 9500.0, 1e-8);
  EXPECT_EQ(doc.at("grid").at("shear_constant").get<double>(), 130.0);
  EXPECT_NEAR(doc.at("grid").at("node_mass").get<double>(), 0.324 * 0.02 * 0.02, 1e-15);
  // KES units and the bending length: 2e-5 N m is 0.204 gf cm^2/cm, c = 18.5 mm.
  EXPECT_NEAR(doc.at("bending").at("rigidity_kes").get<double>(), 0.20394, 1e-5);
  EXPECT_NEAR(doc.at("bending").at("bending_length").get<double>(), 0.018463, 1e-6);
  for (const char* key : {"areal_density", "bending_rigidity", "tensile_stiffness"})
    EXPECT_FALSE(doc.at("sources").at(key).get<std::string>().empty()) << key;
}

TEST_F(Cli, MeasuredValuesFromTheCommandLine) {
  const Outcome r = run({"material", "--measured", "areal_density=0.2", "tensile_stiffness=1e4",
                         "bending_length=0.02"});
  ASSERT_EQ(r.code, kOk) << r.err;
  // B = 0.2 * 9.80665 * 0.02^3 = 1.569e-5 N m.
  EXPECT_NE(r.out.find("rigidity 1.56906e-05 N m"), std::string::npos) << r.out;
  for (const std::vector<std::string>& bad :
       {std::vector<std::string>{"areal_density=-1", "tensile_stiffness=1e4"},
        {"areal_density=0.2"},
        {"areal_density=0.2", "tensile_stiffness=1e4", "colour=3"},
        {"velvet"}}) {
    std::vector<std::string> args = {"material", "--measured"};
    args.insert(args.end(), bad.begin(), bad.end());
    const Outcome e = run(args);
    EXPECT_EQ(e.code, kInputError) << bad[0];
    EXPECT_TRUE(e.out.empty()) << e.out;
  }
  const Outcome e = run({"material", "--measured", "areal_density=-1", "tensile_stiffness=1e4"});
  EXPECT_NE(e.err.find("areal_density"), std::string::npos) << e.err;
}

}  // namespace material_measured
}  // namespace neurocloth::cli_test

namespace neurocloth::cli_test {
namespace material_measured {

// fit --bending-length needs a cantilever scene; nothing is written otherwise.
TEST_F(Cli, FitFromABendingLengthNeedsACantilever) {
  const std::string out = (out_dir() / "fitted.json").string();
  expect_input_error({"fit", assets_directory() + "/scenes/table_drape.json", "--bending-length",
                      "0.02", "--params", "bending.rigidity", "--out", out},
                     {"--bending-length", "no cantilever"});
  // Both a reference and a bending length: a usage error, as any conflict of options.
  const Outcome both = run({"fit", assets_directory() + "/scenes/cantilever.json", "--reference",
                            "x.csv", "--bending-length", "0.02", "--out", out});
  EXPECT_EQ(both.code, kUsage) << both.err;
  EXPECT_NE(both.err.find("--bending-length"), std::string::npos) << both.err;
  EXPECT_TRUE(files_in_out_dir().empty());
}

// simulate reads a cantilever scene's strip as the standard does: chord,
// bending length and rigidity in RESULT.json and on its own line.
TEST_F(Cli, SimulateReadsACantileversBendingLength) {
  // 6 spacings of a 2e-5 N m, 0.32 kg/m^2 strip: 2 bending lengths from the clamp.
  const double c = std::cbrt(2e-5 / (0.32 * 9.81)), h = 2 * c / 6.5;
  const std::string scene =
      write("strip.json",
            R"({"cloth": {"grid": {"rows": 2, "cols": 8, "spacing": )" + std::to_string(h) +
                R"(, "origin": [0, 0.2, 0], "row_direction": [0, 0, 1], "col_direction": [1, 0, 0]},
            "springs": ["structural", "shear"], "pins": [[0, 0], [0, 1], [1, 0], [1, 1]]},
          "material": {"measured": {"areal_density": 0.32, "tensile_stiffness": 1000,
                                    "bending_rigidity": 2e-5, "damping": 0}},
          "gravity": [0, -9.81, 0], "modules": [{"type": "air_drag", "rate": 40}],
          "solver": {"integrator": "network", "dt": 0.01, "adaptive": true}})");
  const Outcome r = run({"simulate", scene, "--seconds", "0.4", "--out", result_path()});
  ASSERT_EQ(r.code, kOk) << r.err;
  EXPECT_NE(r.out.find("cantilever: chord"), std::string::npos) << r.out;
  const json doc = read_result();
  const json& cant = doc.at("cantilever");
  // Measured: 40.95 degrees (the elastica's 41.49), a bending length of 18.74 mm of 18.54.
  EXPECT_NEAR(cant.at("chord_angle").get<double>(), 41.49, 0.6);
  EXPECT_NEAR(cant.at("bending_length").get<double>(), c, 0.0003);
  EXPECT_NEAR(cant.at("bending_rigidity").get<double>(), 2e-5, 0.1e-5);
  EXPECT_NEAR(cant.at("overhang").get<double>(), 2 * c, 1e-6);
  // The strip has shear springs: nothing it cannot represent, so no note.
  EXPECT_EQ(r.out.find("note:"), std::string::npos) << r.out;
  // Without them its shear stiffness is 0, and simulate says so.
  std::string no_shear = read_text(scene);
  no_shear.replace(no_shear.find(R"("structural", "shear")"), 21, R"("structural")");
  const Outcome n = run(
      {"simulate", write("no_shear.json", no_shear), "--seconds", "0.01", "--out", result_path()});
  ASSERT_EQ(n.code, kOk) << n.err;
  EXPECT_NE(n.out.find("note: the grid has no shear springs"), std::string::npos) << n.out;
  // A scene that is no cantilever has no reading.
  ASSERT_EQ(run({"simulate", assets_directory() + "/scenes/hanging.json", "--seconds", "0.01",
                 "--out", result_path()})
                .code,
            kOk);
  EXPECT_FALSE(read_result().contains("cantilever"));
}

}  // namespace material_measured
}  // namespace neurocloth::cli_test
