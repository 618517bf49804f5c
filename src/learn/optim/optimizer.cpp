#include "learn/optim/optimizer.h"

#include <LBFGS.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <limits>
#include <stdexcept>
#include <vector>

#include "core/io/physical_limits.h"

namespace neurocloth {
namespace {

using Vector = Eigen::VectorXd;

// Thrown through LBFGSpp (or the descent loop) to end the run: the driver has
// already kept the best point, this carries why.
struct Stop {
  StopReason reason;
  std::string message;
};
// The objective itself threw: passed on once the run is unwound.
struct ObjectiveThrew {};

// What both methods share: every evaluation goes through evaluate() (the best
// point, the budgets, NaN), every accepted point through accept() (history,
// callback, the stop tests).
class Driver {
 public:
  Driver(const Objective& objective, const OptimizerOptions& options,
         const IterationCallback& callback)
      : objective_(objective), options_(options), callback_(callback) {
    if (!options_.clock)
      options_.clock = [] {
        return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
            .count();
      };
    start_ = options_.clock();
    result_.best_loss = std::numeric_limits<double>::quiet_NaN();
  }

  double evaluate(const Vector& theta, Vector* gradient) {
    if (options_.should_stop && options_.should_stop())
      throw Stop{StopReason::stopped, "stopped on request"};
    // The start is always evaluated: a budget shorter than one evaluation
    // still ends with the start's loss, not with none.
    if (options_.time_budget > 0 && result_.evaluations > 0 && elapsed() >= options_.time_budget)
      throw Stop{StopReason::time_budget,
                 "the time budget of " + show_number(options_.time_budget) + " s ran out"};
    double loss = 0;
    try {
      loss = objective_(theta, gradient);
    } catch (...) {
      thrown_ = std::current_exception();
      throw ObjectiveThrew{};
    }
    ++result_.evaluations;
    if (result_.best_theta.size() == 0) result_.best_theta = theta;  // the start, at least
    const bool finite_gradient = !gradient || gradient->allFinite();
    if (!std::isfinite(loss) || !finite_gradient) {
      const std::string what = std::string(std::isfinite(loss) ? "the gradient" : "the loss") +
                               " came back " + (std::isnan(loss) ? "NaN" : "not finite") +
                               " at evaluation " + std::to_string(result_.evaluations);
      // At the start there is nothing to go back to. Later it is a trial step
      // too long (a cloth too stiff for its step blows up): the line search
      // sees an infinite loss and shortens the step; if every trial blows up,
      // the search fails and finish() says why.
      if (result_.evaluations == 1) throw Stop{StopReason::not_finite, what};
      last_not_finite_ = what;
      if (gradient) gradient->setZero();
      return std::numeric_limits<double>::infinity();
    }
    last_not_finite_.clear();
    if (!(loss >= result_.best_loss)) {  // also when best_loss is still NaN
      result_.best_loss = loss;
      result_.best_theta = theta;
    }
    return loss;
  }

  // The point the current iteration ended at (the start for iteration 0).
  void accept(const Vector& theta, double loss, const Vector& gradient) {
    const int k = result_.iterations;
    const double seconds = elapsed();
    result_.history.push_back({k, loss, result_.evaluations, seconds});
    if (callback_ && !callback_({k, loss, result_.evaluations, seconds, theta}))
      throw Stop{StopReason::stopped, "stopped on request after iteration " + std::to_string(k)};
    if (loss <= options_.loss_tolerance)
      throw Stop{StopReason::loss_small, "the loss " + show_number(loss) +
                                             " is within the tolerance " +
                                             show_number(options_.loss_tolerance)};
    if (k == 0) start_gradient_ = gradient.norm();
    if (gradient.norm() <= options_.gradient_tolerance * start_gradient_)
      throw Stop{StopReason::gradient_small, "the gradient's norm " + show_number(gradient.norm()) +
                                                 " is within " +
                                                 show_number(options_.gradient_tolerance) +
                                                 " of its start " + show_number(start_gradient_)};
    const int w = options_.stall_iterations;
    if (w > 0 && k >= w) {
      const double before = result_.history[result_.history.size() - 1 - w].loss;
      if (before - loss <= options_.stall_tolerance * std::abs(loss))
        throw Stop{StopReason::stalled, "the loss fell by less than " +
                                            show_number(options_.stall_tolerance * 100) +
                                            "% over " + std::to_string(w) + " iterations"};
    }
    if (k >= options_.max_iterations)
      throw Stop{
          StopReason::iteration_budget,
          "the budget of " + std::to_string(options_.max_iterations) + " iterations ran out"};
    if (options_.time_budget > 0 && seconds >= options_.time_budget)
      throw Stop{StopReason::time_budget,
                 "the time budget of " + show_number(options_.time_budget) + " s ran out"};
    ++result_.iterations;
  }

  OptimizerResult finish(StopReason reason, std::string why) {
    if (thrown_) std::rethrow_exception(thrown_);
    // A search that ended on a blown-up trial failed because of it: a NaN stop.
    if (reason == StopReason::line_search_failed && !last_not_finite_.empty()) {
      reason = StopReason::not_finite;
      why = last_not_finite_ + " and no shorter step along the search direction was finite";
    }
    result_.reason = reason;
    result_.seconds = elapsed();
    // accept() counts an iteration only once it passed every test.
    if (!result_.history.empty()) result_.iterations = result_.history.back().iteration;
    if (std::isnan(result_.best_loss))
      result_.message = why + "; no evaluation had a finite loss, the start point is returned";
    else
      result_.message =
          why + "; the best parameters seen (loss " + show_number(result_.best_loss) + ") are kept";
    return result_;
  }

  const OptimizerOptions& options() const { return options_; }

 private:
  double elapsed() const { return options_.clock() - start_; }

  const Objective& objective_;
  OptimizerOptions options_;
  const IterationCallback& callback_;
  double start_ = 0;
  double start_gradient_ = 0;    // |grad| at iteration 0
  std::string last_not_finite_;  // the last evaluation's, when it was not finite
  OptimizerResult result_;
  std::exception_ptr thrown_;
};

// LBFGSpp's interface to the objective, with the hook its iterations end in.
struct LbfgsObjective {
  Driver& driver;
  bool started = false;

  double operator()(const Vector& theta, Vector& gradient) {
    const double loss = driver.evaluate(theta, &gradient);
    if (!started) {  // LBFGSpp's first evaluation is the start point
      started = true;
      driver.accept(theta, loss, gradient);
    }
    return loss;
  }
};

// LBFGSpp's backtracking line search, and then the end of the iteration (it
// has no callback of its own; a line search ends every iteration).
template <typename Scalar>
class LineSearchThenHook {
 public:
  template <typename Foo>
  static void LineSearch(Foo& f, Scalar& fx, Vector& x, Vector& grad, Scalar& step,
                         const Vector& drt, const Vector& xp,
                         const LBFGSpp::LBFGSParam<Scalar>& param) {
    LBFGSpp::LineSearchBacktracking<Scalar>::LineSearch(f, fx, x, grad, step, drt, xp, param);
    f.driver.accept(x, fx, grad);
  }
};

void run_lbfgs(Driver& driver, const Vector& start) {
  LBFGSpp::LBFGSParam<double> param;
  param.m = driver.options().lbfgs_memory;
  param.epsilon = 0;  // the gradient test is the driver's (relative to the start)
  param.epsilon_rel = 0;
  param.past = 0;            // the stall test is the driver's
  param.max_iterations = 0;  // so is the budget
  param.linesearch = LBFGSpp::LBFGS_LINESEARCH_BACKTRACKING_WOLFE;
  param.max_linesearch = 40;
  LBFGSpp::LBFGSSolver<double, LineSearchThenHook> solver(param);
  LbfgsObjective f{driver};
  Vector x = start;
  double fx = 0;
  solver.minimize(f, x, fx);
}

// Plain gradient descent with the Armijo backtracking rule (header comment).
void run_gradient_descent(Driver& driver, const Vector& start) {
  constexpr double kArmijo = 1e-4;
  Vector x = start, g(start.size()), trial_g(start.size());
  double f = driver.evaluate(x, &g);
  driver.accept(x, f, g);
  double step = 1 / g.norm();  // a first trial of unit length in theta
  for (;;) {
    const double slope = g.squaredNorm();
    for (;;) {
      const Vector trial = x - step * g;
      const double trial_f = driver.evaluate(trial, &trial_g);
      if (trial_f <= f - kArmijo * step * slope) {
        x = trial;
        f = trial_f;
        g.swap(trial_g);
        break;
      }
      step *= 0.5;
      if (step * std::sqrt(slope) <= 1e-15 * (1 + x.norm()))
        throw Stop{StopReason::line_search_failed,
                   "no step along the gradient lowered the loss (the step fell below rounding)"};
    }
    driver.accept(x, f, g);
    step *= 2;
  }
}

// SPG (optimizer.h): the projected gradient P(x - g) - x stands for the
// gradient in the driver's stop test, as it vanishes at a constrained optimum.
void run_projected(Driver& driver, const Projection& project, const Vector& start) {
  constexpr double kArmijo = 1e-4, kMinStep = 1e-10, kMaxStep = 1e10;
  constexpr std::size_t kMemory = 10;  // losses the non-monotone test looks back on
  Vector x = project(start), g(x.size()), trial_g(x.size());
  double f = driver.evaluate(x, &g);
  std::vector<double> recent = {f};
  auto projected_gradient = [&](const Vector& at, const Vector& grad) -> Vector {
    return project(at - grad) - at;
  };
  Vector pg = projected_gradient(x, g);
  driver.accept(x, f, pg);
  double lambda = std::clamp(1 / std::max(pg.cwiseAbs().maxCoeff(), 1e-300), kMinStep, kMaxStep);
  for (;;) {
    const Vector d = project(x - lambda * g) - x;
    const double slope = g.dot(d);
    if (!(slope < 0))
      throw Stop{StopReason::line_search_failed,
                 "the projected step does not lower the loss (a constrained optimum, to rounding)"};
    const double reference = *std::max_element(recent.begin(), recent.end());
    double t = 1, trial_f = 0;
    for (int tries = 0;; ++tries) {
      trial_f = driver.evaluate(x + t * d, &trial_g);
      if (trial_f <= reference + kArmijo * t * slope) break;
      if (tries == 40)
        throw Stop{StopReason::line_search_failed,
                   "no step towards the projected gradient lowered the loss"};
      // The minimum of the quadratic through f, the slope and the trial, kept
      // within [0.1 t, 0.5 t]; halved when the trial was not finite.
      const double q =
          std::isfinite(trial_f) ? -slope * t * t / (2 * (trial_f - f - slope * t)) : 0.5 * t;
      t = std::clamp(q, 0.1 * t, 0.5 * t);
    }
    const Vector s = t * d, y = trial_g - g;
    x += s;
    f = trial_f;
    g.swap(trial_g);
    recent.push_back(f);
    if (recent.size() > kMemory) recent.erase(recent.begin());
    const double sy = s.dot(y);
    lambda = sy > 0 ? std::clamp(s.squaredNorm() / sy, kMinStep, kMaxStep) : kMaxStep;
    pg = projected_gradient(x, g);
    driver.accept(x, f, pg);
  }
}

void check(const OptimizerOptions& o) {
  if (o.max_iterations < 1) throw std::invalid_argument("max_iterations must be at least 1");
  if (!(o.time_budget >= 0)) throw std::invalid_argument("the time budget must be >= 0");
  if (!(o.loss_tolerance >= 0) || !(o.gradient_tolerance >= 0) || !(o.stall_tolerance >= 0) ||
      o.stall_iterations < 0)
    throw std::invalid_argument("tolerances must be >= 0");
  if (o.lbfgs_memory < 1) throw std::invalid_argument("lbfgs_memory must be at least 1");
}

}  // namespace

bool parse_optimizer_method(const std::string& name, OptimizerMethod& method) {
  if (name == "lbfgs")
    method = OptimizerMethod::lbfgs;
  else if (name == "gd")
    method = OptimizerMethod::gradient_descent;
  else
    return false;
  return true;
}

const char* to_string(OptimizerMethod m) {
  return m == OptimizerMethod::lbfgs ? "lbfgs" : "gd";
}

const char* to_string(StopReason r) {
  switch (r) {
    case StopReason::loss_small:
      return "loss_small";
    case StopReason::gradient_small:
      return "gradient_small";
    case StopReason::stalled:
      return "stalled";
    case StopReason::iteration_budget:
      return "iteration_budget";
    case StopReason::time_budget:
      return "time_budget";
    case StopReason::stopped:
      return "stopped";
    case StopReason::not_finite:
      return "not_finite";
    case StopReason::line_search_failed:
      return "line_search_failed";
  }
  return "?";
}

bool converged(StopReason r) {
  return r == StopReason::loss_small || r == StopReason::gradient_small || r == StopReason::stalled;
}

OptimizerResult minimize(const Objective& objective, const Vector& start,
                         const OptimizerOptions& options, const IterationCallback& callback) {
  check(options);
  Driver driver(objective, options, callback);
  try {
    if (options.method == OptimizerMethod::lbfgs)
      run_lbfgs(driver, start);
    else
      run_gradient_descent(driver, start);
    // LBFGSpp returns by itself only at a gradient within epsilon.
    return driver.finish(StopReason::gradient_small, "the gradient vanished");
  } catch (const Stop& stop) {
    return driver.finish(stop.reason, stop.message);
  } catch (const ObjectiveThrew&) {
    return driver.finish(StopReason::stopped, "");  // rethrows the objective's exception
  } catch (const std::exception& e) {  // LBFGSpp: a line search that found no lower point
    return driver.finish(StopReason::line_search_failed,
                         std::string("the line search found no lower loss (") + e.what() + ")");
  }
}

OptimizerResult minimize_projected(const Objective& objective, const Projection& project,
                                   const Vector& start, const OptimizerOptions& options,
                                   const IterationCallback& callback) {
  check(options);
  Driver driver(objective, options, callback);
  try {
    run_projected(driver, project, start);
    return driver.finish(StopReason::gradient_small, "the projected gradient vanished");
  } catch (const Stop& stop) {
    return driver.finish(stop.reason, stop.message);
  } catch (const ObjectiveThrew&) {
    return driver.finish(StopReason::stopped, "");  // rethrows the objective's exception
  }
}

OptimizerResult minimize_from(const Objective& objective,
                              const std::vector<Eigen::VectorXd>& starts,
                              const OptimizerOptions& options, const IterationCallback& callback) {
  if (starts.empty()) throw std::invalid_argument("minimize_from: no start");
  if (starts.size() == 1) return minimize(objective, starts.front(), options, callback);
  OptimizerOptions o = options;
  if (!o.clock)
    o.clock = [] {
      return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
          .count();
    };
  const double t0 = o.clock();
  OptimizerResult best;
  best.best_loss = std::nan("");
  int iterations = 0, evaluations = 0, winner = 0;
  for (std::size_t k = 0; k < starts.size(); ++k) {
    const int offset = iterations + (k > 0 ? 1 : 0);  // each run's start is an iteration too
    const int evaluated = evaluations;
    const double shift = o.clock() - t0;
    OptimizerOptions run = o;
    if (options.time_budget > 0) {
      run.time_budget = options.time_budget - shift;
      if (!(run.time_budget > 0)) break;
    }
    OptimizerResult r = minimize(objective, starts[k], run, [&](const IterationInfo& it) {
      if (!callback) return true;
      const IterationInfo shifted{it.iteration + offset, it.loss, it.evaluations + evaluated,
                                  it.seconds + shift, it.theta};
      return callback(shifted);
    });
    iterations = offset + r.iterations;
    evaluations += r.evaluations;
    const bool lower = std::isfinite(r.best_loss) && !(r.best_loss >= best.best_loss);
    if (k == 0 || lower) {
      best = std::move(r);
      winner = static_cast<int>(k);
    } else if (r.reason == StopReason::stopped || r.reason == StopReason::time_budget) {
      best.reason = r.reason;  // what cut the search short, with the best point kept
      best.message = r.message;
    }
    if (best.reason == StopReason::stopped || best.reason == StopReason::time_budget) break;
  }
  best.iterations = iterations;
  best.evaluations = evaluations;
  best.seconds = o.clock() - t0;
  best.message += " (start " + std::to_string(winner + 1) + " of " + std::to_string(starts.size()) +
                  " gave the lowest loss)";
  return best;
}

}  // namespace neurocloth
