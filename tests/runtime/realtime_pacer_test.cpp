// Pacing rules on a synthetic clock: steps owed follow wall time, ahead means
// wait, far behind means re-sync (drop the debt but one slice) rather than
// chase; the rate window measures simulated seconds per wall second.
#include "runtime/realtime_pacer.h"

#include <gtest/gtest.h>

namespace neurocloth {
namespace {

constexpr double dt = 1e-3;
constexpr int kSlice = 50;  // max steps per slice (0.05 s)

TEST(RealtimePacer, StepsFollowTheWallClock) {
  RealtimePacer p(0.1);
  p.sync(10.0, 0.0);
  EXPECT_EQ(p.plan(10.0, 0.0, dt, kSlice), 0);      // nothing owed yet
  EXPECT_EQ(p.plan(10.0205, 0.0, dt, kSlice), 20);  // 20.5 ms owed: 20 whole steps
  EXPECT_EQ(p.plan(10.0205, 0.020, dt, kSlice), 0);
  EXPECT_EQ(p.plan(10.030, 0.020, dt, kSlice),
            10);  // round-off in the wall time is not a step less
  EXPECT_EQ(p.plan(10.090, 0.020, dt, kSlice), kSlice);  // capped at one slice
  EXPECT_EQ(p.resyncs(), 0);
  EXPECT_LT(p.owed(10.0, 0.02), 0);  // ahead
}

TEST(RealtimePacer, FallingFarBehindResyncsInsteadOfCatchingUp) {
  RealtimePacer p(0.1);
  p.sync(0.0, 0.0);
  double sim = 0, wall = 0.01;
  // A simulation that takes 2 wall seconds per simulated second.
  for (int i = 0; i < 100; ++i) {
    const int steps = p.plan(wall, sim, dt, kSlice);
    ASSERT_GT(steps, 0);
    sim += steps * dt;
    wall += 2 * steps * dt;
    EXPECT_LE(p.owed(wall, sim), 0.1 + 2 * kSlice * dt);  // the debt never piles up
  }
  EXPECT_GT(p.resyncs(), 10);
  EXPECT_GT(p.last_resync(), 0);
}

TEST(RateWindow, MeasuresSimulatedSecondsPerWallSecondOverTheLastSpan) {
  RateWindow w(1.0);
  EXPECT_EQ(w.realtime_ratio(), 1.0);  // too short to tell
  EXPECT_EQ(w.steps_per_second(), 0.0);
  // Half speed for 3 s, then full speed for 2 s: the window sees only the last second.
  double sim = 0;
  long steps = 0;
  for (int i = 0; i <= 300; ++i) {
    w.add(i / 100.0, sim, steps);
    sim += 0.005;
    steps += 5;
  }
  EXPECT_NEAR(w.realtime_ratio(), 0.5, 1e-9);
  EXPECT_NEAR(w.steps_per_second(), 500, 1e-6);
  for (int i = 301; i <= 500; ++i) {
    w.add(i / 100.0, sim, steps);
    sim += 0.01;
    steps += 10;
  }
  EXPECT_NEAR(w.realtime_ratio(), 1.0, 0.02);
  EXPECT_NEAR(w.covered(), 1.0, 0.011);
  w.add(5.01, 0.0, 0);  // a reset: time went back
  EXPECT_EQ(w.realtime_ratio(), 1.0);
}

}  // namespace
}  // namespace neurocloth
