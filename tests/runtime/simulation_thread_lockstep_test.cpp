// The lockstep clock (Options::lockstep, the window's --lockstep): the thread
// never steps on its own, each Advance moves simulated time on in whole steps
// of dt with the remainder carried, and the result depends on the commands
// alone — not on the machine's speed, nor on how the queue happened to be
// batched. Every expectation here is exact: no wall clock is involved.
#include <gtest/gtest.h>

#include <chrono>
#include <condition_variable>
#include <limits>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "runtime/simulation_thread.h"
#include "support/lockstep.h"
#include "support/test_support.h"

namespace neurocloth {
namespace {

using test::lockstep;

constexpr double kFrame = 1.0 / 60.0;
constexpr double kHangingDt = 1e-3;  // hanging.json: fixed step

// Sixty frames of 1/60 s are one second of simulated time in 1 ms steps: the
// 0.67 ms of each frame that is not a whole step is carried, not lost. The
// cloth is exactly where the core alone puts it after those steps.
TEST(SimulationThreadLockstep, AdvanceTakesWholeStepsAndCarriesTheRemainder) {
  const Scene scene = test::asset_scene("hanging");
  SimulationThread sim(scene, lockstep());
  sim.wait_for_commands();
  EXPECT_EQ(sim.status().time, 0) << "no step without an Advance";
  sim.post(Advance{kFrame});
  sim.wait_for_commands();
  EXPECT_EQ(sim.status().steps, 16);  // 16.67 ms owed: 16 whole steps
  for (int i = 1; i < 60; ++i)
    sim.post(Advance{kFrame});
  sim.wait_for_commands();
  const SimulationStatus s = sim.status();
  EXPECT_GE(s.steps, 999);  // 1000 but for the round-off of sixty sums of 1/60
  EXPECT_LE(s.steps, 1000);
  EXPECT_EQ(s.commands_refused, 0);

  Simulation alone = scene.make_simulation();
  ASSERT_EQ(alone.advance(static_cast<double>(s.steps) * kHangingDt), RunStatus::ok);
  FrameSnapshot expected;
  capture(alone, expected);
  EXPECT_EQ(sim.latest()->position, expected.position);
}

// The thread's own loop never moves time in lockstep, however long it is left alone.
TEST(SimulationThreadLockstep, WithoutAdvanceTimeStandsStill) {
  SimulationThread sim(test::asset_scene("hanging"), lockstep());
  sim.post(SetParameter{test::parameter("viscosity"), 0.2});
  sim.wait_for_commands();
  const long serial = sim.latest()->serial;
  // Long enough for several of the thread's idle wake-ups (every 0.1 s): a
  // thread that stepped on its own would have moved by now on any machine.
  std::this_thread::sleep_for(std::chrono::milliseconds(350));
  EXPECT_EQ(sim.status().time, 0);
  EXPECT_EQ(sim.latest()->serial, serial);
}

// A paused run owes nothing for the frames that passed: on resume one frame
// runs one frame's steps, as a realtime run owes nothing for a pause.
TEST(SimulationThreadLockstep, PausedAdvancesOweNothing) {
  SimulationThread sim(test::asset_scene("hanging"), lockstep(/*paused=*/true));
  for (int i = 0; i < 30; ++i)
    sim.post(Advance{kFrame});
  sim.wait_for_commands();
  EXPECT_EQ(sim.status().time, 0);
  sim.post(SingleStep{});  // still allowed while paused
  sim.post(SetPaused{false});
  sim.post(Advance{kFrame});
  sim.wait_for_commands();
  EXPECT_EQ(sim.status().steps, 1 + 16);
}

// The same commands give the same cloth bit for bit whether each is waited
// for (the window under --lockstep) or all are posted at once and taken in
// whatever batches the thread happens to find.
TEST(SimulationThreadLockstep, TheResultDependsOnTheCommandsNotOnTheirBatching) {
  const Scene scene = test::asset_scene("hanging");
  const int corner = 399;
  std::vector<SimCommand> commands;
  commands.push_back(ApplyForce{corner, Vec3(0.3, 0.5, 0), Vec3(1, 2, 1)});
  for (int i = 0; i < 20; ++i)
    commands.push_back(Advance{kFrame});
  commands.push_back(SetPinned{corner - 5, true});
  commands.push_back(SetParameter{test::parameter("viscosity"), 0.4});
  commands.push_back(ReleaseForce{corner});
  for (int i = 0; i < 20; ++i)
    commands.push_back(Advance{kFrame});
  commands.push_back(SetPaused{true});
  commands.push_back(SingleStep{});
  commands.push_back(SetPaused{false});
  commands.push_back(SetParameter{test::parameter("gravity.x"), 3});
  for (int i = 0; i < 20; ++i)
    commands.push_back(Advance{kFrame});

  SimulationThread waited(scene, lockstep()), at_once(scene, lockstep());
  for (const SimCommand& c : commands) {
    waited.post(c);
    waited.wait_for_commands();
  }
  for (const SimCommand& c : commands)
    at_once.post(c);
  at_once.wait_for_commands();
  const auto a = waited.latest(), b = at_once.latest();
  EXPECT_GT(a->time, 0.9);
  EXPECT_EQ(a->time, b->time);
  EXPECT_EQ(a->position, b->position);
  EXPECT_EQ(a->pinned, b->pinned);
  EXPECT_EQ(waited.status().steps, at_once.status().steps);
  EXPECT_EQ(waited.status().commands_refused, 0);
}

TEST(SimulationThreadLockstep, AdvanceIsRefusedWhenTheThreadPacesItselfOrTheTimeIsNoFrame) {
  SimulationThread::Options flat_out;
  flat_out.realtime = false;
  flat_out.start_paused = true;
  SimulationThread paced(test::asset_scene("hanging"), flat_out);
  paced.post(Advance{kFrame});
  paced.wait_for_commands();
  EXPECT_EQ(paced.status().commands_refused, 1);
  EXPECT_NE(paced.status().last_error.find("lockstep"), std::string::npos)
      << paced.status().last_error;

  SimulationThread sim(test::asset_scene("hanging"), lockstep());
  sim.post(Advance{-1});
  sim.post(Advance{std::numeric_limits<double>::infinity()});
  sim.post(Advance{1e300});  // would hold the thread (and its stop) for ever
  sim.post(Advance{std::numeric_limits<double>::quiet_NaN()});
  sim.wait_for_commands();
  EXPECT_EQ(sim.status().commands_refused, 4);
  EXPECT_NE(sim.status().last_error.find("[0, 1]"), std::string::npos) << sim.status().last_error;
  EXPECT_EQ(sim.status().time, 0);
}

// A run that diverges stands still (nothing owed piles up) and Reset starts
// the clock over.
TEST(SimulationThreadLockstep, ADivergedRunStandsStillAndResetRestartsTheClock) {
  SimulationThread sim(test::asset_scene("hanging"), lockstep());
  sim.post(SetIntegrator{IntegratorKind::explicit_euler});
  sim.post(SetAdaptive{false});
  sim.post(SetParameter{test::parameter("dt"), 0.1});
  sim.post(SetParameter{test::parameter("viscosity"), 0});
  // Forward Euler without viscosity gains energy at every step: within 20 simulated s.
  for (int i = 0; i < 200 && sim.status().run == RunStatus::ok; ++i) {
    sim.post(Advance{0.1});
    sim.wait_for_commands();
  }
  ASSERT_EQ(sim.status().run, RunStatus::diverged);
  const double stopped = sim.status().time;
  sim.post(Advance{1.0});
  sim.wait_for_commands();
  EXPECT_EQ(sim.status().time, stopped);

  sim.post(Reset{});
  sim.post(Advance{kFrame});
  sim.wait_for_commands();
  EXPECT_EQ(sim.status().run, RunStatus::ok);
  EXPECT_EQ(sim.status().steps, 16);
}

}  // namespace
}  // namespace neurocloth

namespace neurocloth {
namespace {

// A wait with a timeout says whether the commands were applied: false while
// the thread is held (here inside the clock it reads before it marks a batch
// done), true once it is let go. No speed is involved: the thread cannot
// finish while it is held, and the second wait's minute is a hang bound.
TEST(SimulationThreadLockstep, AWaitWithATimeoutSaysWhetherTheCommandsWereApplied) {
  std::mutex m;
  std::condition_variable cv;
  bool hold = false;
  SimulationThread::Options options = test::lockstep();
  options.clock = [&] {
    std::unique_lock<std::mutex> lock(m);
    cv.wait(lock, [&] { return !hold; });
    return 0.0;
  };
  SimulationThread sim(test::asset_scene("hanging"), options);
  EXPECT_TRUE(sim.wait_for_commands(std::chrono::seconds(60)));  // nothing pending
  {
    std::lock_guard<std::mutex> lock(m);
    hold = true;
  }
  sim.post(Advance{0.01});
  EXPECT_FALSE(sim.wait_for_commands(std::chrono::milliseconds(20)));
  {
    std::lock_guard<std::mutex> lock(m);
    hold = false;
  }
  cv.notify_all();
  EXPECT_TRUE(sim.wait_for_commands(std::chrono::seconds(60)));
  EXPECT_EQ(sim.status().steps, 10);
}

}  // namespace
}  // namespace neurocloth
