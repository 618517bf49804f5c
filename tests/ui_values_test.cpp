// The UI's own copy of the settings: it follows the simulation only when the
// run starts over, so an edit in flight is never pulled back by a status that
// has not caught up with it yet.
#include <gtest/gtest.h>

#include "ui_values.h"

namespace neurocloth {
namespace {

SimulationStatus status_at(double time, double viscosity) {
  SimulationStatus s;
  s.scene_path = "scene.json";
  s.time = time;
  s.viscosity = viscosity;
  s.material_inputs = {{"mass", 0.2}};
  return s;
}

TEST(UiValues, TakesEverythingFromTheFirstStatus) {
  UiValues v;
  SimulationStatus s = status_at(0, 0.8);
  s.gravity = Vec3(0, -3, 0);
  s.wind = Vec3(1, 2, 3);
  v.follow(s);
  EXPECT_EQ(v.viscosity, 0.8);
  EXPECT_EQ(v.gravity[1], -3);
  EXPECT_TRUE(v.has_wind);
  EXPECT_EQ(v.wind[2], 3);
  EXPECT_STREQ(v.scene_path.data(), "scene.json");
}

TEST(UiValues, AnEditIsNotPulledBackByALaggingStatus) {
  UiValues v;
  v.follow(status_at(0, 0.8));
  ASSERT_TRUE(v.assign("viscosity", 0.5));
  v.follow(status_at(0.1, 0.8));  // the command has not been applied yet
  EXPECT_EQ(v.viscosity, 0.5);
}

TEST(UiValues, ResetOrANewSceneStartsOver) {
  UiValues v;
  v.follow(status_at(1.0, 0.8));
  v.assign("viscosity", 0.5);
  v.follow(status_at(0.0, 0.8));  // time went back: a reset
  EXPECT_EQ(v.viscosity, 0.8);
  v.assign("viscosity", 0.5);
  SimulationStatus other = status_at(0.5, 0.3);
  other.scene_path = "other.json";
  v.follow(other);
  EXPECT_EQ(v.viscosity, 0.3);
}

TEST(UiValues, NamesAreTheSetParameterNames) {
  UiValues v;
  v.follow(status_at(0, 0.8));
  for (const char* name :
       {"viscosity", "friction", "dt", "gravity.x", "gravity.z", "wind.y", "input.mass"})
    EXPECT_TRUE(v.assign(name, 0.25)) << name;
  EXPECT_EQ(v.inputs[0].second, 0.25);
  EXPECT_FALSE(v.assign("gravity.w", 1));
  EXPECT_FALSE(v.assign("input.colour", 1));
  EXPECT_FALSE(v.assign("mass", 1));
}

TEST(UiValues, StatusValueReadsTheSameNames) {
  SimulationStatus s = status_at(0, 0.8);
  s.gravity = Vec3(0, -9.81, 0);
  EXPECT_EQ(status_value(s, "viscosity"), 0.8);
  EXPECT_EQ(status_value(s, "gravity.y"), -9.81);
  EXPECT_EQ(status_value(s, "input.mass"), 0.2);
  EXPECT_FALSE(status_value(s, "wind.x")) << "no wind module";
  EXPECT_FALSE(status_value(s, "nonsense"));
}

}  // namespace
}  // namespace neurocloth
