// Parameter ids: text is read once, against a scene's names, and written back
// the same way; a name that is not there is refused with the text quoted.
#include "core/network/parameter_id.h"

#include <gtest/gtest.h>

#include "support/test_support.h"

namespace neurocloth {
namespace {

using test::contains;

// Two wind modules, so that the second needs its index in text.
ParameterNames two_winds() {
  ParameterNames names;
  names.inputs = {"elasticity", "force", "mass"};
  names.modules = {"plane", "wind", "air_drag", "wind"};
  return names;
}

TEST(ParameterId, EveryParameterRoundTripsThroughText) {
  for (const ParameterNames& names :
       {ParameterNames{}, parameter_names(test::asset_scene("flag")),
        parameter_names(test::asset_scene("hanging_fuzzy")), two_winds()}) {
    const std::vector<ParameterId> ids = all_parameters(names);
    for (const ParameterId& id : ids) {
      const std::string text = to_string(id, names);
      const auto back = parse_parameter(text, names);
      ASSERT_TRUE(back.has_value()) << text;
      EXPECT_EQ(*back, id) << text;
    }
    for (std::size_t a = 0; a < ids.size(); ++a)  // one text per id
      for (std::size_t b = a + 1; b < ids.size(); ++b)
        EXPECT_NE(to_string(ids[a], names), to_string(ids[b], names));
  }
}

TEST(ParameterId, NamesSayWhatTheyAre) {
  const ParameterNames names = two_winds();
  using Kind = ParameterId::Kind;
  EXPECT_EQ(parse_parameter("viscosity", names), ParameterId::of(Kind::viscosity));
  EXPECT_EQ(parse_parameter("dt", names), ParameterId::of(Kind::dt));
  EXPECT_EQ(parse_parameter("gravity.y", names), ParameterId::gravity(1));
  EXPECT_EQ(parse_parameter("input.mass", names), ParameterId::input(2));  // sorted by name
  EXPECT_EQ(parse_parameter("wind.velocity.z", names),
            ParameterId::module(1, ModuleParameter::velocity, 2));
  EXPECT_EQ(parse_parameter("wind[1].velocity.x", names),
            ParameterId::module(3, ModuleParameter::velocity, 0));
}

TEST(ParameterId, ABadNameIsRefusedWithTheTextQuoted) {
  const ParameterNames names = parameter_names(test::asset_scene("flag"));
  for (const char* bad :
       {"viscosty", "gravity.w", "gravity", "gravity.x.y", "input.mass", "wind.x", "wind.density.x",
        "wind[1].velocity.x", "plane.velocity.x", "", "VISCOSITY", " viscosity"}) {
    std::string why;
    EXPECT_FALSE(parse_parameter(bad, names, &why).has_value()) << bad;
    EXPECT_TRUE(contains(why, std::string("unknown parameter '") + bad + "'")) << why;
    EXPECT_TRUE(contains(why, "wind.velocity.x")) << "lists what the scene has: " << why;
  }
  EXPECT_FALSE(parse_parameter("input.mass", ParameterNames{}).has_value()) << "no rule base";
}

TEST(ParameterId, FieldsAKindDoesNotUseTakeNoPartInEquality) {
  using Kind = ParameterId::Kind;
  EXPECT_EQ((ParameterId{Kind::gravity, 0, 3, ModuleParameter::velocity}), ParameterId::gravity(0));
  EXPECT_EQ((ParameterId{Kind::dt, 2, 1, ModuleParameter::velocity}), ParameterId::of(Kind::dt));
  EXPECT_EQ((ParameterId{Kind::input, 2, 1, ModuleParameter::velocity}), ParameterId::input(1));
  EXPECT_NE(ParameterId::gravity(0), ParameterId::gravity(1));
  EXPECT_NE(ParameterId::input(0), ParameterId::input(1));
  EXPECT_NE(ParameterId::module(1, ModuleParameter::velocity, 0),
            ParameterId::module(2, ModuleParameter::velocity, 0));
}

TEST(ParameterId, AnIdTheNamesLackIsWrittenButNeverParsed) {
  const ParameterNames names = parameter_names(test::asset_scene("hanging"));
  const ParameterId input = ParameterId::input(7);
  const ParameterId module = ParameterId::module(2, ModuleParameter::velocity, 0);
  EXPECT_EQ(to_string(input, names), "input#7");
  EXPECT_EQ(to_string(module, names), "module#2");
  EXPECT_FALSE(parse_parameter(to_string(input, names), names).has_value());
  EXPECT_FALSE(parse_parameter(to_string(module, names), names).has_value());
}

}  // namespace
}  // namespace neurocloth
