// A material in a fabric lab's units (measured_material.h): the weights it
// gives a grid and a mesh, mass per area at any resolution, the bending
// module it brings, and bad input refused with the field named.
#include "core/scene/measured_material.h"

#include <gtest/gtest.h>

#include <map>
#include <string>
#include <vector>

#include "core/fuzzy/term_degrees.h"
#include "core/io/asset_paths.h"
#include "core/io/input_error.h"
#include "core/scene/fuzzy_material.h"
#include "core/scene/scene.h"
#include "support/input_error_check.h"

namespace neurocloth::measured_material_test {

std::string grid_scene(int n, const std::string& measured, const std::string& extra = "") {
  return R"({"cloth": {"grid": {"rows": )" + std::to_string(n) + R"(, "cols": )" +
         std::to_string(n) + R"(, "spacing": )" + std::to_string(0.3 / (n - 1)) +
         R"(}}, "material": {"measured": )" + measured + "}" + extra + "}";
}
const std::string kDenim =
    R"({"areal_density": 0.32, "tensile_stiffness": 10000, "shear_stiffness": 100,
        "bending_rigidity": 2e-5})";

TEST(MeasuredMaterial, AGridsSheetHasTheMeasuredStiffnessAndMassAtAnySpacing) {
  for (const int n : {5, 11, 31}) {
    const Scene s = parse_scene(grid_scene(n, kDenim), "m.json");
    ASSERT_TRUE(s.measured_material);
    // Shear springs carry G; the structural ones what makes the sheet's
    // free-sided tensile stiffness the measured one.
    EXPECT_DOUBLE_EQ(s.material.shear(), 100.0);
    EXPECT_NEAR(grid_tensile_stiffness(s.material), 10000.0, 1e-8);
    EXPECT_NEAR(cloth_mass(s), 0.32 * 0.3 * 0.3, 1e-12) << n;
    // No bend springs: the bending module bends, with the measured rigidity.
    for (const SpringSpec& spring : s.topology.springs)
      EXPECT_NE(spring.family, SpringFamily::bend);
    ASSERT_EQ(s.modules.size(), 1u);
    ASSERT_TRUE(std::holds_alternative<BendingSpec>(s.modules[0].spec));
    EXPECT_EQ(*std::get<BendingSpec>(s.modules[0].spec).rigidity, 2e-5);
    EXPECT_TRUE(s.material_notes.empty());
  }
}

TEST(MeasuredMaterial, ABendingLengthIsARigidity) {
  const Scene s = parse_scene(
      grid_scene(5, R"({"areal_density": 0.2, "tensile_stiffness": 5000, "bending_length": 0.02})"),
      "m.json");
  EXPECT_NEAR(*s.measured_material->bending_rigidity, 0.2 * 9.80665 * 8e-6, 1e-18);
  EXPECT_DOUBLE_EQ(s.measured_material->shear(), 1875.0);  // unset: 3/8 of the tensile
}

TEST(MeasuredMaterial, ADeclaredBendingModuleTakesTheMeasuredRigidityUnlessItHasOne) {
  const Scene own = parse_scene(
      grid_scene(5, kDenim, R"(, "modules": [{"type": "bending", "rigidity": 1e-4}])"), "m.json");
  ASSERT_EQ(own.modules.size(), 1u);
  EXPECT_EQ(*std::get<BendingSpec>(own.modules[0].spec).rigidity, 1e-4);
  const Scene taken =
      parse_scene(grid_scene(5, kDenim, R"(, "modules": [{"type": "bending"}])"), "m.json");
  EXPECT_EQ(*std::get<BendingSpec>(taken.modules[0].spec).rigidity, 2e-5);
}

TEST(MeasuredMaterial, AMeshsEdgesCarryTheirTrianglesArea) {
  // A right triangle pair: the square's diagonal carries half what a side does.
  ClothTopology t;
  t.rest_positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)};
  t.triangles = {{0, 1, 2}, {0, 2, 3}};
  t.springs = {{0, 1, SpringFamily::structural},
               {0, 2, SpringFamily::structural},
               {1, 3, SpringFamily::bend}};
  const std::vector<double> share = measured_spring_shares(t);
  EXPECT_DOUBLE_EQ(share[0], 0.5);  // one triangle of 1/2 on a side of 1
  EXPECT_DOUBLE_EQ(share[1], 0.5);  // two of 1/2 on a diagonal of length^2 2
  EXPECT_DOUBLE_EQ(share[2], 0.0);  // bend springs carry nothing
}

TEST(MeasuredMaterial, BadInputNamesTheField) {
  using test::expect_input_error;
  auto read = [](const std::string& measured, const std::string& extra = "") {
    return [=] { parse_scene(grid_scene(5, measured, extra), "m.json"); };
  };
  expect_input_error(read(R"({"areal_density": -0.2, "tensile_stiffness": 1000})"), "m.json", 1,
                     "material.measured.areal_density", {"kg/m^2"});
  expect_input_error(read(R"({"areal_density": 6, "tensile_stiffness": 1000})"), "m.json", 1,
                     "material.measured.areal_density");
  expect_input_error(read(R"({"areal_density": 0.2, "tensile_stiffness": 1000,
                               "bending_rigidity": 5})"),
                     "m.json", 2, "material.measured.bending_rigidity");
  expect_input_error(read(R"({"areal_density": 0.2})"), "m.json", 1,
                     "material.measured.tensile_stiffness");
  expect_input_error(read(R"({"areal_density": 0.2, "tensile_stiffness": 1000,
                               "bending_rigidity": 1e-5, "bending_length": 0.02})"),
                     "m.json", 2, "material.measured.bending_length");
  expect_input_error(read(R"({"areal_density": 0.2, "tensile_stiffness": 1000, "colour": 1})"),
                     "m.json", 1, "material.measured.colour");
  // Beside rules or numbers: named.
  expect_input_error(
      [] {
        parse_scene(R"({"cloth": {"grid": {"rows": 3, "cols": 3, "spacing": 0.1}},
          "material": {"measured": {"areal_density": 0.2, "tensile_stiffness": 1000},
                       "spring_constant": 100}})",
                    "m.json");
      },
      "m.json", 3, "material.spring_constant", {"measured"});
  // A bending module with nothing to take.
  expect_input_error(
      [] {
        parse_scene(R"({"cloth": {"grid": {"rows": 3, "cols": 3, "spacing": 0.1}},
          "material": {"spring_constant": 100, "node_mass": 0.01, "viscosity": 0.1},
          "modules": [{"type": "bending"}]})",
                    "m.json");
      },
      "m.json", 0, "modules[0].rigidity");
}

}  // namespace neurocloth::measured_material_test

namespace neurocloth::measured_material_test {

// cloth.fcl's words for mass against fabric practice: light below 135 g/m^2,
// heavy above 270 (4 and 8 oz/yd^2). The terms cross there, and each shipped
// fabric's density is said in the word its class has.
TEST(MeasuredMaterial, ClothFclsLightAndHeavyAreFabricPeoples) {
  const FuzzyMaterial rules = FuzzyMaterial::load(assets_directory() + "/materials/cloth.fcl");
  const fuzzy::LinguisticVariable& mass =
      rules.system().inputs[static_cast<std::size_t>(rules.system().input_index("mass"))];
  auto word = [&](double density) { return fuzzy::term_degrees(mass, density).at(0).term; };
  EXPECT_EQ(word(0.134), "small");
  EXPECT_EQ(word(0.136), "medium");
  EXPECT_EQ(word(0.269), "medium");
  EXPECT_EQ(word(0.271), "big");
  const std::map<std::string, std::string> expected = {{"silk", "small"},    {"polyester", "small"},
                                                       {"cotton", "medium"}, {"wool", "medium"},
                                                       {"denim", "big"},     {"leather", "big"}};
  for (const std::string& name : measured_preset_names()) {
    const MeasuredPreset p = load_measured_preset(name);
    EXPECT_EQ(word(p.measured.areal_density), expected.at(name))
        << name << " at " << p.measured.areal_density
        << " kg/m^2: " << fuzzy::in_words(mass, p.measured.areal_density);
  }
}

TEST(MeasuredMaterial, EveryShippedFabricReadsAndNamesItsSources) {
  const std::vector<std::string> names = measured_preset_names();
  EXPECT_EQ(names,
            (std::vector<std::string>{"cotton", "denim", "leather", "polyester", "silk", "wool"}));
  for (const std::string& name : names) {
    const MeasuredPreset p = load_measured_preset(name);
    EXPECT_FALSE(p.description.empty()) << name;
    EXPECT_TRUE(p.measured.bending_rigidity) << name;
    for (const char* key :
         {"areal_density", "bending_rigidity", "tensile_stiffness", "shear_stiffness"})
      EXPECT_TRUE(p.sources.count(key) && !p.sources.at(key).empty())
          << name << " has no source for " << key;
  }
  EXPECT_THROW(load_measured_preset("velvet"), InputError);
  EXPECT_THROW(load_measured_preset("../scenes/hanging"), InputError);
}

}  // namespace neurocloth::measured_material_test
