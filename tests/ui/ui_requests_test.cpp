// What the UI asks of the simulation is checked on the UI side first: a value
// out of range, a scene or a rule base that does not read is refused with the
// reason, and nothing is posted.
#include <gtest/gtest.h>

#include <variant>
#include <vector>

#include "core/io/asset_paths.h"
#include "support/posted_commands.h"
#include "support/scratch_dir.h"
#include "support/test_support.h"
#include "ui/ui_requests.h"

namespace neurocloth {
namespace {

std::string scene_asset(const std::string& name) {
  return assets_directory() + "/scenes/" + name + ".json";
}

TEST(UiRequests, AValueInRangeIsPostedAndMirrored) {
  const SceneInfo scene(load_scene(scene_asset("table_drape")));
  UiValues values;
  test::PostedCommands posted;
  EXPECT_EQ(request_parameter(scene, values, posted.sink(), "viscosity", 0.5), "");
  ASSERT_EQ(posted.commands.size(), 1u);
  const auto& set = std::get<SetParameter>(posted.commands[0]);
  EXPECT_EQ(set.id, ParameterId::of(ParameterId::Kind::viscosity));
  EXPECT_EQ(set.value, 0.5);
  EXPECT_EQ(values.viscosity, 0.5);
}

TEST(UiRequests, AValueOutOfRangeIsRefusedWithItsRange) {
  const SceneInfo scene(load_scene(scene_asset("table_drape")));
  UiValues values;
  values.viscosity = 0.8;
  test::PostedCommands posted;
  const std::string refusal = request_parameter(scene, values, posted.sink(), "viscosity", -3);
  const ParameterRange* range = scene.range(ParameterId::of(ParameterId::Kind::viscosity));
  ASSERT_NE(range, nullptr);
  EXPECT_NE(refusal.find("valid range " + range_text(*range)), std::string::npos) << refusal;
  EXPECT_TRUE(posted.commands.empty());
  EXPECT_EQ(values.viscosity, 0.8) << "the last accepted value stays";
  EXPECT_NE(request_parameter(scene, values, posted.sink(), "viscosity", std::nan("")), "");
}

TEST(UiRequests, AnUnknownParameterNamesTheKnownOnes) {
  const SceneInfo scene(load_scene(scene_asset("table_drape")));
  UiValues values;
  test::PostedCommands posted;
  const std::string refusal = request_parameter(scene, values, posted.sink(), "wind.velocity.x", 1);
  EXPECT_NE(refusal.find("unknown parameter 'wind.velocity.x'"), std::string::npos) << refusal;
  EXPECT_NE(refusal.find("viscosity"), std::string::npos) << refusal;
  EXPECT_TRUE(posted.commands.empty());
}

TEST(UiRequests, ABadSceneIsNamedAndNotPosted) {
  test::PostedCommands posted;
  const std::string error = request_scene("/nonexistent/scene.json", posted.sink());
  EXPECT_NE(error.find("/nonexistent/scene.json"), std::string::npos) << error;
  EXPECT_TRUE(posted.commands.empty());
  EXPECT_EQ(request_scene(scene_asset("hanging"), posted.sink()), "");
  ASSERT_EQ(posted.commands.size(), 1u);
  ASSERT_TRUE(std::holds_alternative<LoadScene>(posted.commands[0]));
  // The scene read here travels with the command: the thread does not read it again.
  const LoadScene& load = std::get<LoadScene>(posted.commands[0]);
  ASSERT_NE(load.scene, nullptr);
  EXPECT_EQ(load.scene->name, "hanging");
}

TEST(UiRequests, RulesNeedALinguisticMaterial) {
  SceneInfo numeric(load_scene(scene_asset("hanging")));
  test::PostedCommands posted;
  EXPECT_NE(request_rules(numeric, assets_directory() + "/materials/cloth.fcl", posted.sink()), "");
  EXPECT_TRUE(posted.commands.empty());

  SceneInfo fuzzy(load_scene(scene_asset("hanging_fuzzy")));
  EXPECT_NE(request_rules(fuzzy, "/nonexistent.fcl", posted.sink()), "");
  EXPECT_TRUE(posted.commands.empty());
  EXPECT_EQ(request_rules(fuzzy, assets_directory() + "/materials/cloth.fcl", posted.sink()), "");
  ASSERT_EQ(posted.commands.size(), 1u);
  ASSERT_TRUE(fuzzy.fuzzy().has_value());
  // The simulation takes the rule base as read here: one read per load.
  EXPECT_EQ(std::get<LoadRules>(posted.commands[0]).rules, fuzzy.fuzzy()->rules());
}

// The scene the window opens first speaks in words: the Material panel shows
// its rule base and input sliders, not "given as numbers".
TEST(UiRequests, TheDefaultSceneHasALinguisticMaterial) {
  const SceneInfo scene(load_scene(scene_asset("table_drape")));
  ASSERT_TRUE(scene.fuzzy().has_value());
  EXPECT_NE(scene.fuzzy()->rules_path().find("cloth.fcl"), std::string::npos);
}

TEST(UiRequests, TheUiSharesTheScenesRuleBase) {
  const Scene scene = test::fuzzy_scene_without_its_rules(test::scratch_dir().string());
  SceneInfo info(scene);  // would throw if it read the rule base again
  ASSERT_TRUE(info.fuzzy().has_value());
  EXPECT_EQ(info.fuzzy()->rules(), scene.fuzzy_material->rules);
  UiValues values;
  values.inputs = {{"mass", 0.2}};
  test::PostedCommands posted;
  EXPECT_EQ(request_parameter(info, values, posted.sink(), "input.mass", 0.7), "");
  EXPECT_EQ(values.inputs[0].second, 0.7);
  EXPECT_GT(info.node_mass(0, values.inputs), 0);
}

}  // namespace
}  // namespace neurocloth
