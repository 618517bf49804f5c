// The window's fit on its own thread (fit_worker.h): it fits, it stops when
// told from another thread, it fails with a message rather than dying, and
// what it found maps onto the running scene's parameters. Deterministic: the
// tests wait for the worker (wait(), or a hook the worker calls after each
// row), never for a time.
#include "runtime/fit_worker.h"

#include <gtest/gtest.h>

#include <cmath>
#include <future>

#include "support/test_support.h"

namespace neurocloth {
namespace {

// `scene` run for `seconds`, every node in file order at 60 frames per second:
// what `simulate --record` writes, in memory. (dt = 1 ms divides no 1/60 s
// exactly, so the frames here are taken at the step nearest each frame time.)
ReferenceMotion recorded(const Scene& scene, double seconds) {
  Simulation sim = scene.make_simulation();
  ReferenceMotion ref;
  ref.path = "in memory";
  const std::size_t n = scene.topology.rest_positions.size();
  const double dt = scene.solver.dt;
  for (int k = 0; k / 60.0 <= seconds + 1e-12; ++k) {
    const double t = k / 60.0;
    const double steps = std::round(t / dt);
    if (steps * dt > sim.time() + 0.5 * dt) sim.advance(steps * dt - sim.time());
    ReferenceFrame f;
    f.time = sim.time();
    for (std::size_t file = 0; file < n; ++file) {
      f.nodes.push_back(static_cast<std::int32_t>(file));
      f.positions.push_back(sim.state().position(scene.topology.numbering.node(int(file))));
    }
    ref.frames.push_back(std::move(f));
  }
  return ref;
}

// The hanging cloth fitted to a motion recorded with twice its stiffness.
FitJob stiffness_job(int max_iterations) {
  Scene truth = test::asset_scene("hanging");
  truth.material.spring_constant = 400;
  FitJob job;
  job.scene = std::make_shared<const Scene>(test::asset_scene("hanging"));
  job.reference = std::make_shared<const ReferenceMotion>(recorded(truth, 0.2));
  job.settings.params = {"spring_constant"};
  job.max_iterations = max_iterations;
  return job;
}

TEST(FitWorker, FitsTheStiffnessOfARecordedMotionAndReportsEveryIteration) {
  FitWorker worker;
  ASSERT_EQ(worker.start(stiffness_job(40)), "");
  worker.wait();
  const FitProgress p = worker.progress();
  ASSERT_EQ(p.state, FitProgress::State::finished) << p.message;
  ASSERT_TRUE(p.reason.has_value());
  EXPECT_TRUE(converged(*p.reason)) << p.message;
  ASSERT_EQ(p.names, std::vector<std::string>{"spring_constant"});
  ASSERT_EQ(p.values.size(), 1u);
  ASSERT_GE(p.loss.size(), 2u);
  EXPECT_EQ(p.values[0].size(), p.loss.size());
  EXPECT_DOUBLE_EQ(p.values[0].front(), 200);  // the start point is the first row
  EXPECT_LT(p.loss.back(), 1e-6 * p.loss.front());
  ASSERT_TRUE(p.outcome);
  EXPECT_NEAR(p.outcome->command.material.spring_constant, 400, 0.4);
  EXPECT_DOUBLE_EQ(p.outcome->command.material.viscosity, 0.05);  // not fitted: the scene's
  EXPECT_TRUE(p.outcome->command.module_parameters.empty());
  EXPECT_FALSE(worker.running());
}

TEST(FitWorker, StopFromAnotherThreadEndsTheFitKeepingTheBestSoFar) {
  std::promise<void> reached, released;
  std::shared_future<void> release = released.get_future().share();
  // The worker waits at its second row until the test has pressed Stop.
  FitWorker worker([&](int row) {
    if (row != 1) return;
    reached.set_value();
    release.wait();
  });
  ASSERT_EQ(worker.start(stiffness_job(1000)), "");
  reached.get_future().wait();
  EXPECT_TRUE(worker.running());
  worker.stop();
  released.set_value();
  worker.wait();
  const FitProgress p = worker.progress();
  EXPECT_EQ(p.state, FitProgress::State::finished);
  ASSERT_TRUE(p.reason.has_value());
  EXPECT_EQ(*p.reason, StopReason::stopped) << p.message;
  EXPECT_EQ(p.loss.size(), 2u);  // the start point and one iteration, nothing after Stop
  ASSERT_TRUE(p.outcome);
  EXPECT_GT(p.outcome->command.material.spring_constant, 200);  // moved towards 400
}

TEST(FitWorker, RefusesASecondFitWhileOneRunsAndFailsCleanlyOnABadParameter) {
  std::string second;
  FitWorker* self = nullptr;
  FitWorker worker([&](int row) {
    if (row == 0) second = self->start(stiffness_job(1));
  });
  self = &worker;
  ASSERT_EQ(worker.start(stiffness_job(1)), "");
  worker.wait();
  EXPECT_EQ(second, "a fit is running: stop it first");
  EXPECT_EQ(worker.progress().state, FitProgress::State::finished);

  FitJob bad = stiffness_job(5);
  bad.settings.params = {"no_such_parameter"};
  ASSERT_EQ(worker.start(bad), "");
  worker.wait();
  const FitProgress p = worker.progress();
  EXPECT_EQ(p.state, FitProgress::State::failed);
  EXPECT_NE(p.message.find("no_such_parameter"), std::string::npos) << p.message;
  EXPECT_FALSE(p.outcome);
  EXPECT_EQ(p.job, 2);

  FitJob none = stiffness_job(5);
  none.reference.reset();
  EXPECT_NE(worker.start(none).find("no reference"), std::string::npos);
}

TEST(FitWorker, OnlineAdaptationRunsThroughTheReferenceOnce) {
  FitJob job = stiffness_job(1);
  job.online = true;
  job.online_settings = {20, 0.1};
  FitWorker worker;
  ASSERT_EQ(worker.start(job), "");
  worker.wait();
  const FitProgress p = worker.progress();
  ASSERT_EQ(p.state, FitProgress::State::finished) << p.message;
  EXPECT_EQ(p.message, "the reference ended");
  EXPECT_TRUE(p.online);
  EXPECT_GE(p.loss.size(), 5u);
  EXPECT_NEAR(p.online_time, job.reference->frames.back().time, 1e-9);
  ASSERT_TRUE(p.outcome);
  EXPECT_GT(p.values[0].back(), 200);  // stiffened towards the reference's 400
}

TEST(FitWorker, ModuleParametersMapToTheRunningScenesIds) {
  const Scene flag = test::asset_scene("flag");
  ReferenceMotion ref;
  ref.source = ReferenceMotion::Source::markers;
  ref.frames.push_back({0.05, {0}, {flag.topology.rest_positions[0]}});
  FitSettings settings;
  settings.params = {"spring_constant", "wind.velocity.x", "rest_length"};
  FitProblem problem(flag, ref, settings);
  const FitOutcome out = fit_outcome(problem, flag, problem.initial());
  ASSERT_EQ(out.command.module_parameters.size(), 1u);
  EXPECT_EQ(out.command.module_parameters[0].first, test::parameter(flag, "wind.velocity.x"));
  EXPECT_DOUBLE_EQ(out.command.module_parameters[0].second, 6.0);
  ASSERT_EQ(out.not_applied.size(), 1u);
  EXPECT_EQ(out.not_applied[0].rfind("rest_length", 0), 0u);
  EXPECT_DOUBLE_EQ(out.command.material.spring_constant, flag.material.spring_constant);
}

}  // namespace
}  // namespace neurocloth
