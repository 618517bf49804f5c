#include "learn/optim/optimizer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

namespace neurocloth {
namespace {

using Eigen::VectorXd;

// Rosenbrock's valley: minimum 0 at (1, 1), reached along a curved floor.
double rosenbrock(const VectorXd& x, VectorXd* g) {
  const double a = 1 - x[0], b = x[1] - x[0] * x[0];
  if (g) {
    g->resize(2);
    (*g)[0] = -2 * a - 400 * x[0] * b;
    (*g)[1] = 200 * b;
  }
  return a * a + 100 * b * b;
}

// 1/2 sum w_i (x_i - c_i)^2, minimum 0 at c.
Objective quadratic(VectorXd c, VectorXd w) {
  return [c, w](const VectorXd& x, VectorXd* g) {
    const VectorXd d = x - c;
    if (g) *g = w.cwiseProduct(d);
    return 0.5 * d.dot(w.cwiseProduct(d));
  };
}

class BothMethods : public ::testing::TestWithParam<OptimizerMethod> {
 protected:
  OptimizerOptions options(int iterations) const {
    OptimizerOptions o;
    o.method = GetParam();
    o.max_iterations = iterations;
    return o;
  }
};

TEST_P(BothMethods, ReachesTheMinimumOfAQuadratic) {
  OptimizerOptions o = options(2000);
  o.stall_iterations = 0;
  o.gradient_tolerance = 1e-9;
  const OptimizerResult r = minimize(
      quadratic(VectorXd::Constant(3, 2.0), VectorXd::LinSpaced(3, 1, 10)), VectorXd::Zero(3), o);
  EXPECT_EQ(r.reason, StopReason::gradient_small) << r.message;
  EXPECT_TRUE(converged(r.reason));
  EXPECT_LT((r.best_theta - VectorXd::Constant(3, 2.0)).norm(), 1e-8);
  EXPECT_NEAR(r.best_loss, 0, 1e-16);
}

TEST_P(BothMethods, FollowsRosenbrocksValleyToItsMinimum) {
  OptimizerOptions o = options(GetParam() == OptimizerMethod::lbfgs ? 200 : 100000);
  o.stall_iterations = 0;
  o.gradient_tolerance = 1e-7;
  const OptimizerResult r = minimize(rosenbrock, VectorXd{{-1.2, 1.0}}, o);
  EXPECT_TRUE(converged(r.reason)) << to_string(r.reason) << ": " << r.message;
  EXPECT_NEAR(r.best_theta[0], 1, 1e-4);
  EXPECT_NEAR(r.best_theta[1], 1, 1e-4);
  // Every accepted point is no worse than the one before (Armijo).
  for (std::size_t i = 1; i < r.history.size(); ++i)
    EXPECT_LE(r.history[i].loss, r.history[i - 1].loss) << "iteration " << i;
}

// A trial step into a region where the objective is NaN (a cloth too stiff for
// its step blows up) is a step too long: the search shortens it and goes on,
// never accepting a NaN point.
TEST_P(BothMethods, BacksOffFromANanRegionKeepingTheBestPointSeen) {
  // The minimum at 3 lies beyond a region (x > 1) where the objective diverges.
  const Objective base = quadratic(VectorXd::Constant(1, 3.0), VectorXd::Ones(1));
  int nan_calls = 0;
  const Objective f = [&](const VectorXd& x, VectorXd* g) {
    if (x[0] > 1) {
      ++nan_calls;
      if (g) *g = VectorXd::Constant(1, std::nan(""));
      return std::numeric_limits<double>::quiet_NaN();
    }
    return base(x, g);
  };
  const OptimizerResult r = minimize(f, VectorXd::Constant(1, -2.0), options(100));
  EXPECT_GE(nan_calls, 1);
  for (const OptimizerRecord& h : r.history)
    EXPECT_TRUE(std::isfinite(h.loss)) << "iteration " << h.iteration;
  ASSERT_EQ(r.best_theta.size(), 1);
  EXPECT_LE(r.best_theta[0], 1);
  EXPECT_GT(r.best_theta[0], 0.5) << "it went on towards the minimum after the NaN";
  EXPECT_TRUE(std::isfinite(r.best_loss));
  EXPECT_DOUBLE_EQ(r.best_loss, base(r.best_theta, nullptr));
}

// When no step along the search direction is finite, the fit stops there,
// says it was a NaN, and keeps the best point.
TEST_P(BothMethods, StopsWhenEveryTrialStepIsNanKeepingTheBestPointSeen) {
  const Objective base = quadratic(VectorXd::Constant(1, 3.0), VectorXd::Ones(1));
  const VectorXd start = VectorXd::Constant(1, -2.0);
  const Objective f = [&](const VectorXd& x, VectorXd* g) {
    if (x[0] != start[0]) {
      if (g) *g = VectorXd::Constant(1, std::nan(""));
      return std::numeric_limits<double>::quiet_NaN();
    }
    return base(x, g);
  };
  const OptimizerResult r = minimize(f, start, options(100));
  EXPECT_EQ(r.reason, StopReason::not_finite) << r.message;
  EXPECT_NE(r.message.find("NaN"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("best parameters"), std::string::npos) << r.message;
  EXPECT_EQ(r.best_theta, start);
  EXPECT_DOUBLE_EQ(r.best_loss, base(start, nullptr));
}

TEST_P(BothMethods, ANanAtTheStartReturnsTheStartWithNoFiniteLoss) {
  const Objective f = [](const VectorXd&, VectorXd* g) {
    if (g) *g = VectorXd::Zero(2);
    return std::numeric_limits<double>::quiet_NaN();
  };
  const OptimizerResult r = minimize(f, VectorXd::Ones(2), options(10));
  EXPECT_EQ(r.reason, StopReason::not_finite);
  EXPECT_TRUE(std::isnan(r.best_loss));
  EXPECT_EQ(r.best_theta, VectorXd::Ones(2));
  EXPECT_NE(r.message.find("no evaluation had a finite loss"), std::string::npos) << r.message;
}

TEST_P(BothMethods, HonoursTheIterationBudget) {
  const OptimizerResult r = minimize(rosenbrock, VectorXd{{-1.2, 1.0}}, options(3));
  EXPECT_EQ(r.reason, StopReason::iteration_budget) << r.message;
  EXPECT_EQ(r.iterations, 3);
  ASSERT_EQ(r.history.size(), 4u);  // the start and three iterations
  for (int k = 0; k < 4; ++k)
    EXPECT_EQ(r.history[std::size_t(k)].iteration, k);
  EXPECT_EQ(r.evaluations, r.history.back().evaluations);
  EXPECT_DOUBLE_EQ(r.best_loss, rosenbrock(r.best_theta, nullptr));
}

TEST_P(BothMethods, HonoursTheTimeBudgetOnItsClock) {
  // A fake clock: each evaluation takes one "second".
  double now = 100;
  const Objective f = [&](const VectorXd& x, VectorXd* g) {
    now += 1;
    return rosenbrock(x, g);
  };
  OptimizerOptions o = options(100000);
  o.stall_iterations = 0;
  o.time_budget = 10;
  o.clock = [&] { return now; };
  const OptimizerResult r = minimize(f, VectorXd{{-1.2, 1.0}}, o);
  EXPECT_EQ(r.reason, StopReason::time_budget) << r.message;
  EXPECT_EQ(r.evaluations, 10);  // the 11th would start at 10 s
  EXPECT_DOUBLE_EQ(r.seconds, 10);
  EXPECT_DOUBLE_EQ(r.best_loss, rosenbrock(r.best_theta, nullptr));
  EXPECT_LT(r.best_loss, rosenbrock(VectorXd{{-1.2, 1.0}}, nullptr));
}

TEST_P(BothMethods, TheCallbackStopsTheRunAndSeesEveryIteration) {
  std::vector<int> seen;
  const OptimizerResult r =
      minimize(rosenbrock, VectorXd{{-1.2, 1.0}}, options(100), [&](const IterationInfo& it) {
        seen.push_back(it.iteration);
        EXPECT_DOUBLE_EQ(it.loss, rosenbrock(it.theta, nullptr));
        return it.iteration < 4;
      });
  EXPECT_EQ(r.reason, StopReason::stopped);
  EXPECT_EQ(seen, (std::vector<int>{0, 1, 2, 3, 4}));
  EXPECT_EQ(r.iterations, 4);
}

TEST_P(BothMethods, ShouldStopEndsTheRunBetweenEvaluations) {
  int calls = 0;
  const Objective f = [&](const VectorXd& x, VectorXd* g) {
    ++calls;
    return rosenbrock(x, g);
  };
  OptimizerOptions o = options(100);
  o.should_stop = [&] { return calls >= 5; };
  const OptimizerResult r = minimize(f, VectorXd{{-1.2, 1.0}}, o);
  EXPECT_EQ(r.reason, StopReason::stopped);
  EXPECT_EQ(calls, 5);
}

TEST_P(BothMethods, StopsWhenTheLossIsSmall) {
  OptimizerOptions o = options(1000);
  o.loss_tolerance = 1e-3;
  const OptimizerResult r =
      minimize(quadratic(VectorXd::Ones(2), VectorXd{{1.0, 4.0}}), VectorXd::Zero(2), o);
  EXPECT_EQ(r.reason, StopReason::loss_small);
  EXPECT_LE(r.best_loss, 1e-3);
}

TEST_P(BothMethods, AGradientPointingUphillEndsInAFailedLineSearchWithTheStartKept) {
  const Objective base = quadratic(VectorXd::Ones(2), VectorXd::Ones(2));
  const Objective wrong = [&](const VectorXd& x, VectorXd* g) {
    const double v = base(x, g);
    if (g) *g = -*g;
    return v;
  };
  const OptimizerResult r = minimize(wrong, VectorXd::Zero(2), options(50));
  EXPECT_EQ(r.reason, StopReason::line_search_failed) << r.message;
  EXPECT_EQ(r.best_theta, VectorXd::Zero(2));
  EXPECT_DOUBLE_EQ(r.best_loss, 1.0);
}

TEST_P(BothMethods, PassesOnWhatTheObjectiveThrows) {
  const Objective f = [](const VectorXd&, VectorXd*) -> double {
    throw std::runtime_error("tape too large");
  };
  EXPECT_THROW(minimize(f, VectorXd::Zero(1), options(5)), std::runtime_error);
}

INSTANTIATE_TEST_SUITE_P(Optimizer, BothMethods,
                         ::testing::Values(OptimizerMethod::lbfgs,
                                           OptimizerMethod::gradient_descent),
                         [](const auto& info) { return std::string(to_string(info.param)); });

TEST(Optimizer, RefusesOptionsOutOfRange) {
  OptimizerOptions o;
  o.max_iterations = 0;
  EXPECT_THROW(minimize(rosenbrock, VectorXd::Zero(2), o), std::invalid_argument);
  o.max_iterations = 5;
  o.time_budget = -1;
  EXPECT_THROW(minimize(rosenbrock, VectorXd::Zero(2), o), std::invalid_argument);
}

TEST(Optimizer, StallsWhenTheLossStopsFallingRelativeToItsSize) {
  // A loss with a floor of 1 (data no parameter can explain): near the
  // minimum it falls by far less than a millionth of itself per iteration
  // while its gradient is still well above the gradient tolerance.
  const Objective q = quadratic(VectorXd::Ones(2), VectorXd{{1.0, 4.0}});
  const Objective f = [&](const VectorXd& x, VectorXd* g) { return 1 + q(x, g); };
  for (OptimizerMethod m : {OptimizerMethod::lbfgs, OptimizerMethod::gradient_descent}) {
    OptimizerOptions o;
    o.method = m;
    o.max_iterations = 10000;
    o.stall_iterations = 3;
    o.stall_tolerance = 1e-6;
    o.gradient_tolerance = 1e-12;
    const OptimizerResult r = minimize(f, VectorXd::Zero(2), o);
    EXPECT_EQ(r.reason, StopReason::stalled) << to_string(m) << ": " << r.message;
    EXPECT_NEAR(r.best_loss, 1, 1e-5);
  }
}

// Two valleys, (x - 2)^2 (x + 1)^2 + x: the deeper one near x = -1. From
// x = 3 a descent ends in the shallower valley near 2; with a second start at
// -3 the search keeps the deeper, numbers its iterations on and says which
// start won.
TEST(Optimizer, SeveralStartsKeepTheLowestValley) {
  const Objective f = [](const VectorXd& x, VectorXd* g) {
    const double a = x[0] - 2, b = x[0] + 1;
    if (g) *g = VectorXd::Constant(1, 2 * a * b * b + 2 * a * a * b + 1);
    return a * a * b * b + x[0];
  };
  OptimizerOptions o;
  o.max_iterations = 50;
  const OptimizerResult one = minimize(f, VectorXd::Constant(1, 3.0), o);
  EXPECT_GT(one.best_theta[0], 1.5);
  std::vector<int> seen;
  const OptimizerResult two =
      minimize_from(f, {VectorXd::Constant(1, 3.0), VectorXd::Constant(1, -3.0)}, o,
                    [&](const IterationInfo& it) {
                      seen.push_back(it.iteration);
                      return true;
                    });
  EXPECT_LT(two.best_theta[0], -0.5);
  EXPECT_LT(two.best_loss, one.best_loss);
  EXPECT_NE(two.message.find("start 2 of 2"), std::string::npos) << two.message;
  for (std::size_t i = 1; i < seen.size(); ++i)
    EXPECT_EQ(seen[i], seen[i - 1] + 1);  // numbered on across the runs
  EXPECT_EQ(two.iterations, seen.back());
  // A stop that ends the search ends it: the second start never runs.
  int calls = 0;
  const OptimizerResult cut =
      minimize_from(f, {VectorXd::Constant(1, 3.0), VectorXd::Constant(1, -3.0)}, o,
                    [&](const IterationInfo&) { return ++calls < 3; });
  EXPECT_EQ(cut.reason, StopReason::stopped);
  EXPECT_GT(cut.best_theta[0], 1.5);
}

TEST(Optimizer, ParsesItsMethodNames) {
  OptimizerMethod m{};
  EXPECT_TRUE(parse_optimizer_method("gd", m));
  EXPECT_EQ(m, OptimizerMethod::gradient_descent);
  EXPECT_TRUE(parse_optimizer_method("lbfgs", m));
  EXPECT_EQ(m, OptimizerMethod::lbfgs);
  EXPECT_FALSE(parse_optimizer_method("adam", m));
}

}  // namespace
}  // namespace neurocloth
