// Pinned nodes following a path: keyframes and oscillation, positions and
// velocities at each step's end, and the cloth carried along.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/scene/scene.h"
#include "support/scene_builder.h"
#include "support/test_support.h"

namespace neurocloth {
namespace {

std::string hanger(const std::string& pin_motion) {
  return test::SceneBuilder(6, 6, 0.1)
      .origin(Vec3(0, 1, 0))
      .hanging()
      .pins({{0, 0}, {0, 5}})
      .material(200.0, 0.01, 0.05)
      .modules("[" + pin_motion + "]")
      .text();
}

TEST(PinMotion, KeyframesMoveThePinsAndSetTheirVelocity) {
  const Scene scene = parse_scene(hanger(R"({"type": "pin_motion", "keyframes": [
      {"t": 0, "offset": [0, 0, 0]}, {"t": 1, "offset": [0.5, 0, 0]},
      {"t": 2, "offset": [0.5, 0.2, 0]}]})"),
                                  "t.json");
  Simulation sim = scene.make_simulation();
  sim.advance(0.5);
  EXPECT_NEAR(sim.state().position(0).x(), 0.25, 1e-12);
  EXPECT_NEAR(sim.state().position(5).x(), 0.5 + 0.25, 1e-12);
  EXPECT_NEAR(sim.state().velocity(0).x(), 0.5, 1e-12);
  sim.advance(1.0);  // t = 1.5: second segment, moving up
  EXPECT_NEAR(sim.state().position(0).y(), 1.1, 1e-12);
  EXPECT_NEAR(sim.state().velocity(0).y(), 0.2, 1e-12);
  EXPECT_NEAR(sim.state().velocity(0).x(), 0.0, 1e-12);
  sim.advance(1.0);  // held after the last key, at rest
  EXPECT_NEAR(sim.state().position(0).x(), 0.5, 1e-12);
  EXPECT_NEAR(sim.state().position(0).y(), 1.2, 1e-12);
  EXPECT_EQ(sim.state().velocity(0), Vec3(0, 0, 0));
  // The cloth came along: its lowest row is well to the right of where it hung.
  EXPECT_GT(sim.state().position(33).x(), 0.5);
}

TEST(PinMotion, OscillationFollowsTheSine) {
  Simulation sim = parse_scene(hanger(R"({"type": "pin_motion", "nodes": [[0, 0]],
      "amplitude": [0, 0, 0.1], "frequency": 2})"),
                               "t.json")
                       .make_simulation();
  const double two_pi = 6.283185307179586;
  for (double t : {0.1, 0.3, 0.77}) {
    sim.advance(t - sim.time());
    EXPECT_NEAR(sim.state().position(0).z(), 0.1 * std::sin(two_pi * 2 * t), 1e-9) << t;
    EXPECT_NEAR(sim.state().velocity(0).z(), 0.1 * two_pi * 2 * std::cos(two_pi * 2 * t), 1e-9);
  }
  EXPECT_EQ(sim.state().position(5), Vec3(0.5, 1, 0));  // not listed: stays put
}

TEST(PinMotion, ItsNodesArePinned) {
  const Scene scene = parse_scene(hanger(R"({"type": "pin_motion", "nodes": [[2, 3]],
      "amplitude": [0, 0, 0.1], "frequency": 1})"),
                                  "t.json");
  EXPECT_EQ(scene.pins, (std::vector<int>{0, 5, 15}));
  EXPECT_TRUE(scene.build_network().masses.pinned(15));
}

TEST(PinMotion, EveryIntegratorCarriesTheCloth) {
  for (const char* integrator : {"network", "verlet", "rk4", "implicit_euler"}) {
    SCOPED_TRACE(integrator);
    Scene scene = parse_scene(hanger(R"({"type": "pin_motion", "keyframes": [
        {"t": 0, "offset": [0, 0, 0]}, {"t": 1, "offset": [0.3, 0, 0]}]})"),
                              "t.json");
    scene.solver.integrator = *parse_integrator(integrator);
    Simulation sim = scene.make_simulation();
    sim.advance(2.0);
    ASSERT_EQ(sim.status(), RunStatus::ok);
    EXPECT_NEAR(sim.state().position(0).x(), 0.3, 1e-12);
    EXPECT_GT(sim.state().position(33).x(), 0.3 + 0.2);  // hanging under the moved pins
  }
}

}  // namespace
}  // namespace neurocloth
