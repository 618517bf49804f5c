// The simulation thread from the outside, as the UI sees it: commands posted
// from several threads all arrive and take effect, refusals are reported,
// snapshots are always there and drawable, pause / step / reset behave, and the
// realtime pacing reports honestly. Waits are bounded and generous; nothing
// asserts on speed (the machine may be slow or busy, or under TSan).
#include "runtime/simulation_thread.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <thread>

#include "support/lockstep.h"
#include "support/scratch_dir.h"
#include "support/test_support.h"

namespace neurocloth {
namespace {

using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;

SimulationThread::Options paused_options() {
  SimulationThread::Options o;
  o.realtime = false;
  o.start_paused = true;
  return o;
}

SimulationThread::Options flat_out() {
  SimulationThread::Options o;
  o.realtime = false;
  return o;
}

using test::lockstep;

// Advances `seconds` of simulated time and waits until it is done.
void run_for(SimulationThread& sim, double seconds) {
  sim.post(Advance{seconds});
  sim.wait_for_commands();
}

using test::contains;

// Polls `done` until it holds or `timeout` passes (a bound, not a speed check).
bool eventually(const std::function<bool()>& done, std::chrono::seconds timeout = 20s) {
  const auto end = Clock::now() + timeout;
  while (!done()) {
    if (Clock::now() > end) return false;
    std::this_thread::sleep_for(2ms);
  }
  return true;
}

bool all_finite(const FrameSnapshot& f) {
  for (float p : f.position)
    if (!std::isfinite(p)) return false;
  return true;
}

// Every command posted from two threads arrives, while a third reads snapshots
// and status as fast as it can. Run under ThreadSanitizer in CI.
TEST(SimulationThread, StressManyCommandsFromTwoThreadsNoneLost) {
  SimulationThread sim(test::asset_scene("hanging"), flat_out());
  const int n = static_cast<int>(sim.latest()->geometry->node_count);
  constexpr int kPerThread = 2000;
  std::atomic<bool> posting{true};
  std::atomic<long> invalid{0}, reader_problems{0}, reads{0};
  std::atomic<bool> stepped{false};  // the simulation ran during the storm

  std::thread reader([&] {
    long serial = 0, applied = 0;
    while (posting.load()) {
      const auto f = sim.latest();
      if (!f || f->serial < serial || f->position.size() != 3 * f->geometry->node_count ||
          !all_finite(*f))
        ++reader_problems;
      serial = f ? f->serial : serial;
      // Any step at all: with ~80 resets and pauses in the storm, and a slow
      // sanitizer build on a loaded machine, time may never get far between resets.
      if (f && f->time > 0) stepped = true;
      const SimulationStatus s = sim.status();
      if (s.commands_applied < applied) ++reader_problems;
      applied = s.commands_applied;
      ++reads;
    }
  });

  auto poster = [&](unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_int_distribution<int> kind(0, 99), node(0, n - 1);
    std::uniform_real_distribution<double> u(0, 1);
    for (int i = 0; i < kPerThread; ++i) {
      const int k = kind(rng);
      if (k < 20) {
        sim.post(SetParameter{test::parameter("viscosity"), u(rng)});
      } else if (k < 28) {
        sim.post(SetParameter{test::parameter("gravity.y"), -20 * u(rng)});
      } else if (k < 32) {
        sim.post(SetParameter{test::parameter("dt"), 5e-4 + 1e-3 * u(rng)});
      } else if (k < 36) {
        sim.post(SetParameter{test::parameter("friction"), u(rng)});
      } else if (k < 42) {  // refused every time
        ++invalid;
        sim.post(k % 2 ? SetParameter{test::parameter("viscosity"), 1e6}
                       : SetParameter{ParameterId::input(3), 1});
      } else if (k < 55) {
        sim.post(ApplyForce{node(rng), Vec3(0, 0, 0.2 * u(rng)), Vec3(0, 0, 1)});
      } else if (k < 65) {
        sim.post(ReleaseForce{node(rng)});
      } else if (k < 72) {
        sim.post(SetPinned{node(rng), u(rng) < 0.5});
      } else if (k < 80) {
        sim.post(SetPaused{u(rng) < 0.5});
      } else if (k < 90) {
        sim.post(SingleStep{});
      } else if (k < 93) {
        sim.post(SetIntegrator{kAllIntegrators[k % 5]});
      } else if (k < 95) {
        sim.post(SetAdaptive{u(rng) < 0.3});
      } else if (k < 97) {
        sim.post(ApplyForce{-1, Vec3(0, 0, 1), Vec3::Zero()});  // refused
        ++invalid;
      } else if (k < 98) {
        sim.post(LoadScene{"/no/such/scene.json"});  // refused
        ++invalid;
      } else {
        sim.post(Reset{});
      }
      if (i % 8 == 0) std::this_thread::sleep_for(500us);  // spread over the run
    }
  };
  std::thread a(poster, 1u), b(poster, 2u);
  a.join();
  b.join();
  sim.wait_for_commands();
  posting = false;
  reader.join();

  const SimulationStatus s = sim.status();
  EXPECT_EQ(s.commands_applied, 2 * kPerThread);  // not one lost, not one twice
  EXPECT_GE(s.commands_refused, invalid.load());
  EXPECT_EQ(reader_problems.load(), 0);
  EXPECT_GT(reads.load(), 0);
  EXPECT_TRUE(stepped.load());
  // Still alive and answering.
  sim.post(SetPaused{false});
  sim.post(Reset{});
  sim.wait_for_commands();
  EXPECT_EQ(sim.status().commands_applied, 2 * kPerThread + 2);
  EXPECT_TRUE(eventually([&] { return sim.status().time > 0; }));
}

// A viscosity change reaches the network (the status reads it from the
// springs); a gravity change changes the motion exactly as the closed form says.
TEST(SimulationThread, ParameterChangesReachTheSimulation) {
  {
    SimulationThread sim(test::asset_scene("hanging"), flat_out());
    sim.post(SetParameter{test::parameter("viscosity"), 2.5});
    sim.wait_for_commands();
    const SimulationStatus s = sim.status();
    EXPECT_EQ(s.viscosity, 2.5);
    EXPECT_EQ(s.commands_refused, 0);
  }
  // One free mass, network (symplectic Euler) propagation: after n steps
  // y = y0 + g dt^2 n (n + 1) / 2.
  for (const double g : {-9.81, -20.0, 0.0}) {
    SimulationThread sim(test::asset_scene("free_fall"), paused_options());
    if (g != -9.81) sim.post(SetParameter{test::parameter("gravity.y"), g});
    for (int i = 0; i < 10; ++i)
      sim.post(SingleStep{});
    sim.wait_for_commands();
    const auto f = sim.latest();
    const double dt = 0.01;
    EXPECT_FLOAT_EQ(f->position[1], static_cast<float>(10.0 + g * dt * dt * 55)) << g;
    EXPECT_EQ(sim.status().gravity, Vec3(0, g, 0));
  }
}

// A pulled node moves towards the pull; released, it moves exactly as a
// simulation whose force was zeroed at the same step (the oracle).
TEST(SimulationThread, AppliedForceMovesTheNodeUntilReleased) {
  const Scene scene = test::asset_scene("hanging");
  const int corner = 399;
  const Vec3 pull(0, 0.5, 0);  // up, across the cloth (it starts flat, horizontal)
  auto run = [&](bool pulled) {
    SimulationThread sim(scene, paused_options());
    if (pulled) sim.post(ApplyForce{corner, pull, Vec3(1, 2, 1)});
    for (int i = 0; i < 100; ++i)
      sim.post(SingleStep{});
    sim.wait_for_commands();
    return sim.latest();
  };
  const auto free = run(false), pulled = run(true);
  EXPECT_GT(pulled->node(corner).y(), free->node(corner).y() + 0.01);
  ASSERT_EQ(pulled->forces.size(), 1u);
  EXPECT_EQ(pulled->forces[0].node, corner);
  EXPECT_EQ(pulled->forces[0].anchor, Vec3(1, 2, 1));
  EXPECT_TRUE(free->forces.empty());

  SimulationThread sim(scene, paused_options());
  sim.post(ApplyForce{corner, pull, Vec3(1, 2, 1)});
  for (int i = 0; i < 50; ++i)
    sim.post(SingleStep{});
  sim.post(ReleaseForce{corner});
  for (int i = 0; i < 50; ++i)
    sim.post(SingleStep{});
  sim.wait_for_commands();
  const auto released = sim.latest();
  EXPECT_TRUE(released->forces.empty());

  Simulation oracle = scene.make_simulation();
  oracle.set_external_force(corner, pull);
  for (int i = 0; i < 50; ++i)
    oracle.advance(1e-3);
  oracle.set_external_force(corner, Vec3::Zero());
  for (int i = 0; i < 50; ++i)
    oracle.advance(1e-3);
  FrameSnapshot expected;
  capture(oracle, expected);
  EXPECT_EQ(released->position, expected.position);
  EXPECT_EQ(released->time, oracle.time());
}

TEST(SimulationThread, RefusedCommandsSayWhyAndTheSceneRunsOn) {
  const std::string broken = test::scratch_path("broken_scene.json");
  std::ofstream(broken) << "{ \"name\": \"broken\", \"cloth\": ";

  SimulationThread sim(test::asset_scene("hanging"), lockstep());
  sim.post(SetParameter{test::parameter("viscosity"), 500});
  sim.wait_for_commands();
  SimulationStatus s = sim.status();
  EXPECT_EQ(s.commands_refused, 1);
  EXPECT_TRUE(contains(s.last_error, "viscosity")) << s.last_error;
  EXPECT_TRUE(contains(s.last_error, "[0, 100] N s/m")) << s.last_error;
  EXPECT_EQ(s.viscosity, 0.05);

  sim.post(SetParameter{ParameterId::module(2, ModuleParameter::velocity, 0), 1});
  sim.wait_for_commands();
  s = sim.status();
  EXPECT_EQ(s.commands_refused, 2);
  EXPECT_TRUE(contains(s.last_error, "unknown parameter 'module#2'")) << s.last_error;

  sim.post(LoadScene{broken});
  sim.wait_for_commands();
  s = sim.status();
  EXPECT_EQ(s.commands_refused, 3);
  EXPECT_TRUE(contains(s.last_error, "broken_scene.json")) << s.last_error;
  EXPECT_EQ(s.scene_name, "hanging");
  const double t = s.time;
  run_for(sim, 0.01);
  EXPECT_NEAR(sim.status().time, t + 0.01, 1e-12) << "still running";

  sim.post(LoadScene{assets_directory() + "/scenes/flag.json"});
  sim.wait_for_commands();
  s = sim.status();
  EXPECT_EQ(s.scene_name, "flag");
  EXPECT_EQ(s.commands_refused, 3);
  EXPECT_TRUE(s.wind.has_value());
  EXPECT_EQ(sim.latest()->geometry->scene_name, "flag");
  bool has_wind = false;
  for (const ParameterRange& r : sim.parameter_ranges())
    has_wind |= r.name == "wind.velocity.x";
  EXPECT_TRUE(has_wind);
}

// Fixed-step explicit Euler without viscosity explodes at any step (the guard's
// substeps cannot help it, and the status warned so); the thread keeps
// publishing the last good (finite) state and says why; Reset recovers.
TEST(SimulationThread, DivergenceKeepsTheLastGoodStateAndResetRecovers) {
  SimulationThread sim(test::asset_scene("hanging"), lockstep());
  long serial = sim.latest()->serial;
  sim.post(SetIntegrator{IntegratorKind::explicit_euler});
  sim.post(SetAdaptive{false});
  sim.post(SetParameter{test::parameter("dt"), 0.1});
  sim.post(SetParameter{test::parameter("viscosity"), 0});
  sim.wait_for_commands();
  EXPECT_TRUE(contains(sim.status().last_error, "explicit_euler gains energy"))
      << sim.status().last_error;
  // Every published frame on the way is finite; within 20 simulated seconds it diverges.
  bool ok = true;
  for (int i = 0; i < 200 && sim.status().run == RunStatus::ok; ++i) {
    run_for(sim, 0.1);
    const auto f = sim.latest();
    ok &= f != nullptr && f->serial >= serial && all_finite(*f);
    if (f) serial = f->serial;
  }
  ASSERT_EQ(sim.status().run, RunStatus::diverged);
  EXPECT_TRUE(ok);
  const SimulationStatus s = sim.status();
  EXPECT_FALSE(s.divergence_reason.empty());
  const auto f = sim.latest();
  ASSERT_NE(f, nullptr);
  EXPECT_TRUE(all_finite(*f));
  for (float p : f->position)
    EXPECT_LT(std::abs(p), 100.0f);  // the last good state, not a wild one

  sim.post(Reset{});
  sim.wait_for_commands();
  EXPECT_EQ(sim.status().run, RunStatus::ok);
  EXPECT_EQ(sim.status().dt, 1e-3);
  run_for(sim, 0.02);
  EXPECT_NEAR(sim.status().time, 0.02, 1e-12);
  EXPECT_EQ(sim.status().run, RunStatus::ok);
}

// A change from the UI that would make the step unstable (a dt fifty times
// the explicit limit) is caught: the step runs in substeps under the limit,
// the status says so in last_error (which the viewer shows) without refusing
// anything, and the cloth goes on, finite and in place. Lowering dt again
// takes the message back.
TEST(SimulationThread, AnUnstableChangeIsCaughtReportedAndTheClothHolds) {
  SimulationThread sim(test::asset_scene("hanging"), lockstep());
  sim.post(SetParameter{test::parameter("dt"), 0.05});
  sim.wait_for_commands();
  SimulationStatus s = sim.status();
  EXPECT_EQ(s.commands_refused, 0);
  EXPECT_GT(s.substeps, 20);
  EXPECT_TRUE(contains(s.last_error, "dt = 0.05 s")) << s.last_error;
  EXPECT_TRUE(contains(s.last_error, "substeps")) << s.last_error;
  EXPECT_EQ(s.stability_notice, s.last_error);
  const double t = s.time;
  run_for(sim, 1.0);
  s = sim.status();
  EXPECT_NEAR(s.time, t + 1.0, 1e-9);
  EXPECT_EQ(s.run, RunStatus::ok) << s.divergence_reason;
  const auto f = sim.latest();
  EXPECT_TRUE(all_finite(*f));
  for (float p : f->position)
    EXPECT_LT(std::abs(p), 10.0f);  // the cloth is 1 m across and hangs at 1 m

  sim.post(SetParameter{test::parameter("dt"), 1e-3});
  sim.wait_for_commands();
  s = sim.status();
  EXPECT_EQ(s.last_error, "");
  EXPECT_EQ(s.stability_notice, "");
  EXPECT_EQ(s.substeps, 1);
  EXPECT_EQ(s.run, RunStatus::ok);
}

TEST(SimulationThread, PauseStopsTimeSingleStepAdvancesDtResetRestores) {
  const Scene scene = test::asset_scene("hanging");
  SimulationThread sim(scene, flat_out());
  EXPECT_TRUE(eventually([&] { return sim.status().time > 0.02; }));
  sim.post(SetPaused{true});
  sim.wait_for_commands();
  const SimulationStatus paused = sim.status();
  EXPECT_TRUE(paused.paused);
  const auto frame = sim.latest();
  EXPECT_EQ(frame->time, paused.time);
  std::this_thread::sleep_for(100ms);
  EXPECT_EQ(sim.status().time, paused.time);
  EXPECT_EQ(sim.latest()->time, paused.time);

  sim.post(SingleStep{});
  sim.wait_for_commands();
  EXPECT_EQ(sim.status().time, paused.time + 1e-3);
  EXPECT_EQ(sim.status().steps, paused.steps + 1);
  EXPECT_EQ(sim.latest()->time, paused.time + 1e-3);

  sim.post(SetParameter{test::parameter("viscosity"), 3});
  sim.post(SetPinned{0, false});
  sim.post(Reset{});
  sim.wait_for_commands();
  const SimulationStatus reset = sim.status();
  EXPECT_EQ(reset.time, 0);
  EXPECT_EQ(reset.steps, 0);
  EXPECT_EQ(reset.viscosity, 0.05);
  EXPECT_TRUE(reset.paused);
  FrameSnapshot initial;
  capture(scene.make_simulation(), initial);
  const auto f = sim.latest();
  EXPECT_EQ(f->position, initial.position);
  EXPECT_EQ(f->pinned, initial.pinned);
  EXPECT_GT(f->serial, frame->serial);
}

// In real time the simulated time follows the wall clock: never ahead of it,
// in step with it while it keeps up, and when it falls behind it drops the
// debt and says so. The wall clock here is one the test moves itself, display
// frame by display frame, so what is checked does not depend on how fast this
// machine is (the waits only bound a hang).
TEST(SimulationThread, RealtimeFollowsTheWallClockOrSaysItCannot) {
  std::atomic<double> now{0};
  SimulationThread::Options o;  // realtime by default
  o.clock = [&now] { return now.load(); };
  SimulationThread sim(test::asset_scene("hanging"), o);
  // The thread takes the queue only between passes of its loop, and its first
  // pass syncs the pacer to the clock: after two round trips it has synced at
  // 0, before the clock moves.
  for (int i = 0; i < 2; ++i) {
    sim.post(SetPaused{false});
    sim.wait_for_commands();
  }
  const double dt = 1e-3;  // hanging.json
  // Caught up: within the one step that is not owed yet.
  auto caught_up = [&] { return sim.status().time >= now.load() - dt - 1e-9; };
  for (int frame = 1; frame <= 90; ++frame) {
    now = frame / 60.0;
    ASSERT_TRUE(eventually(caught_up)) << "wall " << now.load() << " s";
    ASSERT_LE(sim.status().time, now.load() + 1e-9) << "ahead of the wall clock";
  }
  SimulationStatus s = sim.status();
  EXPECT_TRUE(s.keeping_up);
  EXPECT_NEAR(s.realtime_ratio, 1.0, 0.01);
  EXPECT_NEAR(s.steps_per_second, 1000, 10);  // 1 ms steps
  EXPECT_FALSE(s.energy_history.empty());
  EXPECT_LE(s.energy_history.size(), 600u);

  // A whole second at once (a stall): more than the 0.1 s it may owe. It
  // re-syncs, runs one slice (0.05 s) of the debt and drops the rest, and says
  // it is not keeping up.
  const double before = s.time;
  now = now.load() + 1.0;
  ASSERT_TRUE(eventually([&] { return sim.status().time > before; }));
  s = sim.status();
  EXPECT_NEAR(s.time, before + 0.05, 1e-9);
  EXPECT_FALSE(s.keeping_up);
  EXPECT_LT(s.realtime_ratio, 0.9);
}

TEST(SimulationThread, StatusDescribesTheRun) {
  SimulationThread sim(test::asset_scene("hanging_fuzzy"), paused_options());
  SimulationStatus s = sim.status();
  EXPECT_EQ(s.scene_name, "hanging_fuzzy");
  EXPECT_TRUE(s.paused);
  EXPECT_TRUE(s.adaptive);
  EXPECT_EQ(s.dt, 0.01);
  EXPECT_GT(s.step_cap, 0);
  EXPECT_LE(s.step_cap, 0.01);
  EXPECT_EQ(s.material_inputs.size(), 3u);
  EXPECT_FALSE(s.wind.has_value());
  const ParameterId mass = test::parameter(test::asset_scene("hanging_fuzzy"), "input.mass");
  sim.post(SetParameter{mass, 0.5});
  sim.post(SetParameter{mass, 99});
  sim.wait_for_commands();
  s = sim.status();
  EXPECT_EQ(s.commands_refused, 1);
  EXPECT_TRUE(contains(s.last_error, "input.mass")) << s.last_error;
  for (const auto& [name, value] : s.material_inputs)
    if (name == "mass") {
      EXPECT_EQ(value, 0.5);
    }
  const auto ranges = sim.parameter_ranges();
  EXPECT_EQ(ranges.size(), parameter_ranges(test::asset_scene("hanging_fuzzy")).size());
}

}  // namespace
}  // namespace neurocloth
