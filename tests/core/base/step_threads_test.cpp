// The step split over threads (step_threads.h) gives the very bits one thread
// gives: every integrator, on scenes with force and constraint modules,
// resized to cloths large enough to be split. Threads only: speed is measured
// by `neurocloth-cli bench --threads N`, never here.
#include "core/base/step_threads.h"

#include <gtest/gtest.h>

#include <atomic>
#include <string>
#include <vector>

#include "core/io/asset_paths.h"
#include "core/network/cloth_state.h"
#include "core/scene/scene.h"

namespace neurocloth {
namespace {

Simulation run(Scene scene, IntegratorKind integrator, int threads, double seconds) {
  scene.solver.integrator = integrator;
  scene.solver.threads = threads;
  Simulation sim = scene.make_simulation();
  sim.advance(seconds);
  return sim;
}

// A shipped scene file resized to n x n.
Scene shipped(const std::string& file, int n) {
  return resized_grid(load_scene(assets_directory() + "/scenes/" + file), n);
}

TEST(StepThreads, EveryPartRunsOnceAndTheCallerWaitsForAll) {
  StepThreads team(3);
  ASSERT_EQ(team.size(), 3);
  std::vector<std::atomic<int>> calls(3);
  for (int round = 0; round < 200; ++round)
    team.run([&](int part) { calls[static_cast<std::size_t>(part)].fetch_add(1); });
  for (const auto& c : calls)
    EXPECT_EQ(c.load(), 200);
}

TEST(StepThreads, PartsCoverTheNodesOnceOnCacheLineBounds) {
  for (std::size_t nodes : {4096u, 4099u, 16384u, 16641u})
    for (int parts : {1, 2, 3, 4}) {
      EXPECT_EQ(part_begin(nodes, 0, parts), 0u);
      EXPECT_EQ(part_begin(nodes, parts, parts), nodes);
      for (int p = 1; p < parts; ++p) {
        EXPECT_EQ(part_begin(nodes, p, parts) % 8, 0u);
        EXPECT_LE(part_begin(nodes, p - 1, parts), part_begin(nodes, p, parts));
      }
    }
}

class ThreadedStep : public ::testing::TestWithParam<IntegratorKind> {};

// The flag (wind, a force module) and the curtain (air drag, pins that move,
// a strain limit) at 64 x 64, the smallest cloth that is split; 2 and 3
// threads (an odd split crosses rows mid-row, the shear and bend runs at other
// places than an even one). Frames of 1/60 s in stable substeps.
TEST_P(ThreadedStep, IsBitIdenticalToOneThread) {
  for (const char* file : {"flag.json", "curtain.json"}) {
    Scene scene = shipped(file, 64);
    ASSERT_GE(scene.topology.rest_positions.size(), kMinThreadedNodes);
    ASSERT_FALSE(scene.modules.empty());
    scene.solver.adaptive = false;
    scene.solver.dt = 1.0 / 60;
    scene.solver.substep_above_cap = true;
    const double seconds = 2 * scene.solver.dt;
    const Simulation one = run(scene, GetParam(), 1, seconds);
    ASSERT_EQ(one.status(), RunStatus::ok) << file;
    for (int threads : {2, 3}) {
      const Simulation many = run(scene, GetParam(), threads, seconds);
      EXPECT_EQ(many.steps(), one.steps()) << file << ", " << threads << " threads";
      EXPECT_TRUE(same_bits(many.state(), one.state())) << file << ", " << threads << " threads";
    }
  }
}

// External forces (the copy path of a force evaluation, at nodes on both sides
// of the split), the adaptive step (forces at trial states), and a copy of a
// threaded simulation continuing on a team of its own.
TEST_P(ThreadedStep, AdaptiveWithExternalForcesAndACopyAgree) {
  Scene scene = shipped("table_drape.json", 64);
  scene.solver.integrator = GetParam();
  scene.solver.adaptive = !iterates_per_step(GetParam());  // they take fixed steps only
  scene.solver.dt = 1.0 / 240;
  Simulation one = scene.make_simulation();
  scene.solver.threads = 2;
  Simulation two = scene.make_simulation();
  for (Simulation* s : {&one, &two})
    for (std::size_t node : {std::size_t{5}, std::size_t{2047}, std::size_t{2048}})
      s->set_external_force(node, Vec3(0.01, 0.02, -0.01));
  one.advance(2 * scene.solver.dt);
  two.advance(scene.solver.dt);
  Simulation copy = two;
  copy.advance(scene.solver.dt);
  two.advance(scene.solver.dt);
  ASSERT_GT(one.steps(), 0);
  EXPECT_TRUE(same_bits(two.state(), one.state()));
  EXPECT_TRUE(same_bits(copy.state(), one.state()));
}

INSTANTIATE_TEST_SUITE_P(EveryIntegrator, ThreadedStep, ::testing::ValuesIn(kAllIntegrators),
                         [](const auto& info) { return std::string(to_string(info.param)); });

TEST(ThreadedStepSettings, ThreadsOutsideTheirRangeAreRefused) {
  SolverSettings s;
  s.threads = 0;
  EXPECT_THROW(validate(s), std::invalid_argument);
  s.threads = kMaxStepThreads + 1;
  EXPECT_THROW(validate(s), std::invalid_argument);
  s.threads = 2;
  EXPECT_NO_THROW(validate(s));
}

}  // namespace
}  // namespace neurocloth
