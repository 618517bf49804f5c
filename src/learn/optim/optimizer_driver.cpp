// The Driver's bodies (optimizer_driver.h): the best point of every
// evaluation, the budgets and the stop tests, once for every method, so that
// whatever stops a run the same best parameters and the same reason come back.
#include "learn/optim/optimizer_driver.h"

#include <chrono>
#include <cmath>
#include <exception>
#include <limits>
#include <string>

#include "core/io/physical_limits.h"

namespace neurocloth {
namespace optim_detail {

Driver::Driver(const Objective& objective, const OptimizerOptions& options,
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

double Driver::evaluate(const Vector& theta, Vector* gradient) {
  if (options_.should_stop && options_.should_stop())
    throw StopRun{StopReason::stopped, "stopped on request"};
  // The start is always evaluated: a budget shorter than one evaluation
  // still ends with the start's loss, not with none.
  if (options_.time_budget > 0 && result_.evaluations > 0 && elapsed() >= options_.time_budget)
    throw StopRun{StopReason::time_budget,
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
    if (result_.evaluations == 1) throw StopRun{StopReason::not_finite, what};
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

void Driver::accept(const Vector& theta, double loss, const Vector& gradient) {
  const int k = result_.iterations;
  const double seconds = elapsed();
  result_.history.push_back({k, loss, result_.evaluations, seconds});
  if (callback_ && !callback_({k, loss, result_.evaluations, seconds, theta}))
    throw StopRun{StopReason::stopped, "stopped on request after iteration " + std::to_string(k)};
  if (loss <= options_.loss_tolerance)
    throw StopRun{StopReason::loss_small, "the loss " + show_number(loss) +
                                              " is within the tolerance " +
                                              show_number(options_.loss_tolerance)};
  if (k == 0) start_gradient_ = gradient.norm();
  if (gradient.norm() <= options_.gradient_tolerance * start_gradient_)
    throw StopRun{StopReason::gradient_small, "the gradient's norm " +
                                                  show_number(gradient.norm()) + " is within " +
                                                  show_number(options_.gradient_tolerance) +
                                                  " of its start " + show_number(start_gradient_)};
  const int w = options_.stall_iterations;
  if (w > 0 && k >= w) {
    const double before = result_.history[result_.history.size() - 1 - w].loss;
    if (before - loss <= options_.stall_tolerance * std::abs(loss))
      throw StopRun{StopReason::stalled, "the loss fell by less than " +
                                             show_number(options_.stall_tolerance * 100) +
                                             "% over " + std::to_string(w) + " iterations"};
  }
  if (k >= options_.max_iterations)
    throw StopRun{
        StopReason::iteration_budget,
        "the budget of " + std::to_string(options_.max_iterations) + " iterations ran out"};
  if (options_.time_budget > 0 && seconds >= options_.time_budget)
    throw StopRun{StopReason::time_budget,
                  "the time budget of " + show_number(options_.time_budget) + " s ran out"};
  ++result_.iterations;
}

OptimizerResult Driver::finish(StopReason reason, std::string why) {
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

}  // namespace optim_detail
}  // namespace neurocloth
