#include "learn/fit/fitted_output.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>

#include "chart/loglog_chart.h"
#include "core/io/asset_paths.h"
#include "core/io/input_error.h"
#include "core/scene/element_weights.h"
#include "core/scene/fuzzy_material.h"
#include "support/release_chart_caches.h"
#include "support/scratch_dir.h"

namespace neurocloth {
namespace {
namespace fs = std::filesystem;

std::string read_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

class FittedOutput : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = test::scratch_dir();
    fs::create_directories(dir_ / "in" / "meshes");
    fs::create_directories(dir_ / "out" / "sub");
  }

  // A shipped scene copied to in/, its mesh (if any) beside it under meshes/.
  Scene copied_scene(const std::string& name) const {
    std::string text = read_text(assets_directory() + "/scenes/" + name + ".json");
    const std::string mesh = "../meshes/square.obj";
    if (const auto at = text.find(mesh); at != std::string::npos) {
      fs::copy_file(assets_directory() + "/meshes/square.obj",
                    dir_ / "in" / "meshes" / "square.obj");
      text.replace(at, mesh.size(), "meshes/square.obj");
    }
    std::ofstream(dir_ / "in" / "scene.json") << text;
    return load_scene((dir_ / "in" / "scene.json").string());
  }

  std::string out() const { return (dir_ / "out" / "sub" / "FITTED.json").string(); }

  static FitSummary summary() {
    FitSummary s;
    s.reference = "reference.csv";
    s.optimizer = "lbfgs";
    s.stop_reason = "gradient_small";
    s.loss = 1e-6;
    s.rms_m = 2e-3;
    s.iterations = 7;
    ParameterUncertainty k;
    k.name = "spring_constant";
    k.value = 321;
    k.sd = 3.2;
    k.relative_sd = 0.01;
    ParameterUncertainty c;
    c.name = "viscosity";
    c.value = 0.05;
    c.sd = c.relative_sd = std::nan("");  // not estimated: written without sd
    s.parameters = {k, c};
    return s;
  }

  static FitHistory history() {
    FitHistory h;
    h.columns = {"spring_constant", "viscosity"};
    h.rows = {{0, 1e-2, 0.1, 0.5, {200, 0.05}},
              {1, 1e-4, 0.01, 1.0, {300, 0.05}},
              {2, 1e-6, 0.001, 1.5, {321, 0.05}}};
    return h;
  }

  fs::path dir_;
};

TEST_F(FittedOutput, PerElementWeightsRoundTripThroughTheSideFileAndTheMeshStillResolves) {
  const Scene original = copied_scene("mesh_square");
  FittedModel model{original, {}, {}};
  model.scene.material.spring_constant = 321;
  const ClothNetwork net = original.build_network();
  for (std::size_t s = 0; s < net.spring_count(); ++s) {
    model.weights.stiffness.push_back(100.0 + double(s));
    model.rest_lengths.push_back(net.springs.rest_length[s] * 1.01);
  }
  for (std::size_t i = 0; i < net.node_count(); ++i)
    model.weights.inverse_mass.push_back(1 / (0.01 + 0.001 * double(i)));

  const FittedFiles files = write_fit_outputs(original, model, summary(), history(), out());
  EXPECT_EQ(fs::path(files.weights).filename(), "FITTED.weights.json");
  ASSERT_TRUE(fs::exists(files.weights));

  const Scene fitted = load_scene(out());
  ASSERT_TRUE(fitted.element_weights);
  EXPECT_EQ(fitted.material.spring_constant, 321);
  const ClothNetwork loaded = fitted.build_network();
  const ClothNetwork intended = model.network();
  EXPECT_EQ(loaded.springs.stiffness, intended.springs.stiffness);
  EXPECT_EQ(loaded.springs.damping, intended.springs.damping);
  EXPECT_EQ(loaded.springs.rest_length, intended.springs.rest_length);
  EXPECT_EQ(loaded.masses.inverse_mass, intended.masses.inverse_mass);
  EXPECT_EQ(loaded.node_count(), net.node_count());

  // The mesh path resolves from the new folder; the note says what was fitted.
  const auto doc = nlohmann::json::parse(read_text(out()));
  EXPECT_EQ(doc["cloth"]["mesh"]["obj"], "../../in/meshes/square.obj");
  EXPECT_EQ(doc["element_weights"], "FITTED.weights.json");
  EXPECT_EQ(doc["fitted"]["source_scene"], original.path);
  EXPECT_EQ(doc["fitted"]["parameters"][0]["verdict"], "determined");
  EXPECT_FALSE(doc["fitted"]["parameters"][1].contains("sd"));
  EXPECT_EQ(doc["fitted"]["replaces"]["spring_constant"], 200.0);
  // The file keeps the original's key order.
  EXPECT_LT(read_text(out()).find("\"name\""), read_text(out()).find("\"cloth\""));
}

TEST_F(FittedOutput, AFamilyFitWritesTheMaterialAndNoSideFile) {
  const Scene original = copied_scene("hanging");
  FittedModel model{original, {}, {}};
  model.scene.material.spring_constant = 250;
  model.scene.material.viscosity = 0.07;
  const FittedFiles files = write_fit_outputs(original, model, summary(), history(), out());
  EXPECT_TRUE(files.weights.empty());
  EXPECT_FALSE(fs::exists(dir_ / "out" / "sub" / "FITTED.weights.json"));
  const Scene fitted = load_scene(out());
  EXPECT_FALSE(fitted.element_weights);
  EXPECT_EQ(fitted.material.spring_constant, 250);
  EXPECT_EQ(fitted.material.viscosity, 0.07);
  EXPECT_FALSE(nlohmann::json::parse(read_text(out())).contains("element_weights"));

  EXPECT_EQ(read_text(files.csv).substr(0, read_text(files.csv).find('\n')),
            "iteration,loss,rms_mm,seconds,spring_constant,viscosity");
  EXPECT_NE(read_text(files.csv).find("\n2,1e-06,1,1.5,321,0.05\n"), std::string::npos)
      << read_text(files.csv);
  EXPECT_EQ(read_text(files.png).substr(1, 3), "PNG");
}

TEST_F(FittedOutput, AMaterialInWordsBecomesNumbersAndKeepsItsMassShares) {
  const Scene original = load_scene(assets_directory() + "/scenes/hanging_fuzzy.json");
  ASSERT_TRUE(original.fuzzy_material);
  // What FitProblem gives a numeric fit: the scene with its numbers, and the
  // weights the fit ran on (each node's mass share from the rule base).
  FittedModel model{original, {}, {}};
  model.scene.material.viscosity *= 2;
  ClothNetwork ran = model.scene.build_network();
  model.weights = {ran.springs.stiffness, ran.springs.damping, ran.masses.inverse_mass,
                   ran.masses.friction};
  model.scene.fuzzy_material.reset();
  write_fit_outputs(original, model, summary(), history(), out());
  const Scene fitted = load_scene(out());
  EXPECT_FALSE(fitted.fuzzy_material);
  EXPECT_EQ(fitted.material.viscosity, model.scene.material.viscosity);
  // The rule base gave each node its lumped share of the mass: the side file keeps it.
  ASSERT_TRUE(fitted.element_weights);
  EXPECT_EQ(fitted.build_network().masses.inverse_mass,
            original.build_network().masses.inverse_mass);
  const auto doc = nlohmann::json::parse(read_text(out()));
  EXPECT_NE(doc["fitted"]["replaces"].get<std::string>().find("material in words"),
            std::string::npos);
  EXPECT_FALSE(doc["material"].contains("rules"));
  // What the fit teaches the rule base: its inputs and the fitted outputs.
  EXPECT_EQ(read_text(fitted_file_names(out()).example),
            "# from a fit of " + original.path + " to " + summary().reference +
                "\nelasticity,force,mass,spring_constant,viscosity\n0.3,3,0.2,321,0.05\n");
}

TEST_F(FittedOutput, FittedInputsKeepTheMaterialInWords) {
  const Scene original = load_scene(assets_directory() + "/scenes/hanging_fuzzy.json");
  ASSERT_TRUE(original.fuzzy_material);
  FittedModel model{original, {}, {}};
  model.scene.fuzzy_material->inputs["elasticity"] = 0.61;
  model.scene.material =
      model.scene.fuzzy_material->rules->derive(model.scene.fuzzy_material->inputs).material;
  FitSummary s = summary();
  s.words = {"elasticity 0.61: big 0.58, medium 0.13"};
  const FittedFiles files = write_fit_outputs(original, model, s, history(), out());
  EXPECT_TRUE(files.weights.empty());  // the rule base builds the network as fitted
  EXPECT_TRUE(files.example.empty());  // the words themselves were fitted: nothing to teach
  const Scene fitted = load_scene(out());
  ASSERT_TRUE(fitted.fuzzy_material);
  EXPECT_EQ(fitted.fuzzy_material->inputs, model.scene.fuzzy_material->inputs);
  EXPECT_EQ(fitted.material.spring_constant, model.scene.material.spring_constant);
  EXPECT_NE(fitted.material.spring_constant, original.material.spring_constant);
  EXPECT_EQ(fitted.build_network().masses.inverse_mass,
            original.build_network().masses.inverse_mass);
  const auto doc = nlohmann::json::parse(read_text(out()));
  EXPECT_EQ(doc["fitted"]["in_words"][0], s.words[0]);
}

TEST_F(FittedOutput, FittedModuleParametersArePatchedIntoTheirModule) {
  const Scene original = copied_scene("curtain");
  FittedModel model{original, {}, {}};
  for (ModuleDeclaration& m : model.scene.modules)
    if (auto* air = std::get_if<AirDragSpec>(&m.spec)) air->rate = 0.123;
  write_fit_outputs(original, model, summary(), history(), out());
  const Scene fitted = load_scene(out());
  bool found = false;
  for (const ModuleDeclaration& m : fitted.modules)
    if (const auto* air = std::get_if<AirDragSpec>(&m.spec)) {
      EXPECT_EQ(air->rate, 0.123);
      found = true;
    }
  EXPECT_TRUE(found);
}

TEST_F(FittedOutput, NothingIsWrittenWhenAFittedValueIsNotFinite) {
  const Scene original = copied_scene("hanging");
  FittedModel model{original, {}, {}};
  model.scene.material.spring_constant = std::nan("");
  EXPECT_THROW(write_fit_outputs(original, model, summary(), history(), out()), std::runtime_error);
  EXPECT_TRUE(fs::is_empty(dir_ / "out" / "sub"));
}

TEST_F(FittedOutput, RebasedPathsResolveFromTheNewFolder) {
  copied_scene("mesh_square");
  const std::string from = (dir_ / "in" / "scene.json").string();
  EXPECT_EQ(rebased_path(from, "meshes/square.obj", out()), "../../in/meshes/square.obj");
  EXPECT_EQ(rebased_path(from, "/abs/x.obj", out()), "/abs/x.obj");
  EXPECT_EQ(fitted_file_names("a/b/F.json").csv, "a/b/F.loss.csv");
  EXPECT_EQ(fitted_file_names("a/b/F.json").png, "a/b/F.loss.png");
  EXPECT_EQ(fitted_file_names("F").weights, "F.weights.json");
}

// FITTED.example.csv is for tune-rules, which refuses an input outside its
// RANGE: a scene's input beyond it is written as the clamped value the rule
// base saw (elasticity 5 in cloth.fcl's RANGE 0 .. 1: 1).
TEST_F(FittedOutput, TheTuningExampleHoldsTheInputsTheRuleBaseSaw) {
  Scene scene = load_scene(assets_directory() + "/scenes/hanging_fuzzy.json");
  ASSERT_TRUE(scene.fuzzy_material);
  scene.fuzzy_material->inputs["elasticity"] = 5;
  scene.fuzzy_material->inputs["mass"] = -3;
  const std::optional<std::string> example = tuning_example(scene, summary());
  ASSERT_TRUE(example);
  EXPECT_NE(example->find("\nelasticity,force,mass,spring_constant,viscosity\n1,3,0.02,321,0.05\n"),
            std::string::npos)
      << *example;
}

}  // namespace
}  // namespace neurocloth
