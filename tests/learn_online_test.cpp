// The paper's online adaptation: weights adapted window by window while the
// reference streams in (truncated back-propagation through time).
#include <gtest/gtest.h>

#include <cmath>

#include "online_adaptation.h"
#include "scene_builder.h"

namespace neurocloth {
namespace {

using test::SceneBuilder;

Scene cloth(double k) {
  SceneBuilder b(6, 6, 0.05);
  b.hanging().pins(nlohmann::json::array({{0, 0}, {0, 5}})).material(k, 0.005, 0.05);
  b.set("/material/shear_constant", 20.0).set("/material/bend_constant", 4.0);
  b.solver("network", 0.001);
  return b.parse();
}

ReferenceMotion record(const Scene& scene, double seconds) {
  Simulation sim = scene.make_simulation();
  ReferenceMotion ref;
  while (sim.time() < seconds - 1e-9) {
    EXPECT_EQ(sim.advance(0.005), RunStatus::ok);
    ReferenceFrame f;
    f.time = sim.time();
    for (std::size_t i = 0; i < sim.state().size(); ++i) {
      f.nodes.push_back(static_cast<std::int32_t>(i));
      f.positions.push_back(sim.state().position(i));
    }
    ref.frames.push_back(f);
  }
  return ref;
}

// From a spring constant 3x too high the online fit walks to the true one while
// the cloth runs. (The cloth runs free from its own state, so the windows'
// error also holds the drift gathered while the weight was wrong: it is printed,
// not asserted; docs/learning.md.)
TEST(LearnOnline, TracksTheSpringConstantWhileTheReferencePlays) {
  const double k = 100;
  const ReferenceMotion ref = record(cloth(k), 1.0);
  FitSettings s;
  s.params = {"spring_constant"};
  FitProblem problem(cloth(3 * k), ref, s);
  OnlineAdaptation online(problem, {20, 0.1});
  double first_rms = -1, last_rms = 0;
  int updates = 0;
  while (!online.done()) {
    const OnlineAdaptation::Update u = online.advance();
    ASSERT_TRUE(std::isfinite(u.loss));
    if (!u.updated) continue;
    ++updates;
    if (first_rms < 0) first_rms = u.rms_m;
    last_rms = u.rms_m;
  }
  const double fitted = std::exp(online.theta()[0]);
  std::printf("  online: %d updates, k %.4g (true %g), window RMS %.3g mm -> %.3g mm\n", updates,
              fitted, k, first_rms * 1e3, last_rms * 1e3);
  EXPECT_EQ(updates, 50);
  EXPECT_NEAR(fitted, k, 0.1 * k);
}

TEST(LearnOnline, RefusesAWindowOfNoStepsAndABadRate) {
  const ReferenceMotion ref = record(cloth(100), 0.05);
  FitProblem problem(cloth(100), ref, FitSettings{});
  EXPECT_THROW(OnlineAdaptation(problem, {0, 0.1}), std::invalid_argument);
  EXPECT_THROW(OnlineAdaptation(problem, {10, 0}), std::invalid_argument);
  EXPECT_THROW(OnlineAdaptation(problem, {10, std::nan("")}), std::invalid_argument);
}

}  // namespace
}  // namespace neurocloth
