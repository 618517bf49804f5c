// A run's state is a value of its own: saved mid-run and restored later, the
// run continues exactly as it did the first time, bit for bit; a state that
// does not fit is refused with what differs; and the comparison sees every
// member, so a restore that forgot one would fail here.
#include "core/simulation/simulation_state.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "support/test_support.h"

namespace neurocloth {
namespace {

constexpr double kBefore = 0.2, kAfter = 0.2;  // s of simulated time before and after the save

// table_drape has a constraint (the table), adaptive steps and rejections;
// an external force makes the inputs part of what must come back.
Simulation started(const std::string& scene) {
  Simulation s = test::asset_scene(scene).make_simulation();
  s.set_external_force(s.network().node_count() / 2, Vec3(0.01, 0, 0));
  s.advance(kBefore);
  return s;
}

TEST(SimulationState, RestoredRunContinuesBitIdentical) {
  Simulation sim = started("table_drape");
  ASSERT_GT(sim.module_count(), 0u);
  const SimulationState saved = sim.run_state();
  ASSERT_EQ(sim.advance(kAfter), RunStatus::ok);
  const SimulationState first = sim.run_state();
  ASSERT_GT(first.counters.steps, saved.counters.steps);

  sim.restore(saved);
  EXPECT_EQ(first_difference(sim.run_state(), saved), "");
  ASSERT_EQ(sim.advance(kAfter), RunStatus::ok);
  EXPECT_EQ(first_difference(sim.run_state(), first), "");
  EXPECT_TRUE(same_bits(sim.run_state(), first));
  EXPECT_EQ(test::state_hash(sim.state()), test::state_hash(first.cloth()));
}

// The members a step writes only now and then (the checkpoint every
// check_interval steps, the counters) must come back too: after running on,
// they differ from the saved ones, and restore must undo that.
TEST(SimulationState, RestoreBringsBackCheckpointAndCounters) {
  Simulation sim = started("table_drape");
  const SimulationState saved = sim.run_state();
  sim.advance(kAfter);
  ASSERT_NE(sim.run_state().checkpoint.steps, saved.checkpoint.steps);
  ASSERT_NE(sim.force_evaluations(), saved.counters.force_evaluations);
  sim.restore(saved);
  EXPECT_EQ(sim.run_state().checkpoint.steps, saved.checkpoint.steps);
  EXPECT_TRUE(same_bits(sim.run_state().checkpoint.state, saved.checkpoint.state));
  EXPECT_EQ(sim.steps(), saved.counters.steps);
  EXPECT_EQ(sim.rejected_steps(), saved.counters.rejected);
  EXPECT_EQ(sim.force_evaluations(), saved.counters.force_evaluations);
  EXPECT_EQ(sim.time(), saved.time);
}

TEST(SimulationState, RefusesAStateOfAnotherSize) {
  Simulation drape = started("table_drape");
  const Simulation other = test::asset_scene("hanging").make_simulation();
  ASSERT_NE(other.network().node_count(), drape.network().node_count());
  const SimulationState before = drape.run_state();
  try {
    drape.restore(other.run_state());
    FAIL() << "a state of another node count was restored";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("node count"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(same_bits(drape.run_state(), before));  // refused before anything changed
}

TEST(SimulationState, RefusesAStateOfAnotherModuleCount) {
  Simulation drape = started("table_drape");
  SimulationState fewer = drape.run_state();
  ASSERT_FALSE(fewer.module_states.empty());
  fewer.module_states.pop_back();
  try {
    drape.restore(fewer);
    FAIL() << "a state of another module count was restored";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("module count"), std::string::npos) << e.what();
  }
}

// Each member changed alone is seen, and named.
TEST(SimulationState, ComparisonSeesEveryMember) {
  const Simulation sim = started("table_drape");
  const SimulationState s = sim.run_state();
  ASSERT_TRUE(same_bits(s, s));
  auto differs = [&](const char* name, auto change) {
    SimulationState t = s;
    change(t);
    EXPECT_FALSE(same_bits(s, t)) << name;
    EXPECT_EQ(first_difference(s, t), name);
  };
  differs("current", [](SimulationState& t) { t.current = 1 - t.current; });
  differs("buffers[0]", [](SimulationState& t) { t.buffers[0].vx[0] += 1; });
  differs("buffers[1]", [](SimulationState& t) { t.buffers[1].z[1] += 1; });
  differs("time", [](SimulationState& t) { t.time += 1e-12; });
  differs("counters.steps", [](SimulationState& t) { ++t.counters.steps; });
  differs("counters.rejected", [](SimulationState& t) { ++t.counters.rejected; });
  differs("counters.force_evaluations", [](SimulationState& t) { ++t.counters.force_evaluations; });
  differs("counters.cg_iterations", [](SimulationState& t) { ++t.counters.cg_iterations; });
  differs("counters.steps_since_check", [](SimulationState& t) { ++t.counters.steps_since_check; });
  differs("counters.degenerate_springs",
          [](SimulationState& t) { ++t.counters.degenerate_springs; });
  differs("inputs.external_force", [](SimulationState& t) { t.inputs.external_force.x[0] = 2; });
  differs("inputs.time", [](SimulationState& t) { t.inputs.time += 1; });
  differs("module_states", [](SimulationState& t) { t.module_states.pop_back(); });
  differs("checkpoint.state", [](SimulationState& t) { t.checkpoint.state.x[0] += 1; });
  differs("checkpoint.time", [](SimulationState& t) { t.checkpoint.time += 1; });
  differs("checkpoint.steps", [](SimulationState& t) { ++t.checkpoint.steps; });
  differs("status", [](SimulationState& t) { t.status = RunStatus::diverged; });
  differs("reason", [](SimulationState& t) { t.reason = "why"; });
  differs("monitor", [](SimulationState& t) { t.monitor = DivergenceMonitor(); });
  differs("ramp", [&](SimulationState& t) {
    t.ramp.start(sim.network(), sim.network().material_weights(Material{}), 4);
  });
}

}  // namespace
}  // namespace neurocloth
