#include "core/scene/element_weights.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "core/io/asset_paths.h"
#include "core/io/input_error.h"
#include "core/scene/scene.h"
#include "support/scratch_dir.h"

namespace neurocloth {
namespace {
namespace fs = std::filesystem;

// The hanging scene with a side file: written from its own network, then
// spoiled by `spoil` before loading.
class ElementWeightsFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = test::scratch_dir();
    scene_ = load_scene(assets_directory() + "/scenes/mesh_square.json");
    doc_ = element_weights_json(scene_.build_network(), scene_.topology);
  }

  // Loads a copy of mesh_square naming the side file; the InputError's text.
  std::string load_error() const {
    std::ofstream(dir_ / "w.json") << doc_.dump(1);
    nlohmann::json scene =
        nlohmann::json::parse(std::ifstream(assets_directory() + "/scenes/mesh_square.json"));
    scene["cloth"]["mesh"]["obj"] = assets_directory() + "/meshes/square.obj";
    scene["element_weights"] = "w.json";
    std::ofstream(dir_ / "scene.json") << scene.dump(1);
    try {
      load_scene((dir_ / "scene.json").string());
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("w.json"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("element_weights"), std::string::npos) << e.what();
      return e.what();
    }
    return "";
  }

  fs::path dir_;
  Scene scene_;
  nlohmann::json doc_;
};

TEST_F(ElementWeightsFile, TheNetworksOwnWeightsLoadBackUnchanged) {
  EXPECT_EQ(load_error(), "");
  const Scene s = load_scene((dir_ / "scene.json").string());
  ASSERT_TRUE(s.element_weights);
  const ClothNetwork a = s.build_network(), b = scene_.build_network();
  EXPECT_EQ(a.springs.stiffness, b.springs.stiffness);
  EXPECT_EQ(a.masses.inverse_mass, b.masses.inverse_mass);
}

TEST_F(ElementWeightsFile, AnUnknownSpringIsNamed) {
  doc_["springs"][3]["a"] = 0;
  doc_["springs"][3]["b"] = 8;  // opposite corners: no spring joins them
  const std::string e = load_error();
  EXPECT_NE(e.find("springs[3]"), std::string::npos) << e;
  EXPECT_NE(e.find("no structural spring between vertices 0 and 8"), std::string::npos) << e;
}

TEST_F(ElementWeightsFile, ASpringListedTwiceIsNamed) {
  doc_["springs"][1] = doc_["springs"][0];
  const std::string e = load_error();
  EXPECT_NE(e.find("springs[1]"), std::string::npos) << e;
  EXPECT_NE(e.find("more than once"), std::string::npos) << e;
}

TEST_F(ElementWeightsFile, TheWrongCountIsNamed) {
  doc_["springs"].erase(doc_["springs"].size() - 1);
  EXPECT_NE(load_error().find("field 'springs'"), std::string::npos);
  SetUp();
  doc_["node_mass"].push_back(0.01);
  EXPECT_NE(load_error().find("node_mass"), std::string::npos);
}

TEST_F(ElementWeightsFile, NonPositiveAndNonNumericValuesAreRefused) {
  doc_["node_mass"][4] = 0;
  EXPECT_NE(load_error().find("node_mass[4]"), std::string::npos);
  SetUp();
  doc_["springs"][2]["stiffness"] = -1;
  EXPECT_NE(load_error().find("springs[2].stiffness"), std::string::npos);
  SetUp();
  doc_["springs"][2]["damping"] = "a lot";
  EXPECT_NE(load_error().find("springs[2].damping"), std::string::npos);
}

TEST_F(ElementWeightsFile, AMissingSideFileIsNamed) {
  std::ofstream(dir_ / "scene.json")
      << R"({"cloth": {"grid": {"rows": 2, "cols": 2, "spacing": 0.1}},
            "material": {"spring_constant": 1, "node_mass": 1, "viscosity": 0},
            "element_weights": "missing.json"})";
  try {
    load_scene((dir_ / "scene.json").string());
    FAIL() << "loaded";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("missing.json"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace neurocloth
