// The solver block's named choices in a scene file: the integrator and the
// springs' precision and damping, and the error that names the field and the valid values.
#include <gtest/gtest.h>

#include <string>

#include "core/io/input_error.h"
#include "core/scene/scene.h"
#include "support/scene_test_support.h"
#include "support/test_support.h"

namespace neurocloth {
namespace {
using test::expect_names;
using test::grid_scene;
using test::line_of;
using test::parse_error;
using test::scratch_path;

TEST(SceneFields, UnknownIntegratorListsValidNames) {
  const std::string path = scratch_path("integrator.json");
  const std::string text = grid_scene().set("/solver/integrator", "leapfrog").text();
  const auto e = parse_error(text, path);
  ASSERT_TRUE(e);
  expect_names(*e, path, "solver.integrator", line_of(text, "\"integrator\""));
  const std::string what = e->what();
  EXPECT_NE(what.find("leapfrog"), std::string::npos) << what;
  for (const char* name : {"network", "explicit_euler", "verlet", "rk4", "implicit_euler"})
    EXPECT_NE(what.find(name), std::string::npos) << name << " missing from: " << what;
}

TEST(SceneFields, PrecisionIsDoubleUnlessTheSceneSaysFloat) {
  EXPECT_EQ(parse_scene(grid_scene().text(), scratch_path("p0.json")).solver.precision,
            SpringPrecision::float64);
  const Scene f =
      parse_scene(grid_scene().set("/solver/precision", "float").text(), scratch_path("p1.json"));
  EXPECT_EQ(f.solver.precision, SpringPrecision::float32);
}

TEST(SceneFields, UnknownPrecisionListsValidNames) {
  const std::string path = scratch_path("precision.json");
  const std::string text = grid_scene().set("/solver/precision", "half").text();
  const auto e = parse_error(text, path);
  ASSERT_TRUE(e);
  expect_names(*e, path, "solver.precision", line_of(text, "\"precision\""));
  const std::string what = e->what();
  for (const char* name : {"half", "double", "float"})
    EXPECT_NE(what.find(name), std::string::npos) << name << " missing from: " << what;
}

// The implicit integrators linearise the springs in double: float is refused there, by name.
TEST(SceneFields, FloatPrecisionIsRefusedForTheImplicitIntegrators) {
  for (const char* integrator : {"implicit_euler", "projective"}) {
    const std::string path = scratch_path(std::string("precision_") + integrator + ".json");
    const std::string text =
        grid_scene().set("/solver/integrator", integrator).set("/solver/precision", "float").text();
    const auto e = parse_error(text, path);
    ASSERT_TRUE(e) << integrator;
    expect_names(*e, path, "solver.precision", line_of(text, "\"precision\""));
    EXPECT_NE(std::string(e->what()).find(integrator), std::string::npos) << e->what();
  }
}

TEST(SceneFields, DampingIsExplicitUnlessTheSceneSaysImplicit) {
  EXPECT_EQ(parse_scene(grid_scene().text(), scratch_path("d0.json")).solver.damping,
            DampingMode::explicit_force);
  const Scene s =
      parse_scene(grid_scene().set("/solver/damping", "implicit").text(), scratch_path("d1.json"));
  EXPECT_EQ(s.solver.damping, DampingMode::implicit_springwise);
}

TEST(SceneFields, UnknownDampingListsValidNamesAndImplicitIsForTheNetworkOnly) {
  const std::string path = scratch_path("damping.json");
  const std::string text = grid_scene().set("/solver/damping", "viscous").text();
  const auto e = parse_error(text, path);
  ASSERT_TRUE(e);
  expect_names(*e, path, "solver.damping", line_of(text, "\"damping\""));
  for (const char* name : {"viscous", "explicit", "implicit"})
    EXPECT_NE(std::string(e->what()).find(name), std::string::npos) << e->what();
  const std::string rk4_path = scratch_path("damping_rk4.json");
  const std::string rk4 =
      grid_scene().set("/solver/integrator", "rk4").set("/solver/damping", "implicit").text();
  const auto refused = parse_error(rk4, rk4_path);
  ASSERT_TRUE(refused);
  expect_names(*refused, rk4_path, "solver.damping", line_of(rk4, "\"damping\""));
  EXPECT_NE(std::string(refused->what()).find("rk4"), std::string::npos) << refused->what();
}

}  // namespace
}  // namespace neurocloth
