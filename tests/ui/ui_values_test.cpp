// The UI's own copy of the settings: it follows the simulation only when the
// run starts over, so an edit in flight is never pulled back by a status that
// has not caught up with it yet.
#include <gtest/gtest.h>

#include "ui/ui_values.h"

namespace neurocloth {
namespace {

// The names of a scene with one linguistic input and a wind module.
ParameterNames names() {
  ParameterNames n;
  n.inputs = {"mass"};
  n.modules = {"plane", "wind"};
  return n;
}

ParameterId id(const std::string& text) {
  const auto parsed = parse_parameter(text, names());
  EXPECT_TRUE(parsed.has_value()) << text;
  return parsed.value_or(ParameterId{});
}

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
  ASSERT_TRUE(v.assign(id("viscosity"), names(), 0.5));
  v.follow(status_at(0.1, 0.8));  // the command has not been applied yet
  EXPECT_EQ(v.viscosity, 0.5);
}

TEST(UiValues, ResetOrANewSceneStartsOver) {
  UiValues v;
  v.follow(status_at(1.0, 0.8));
  v.assign(id("viscosity"), names(), 0.5);
  v.follow(status_at(0.0, 0.8));  // time went back: a reset
  EXPECT_EQ(v.viscosity, 0.8);
  v.assign(id("viscosity"), names(), 0.5);
  SimulationStatus other = status_at(0.5, 0.3);
  other.scene_path = "other.json";
  v.follow(other);
  EXPECT_EQ(v.viscosity, 0.3);
}

TEST(UiValues, EveryParameterOfTheSceneHasAField) {
  UiValues v;
  v.follow(status_at(0, 0.8));
  for (const ParameterId& p : all_parameters(names()))
    EXPECT_TRUE(v.assign(p, names(), 0.25)) << to_string(p, names());
  EXPECT_EQ(v.inputs[0].second, 0.25);
  EXPECT_EQ(v.wind[1], 0.25);
  EXPECT_FALSE(v.assign(ParameterId::gravity(3), names(), 1));
  EXPECT_FALSE(v.assign(ParameterId::input(1), names(), 1)) << "no second input";
  EXPECT_FALSE(v.assign(ParameterId::module(0, ModuleParameter::velocity, 0), names(), 1))
      << "the plane has no velocity";
}

TEST(UiValues, StatusValueReadsTheSameParameters) {
  SimulationStatus s = status_at(0, 0.8);
  s.gravity = Vec3(0, -9.81, 0);
  EXPECT_EQ(status_value(s, id("viscosity"), names()), 0.8);
  EXPECT_EQ(status_value(s, id("gravity.y"), names()), -9.81);
  EXPECT_EQ(status_value(s, id("input.mass"), names()), 0.2);
  EXPECT_FALSE(status_value(s, id("wind.velocity.x"), names())) << "no wind in the status";
  s.wind = Vec3(1, 2, 3);
  EXPECT_EQ(status_value(s, id("wind.velocity.z"), names()), 3);
}

}  // namespace
}  // namespace neurocloth
