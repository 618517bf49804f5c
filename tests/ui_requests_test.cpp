// What the UI asks of the simulation is checked on the UI side first: a value
// out of range, a scene or a rule base that does not read is refused with the
// reason, and nothing is posted.
#include <gtest/gtest.h>

#include <variant>
#include <vector>

#include "asset_paths.h"
#include "ui_requests.h"

namespace neurocloth {
namespace {

struct Posted {
  std::vector<SimCommand> commands;
  CommandSink sink() {
    return [this](SimCommand c) { commands.push_back(std::move(c)); };
  }
};

std::string scene_asset(const std::string& name) {
  return assets_directory() + "/scenes/" + name + ".json";
}

TEST(UiRequests, AValueInRangeIsPostedAndMirrored) {
  const SceneInfo scene(load_scene(scene_asset("table_drape")));
  UiValues values;
  Posted posted;
  EXPECT_EQ(request_parameter(scene, values, posted.sink(), "viscosity", 0.5), "");
  ASSERT_EQ(posted.commands.size(), 1u);
  const auto& set = std::get<SetParameter>(posted.commands[0]);
  EXPECT_EQ(set.name, "viscosity");
  EXPECT_EQ(set.value, 0.5);
  EXPECT_EQ(values.viscosity, 0.5);
}

TEST(UiRequests, AValueOutOfRangeIsRefusedWithItsRange) {
  const SceneInfo scene(load_scene(scene_asset("table_drape")));
  UiValues values;
  values.viscosity = 0.8;
  Posted posted;
  const std::string refusal = request_parameter(scene, values, posted.sink(), "viscosity", -3);
  const ParameterRange* range = scene.range("viscosity");
  ASSERT_NE(range, nullptr);
  EXPECT_NE(refusal.find("valid range " + range_text(*range)), std::string::npos) << refusal;
  EXPECT_TRUE(posted.commands.empty());
  EXPECT_EQ(values.viscosity, 0.8) << "the last accepted value stays";
  EXPECT_NE(request_parameter(scene, values, posted.sink(), "viscosity", std::nan("")), "");
}

TEST(UiRequests, AnUnknownParameterNamesTheKnownOnes) {
  const SceneInfo scene(load_scene(scene_asset("table_drape")));
  UiValues values;
  Posted posted;
  const std::string refusal = request_parameter(scene, values, posted.sink(), "wind.x", 1);
  EXPECT_NE(refusal.find("no parameter 'wind.x'"), std::string::npos) << refusal;
  EXPECT_NE(refusal.find("viscosity"), std::string::npos) << refusal;
  EXPECT_TRUE(posted.commands.empty());
}

TEST(UiRequests, ABadSceneIsNamedAndNotPosted) {
  Posted posted;
  const std::string error = request_scene("/nonexistent/scene.json", posted.sink());
  EXPECT_NE(error.find("/nonexistent/scene.json"), std::string::npos) << error;
  EXPECT_TRUE(posted.commands.empty());
  EXPECT_EQ(request_scene(scene_asset("hanging"), posted.sink()), "");
  ASSERT_EQ(posted.commands.size(), 1u);
  EXPECT_TRUE(std::holds_alternative<LoadScene>(posted.commands[0]));
}

TEST(UiRequests, RulesNeedALinguisticMaterial) {
  SceneInfo numeric(load_scene(scene_asset("table_drape")));
  Posted posted;
  EXPECT_NE(request_rules(numeric, assets_directory() + "/materials/cloth.fcl", posted.sink()), "");
  EXPECT_TRUE(posted.commands.empty());

  SceneInfo fuzzy(load_scene(scene_asset("hanging_fuzzy")));
  EXPECT_NE(request_rules(fuzzy, "/nonexistent.fcl", posted.sink()), "");
  EXPECT_TRUE(posted.commands.empty());
  EXPECT_EQ(request_rules(fuzzy, assets_directory() + "/materials/cloth.fcl", posted.sink()), "");
  EXPECT_EQ(posted.commands.size(), 1u);
  EXPECT_TRUE(fuzzy.fuzzy().has_value());
}

}  // namespace
}  // namespace neurocloth
