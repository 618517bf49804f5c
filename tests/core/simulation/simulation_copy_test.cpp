// A simulation is a value: a copy taken mid-run continues exactly as the
// original would have (bit for bit), and the two never influence each other.
// Learning through time, RK4 stages and rollback rely on this; so does any
// caller that forks a run to try something.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "support/test_support.h"

namespace neurocloth {
namespace {

// A run's whole observable result: state bits, clock and counters.
struct Outcome {
  std::uint64_t hash;
  double time;
  long steps, rejected, evaluations;
  RunStatus status;
  bool operator==(const Outcome& o) const {
    return hash == o.hash && time == o.time && steps == o.steps && rejected == o.rejected &&
           evaluations == o.evaluations && status == o.status;
  }
};

Outcome outcome(const Simulation& s) {
  return {test::state_hash(s.state()), s.time(),  s.steps(), s.rejected_steps(),
          s.force_evaluations(),       s.status()};
}

constexpr double kFirst = 0.04, kSecond = 0.04;  // s of simulated time before and after the copy

// Everything a step reads that is not the cloth's positions: an external force
// on one node (state), and the live parameters of the model.
void drive(Simulation& s) {
  s.set_external_force(s.network().node_count() / 2, Vec3(0.01, 0, 0));
}

class SimulationCopy : public ::testing::TestWithParam<std::string> {};

TEST_P(SimulationCopy, ContinuesBitIdenticalAndIndependent) {
  const Scene scene = test::asset_scene(GetParam());
  Simulation reference = scene.make_simulation();
  drive(reference);
  reference.advance(kFirst);
  reference.advance(kSecond);

  Simulation original = scene.make_simulation();
  drive(original);
  original.advance(kFirst);
  Simulation copy = original;  // mid-run
  const Outcome at_copy = outcome(original);
  EXPECT_EQ(outcome(copy), at_copy);

  // Stepping the copy leaves the original where it was.
  copy.advance(kSecond);
  EXPECT_EQ(outcome(original), at_copy);
  EXPECT_EQ(outcome(copy), outcome(reference)) << GetParam() << ": the copy drifted";

  // And the original, stepped after its copy, ends where the uninterrupted run did.
  original.advance(kSecond);
  EXPECT_EQ(outcome(original), outcome(reference)) << GetParam() << ": the original drifted";
}

TEST_P(SimulationCopy, MovedSimulationContinuesBitIdentical) {
  const Scene scene = test::asset_scene(GetParam());
  Simulation reference = scene.make_simulation();
  reference.advance(kFirst);  // split as below: frames end where a call ends
  reference.advance(kSecond);
  Simulation first = scene.make_simulation();
  first.advance(kFirst);
  Simulation moved = std::move(first);
  moved.advance(kSecond);
  EXPECT_EQ(outcome(moved), outcome(reference));
}

INSTANTIATE_TEST_SUITE_P(EveryShippedScene, SimulationCopy,
                         ::testing::ValuesIn(test::shipped_scene_names()),
                         [](const auto& info) { return info.param; });

// A live change made on a copy (a module's parameter, gravity, an external
// force) stays on that copy.
TEST(SimulationCopy, LiveChangesOnACopyStayOnIt) {
  const Scene scene = test::asset_scene("flag");
  ASSERT_FALSE(scene.make_simulation().network().force_modules.empty())
      << "the flag scene declares wind";
  Simulation reference = scene.make_simulation();
  reference.advance(kFirst);
  reference.advance(kSecond);

  Simulation original = scene.make_simulation();
  original.advance(kFirst);
  Simulation copy = original;
  bool changed = false;
  for (std::size_t k = 0; k < copy.network().force_modules.size(); ++k)
    changed |=
        copy.set_module_parameter(k, ParameterId::module(0, ModuleParameter::velocity, 0), 25.0);
  ASSERT_TRUE(changed) << "the flag's wind takes velocity.x";
  copy.mutable_network().gravity = Vec3(0, -3, 0);
  copy.set_external_force(0, Vec3(1, 2, 3));
  copy.advance(kSecond);
  original.advance(kSecond);
  EXPECT_EQ(outcome(original), outcome(reference));
  EXPECT_NE(outcome(copy).hash, outcome(reference).hash);  // the changes did act on the copy
}

}  // namespace
}  // namespace neurocloth
