// optimizer.h's names and its two entry points: the options checked once,
// then minimize() dispatches to its method (one file each) and both turn
// whatever ended the run into the Driver's result (optimizer_driver.h).
#include "learn/optim/optimizer.h"

#include <exception>
#include <stdexcept>
#include <string>

#include "learn/optim/optimizer_driver.h"

namespace neurocloth {
namespace {

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

OptimizerResult minimize(const Objective& objective, const Eigen::VectorXd& start,
                         const OptimizerOptions& options, const IterationCallback& callback) {
  check(options);
  optim_detail::Driver driver(objective, options, callback);
  try {
    if (options.method == OptimizerMethod::lbfgs)
      optim_detail::run_lbfgs(driver, start);
    else
      optim_detail::run_gradient_descent(driver, start);
    // LBFGSpp returns by itself only at a gradient within epsilon.
    return driver.finish(StopReason::gradient_small, "the gradient vanished");
  } catch (const optim_detail::StopRun& stop) {
    return driver.finish(stop.reason, stop.message);
  } catch (const optim_detail::ObjectiveThrew&) {
    return driver.finish(StopReason::stopped, "");  // rethrows the objective's exception
  } catch (const std::exception& e) {  // LBFGSpp: a line search that found no lower point
    return driver.finish(StopReason::line_search_failed,
                         std::string("the line search found no lower loss (") + e.what() + ")");
  }
}

OptimizerResult minimize_projected(const Objective& objective, const Projection& project,
                                   const Eigen::VectorXd& start, const OptimizerOptions& options,
                                   const IterationCallback& callback) {
  check(options);
  optim_detail::Driver driver(objective, options, callback);
  try {
    optim_detail::run_projected(driver, project, start);
    return driver.finish(StopReason::gradient_small, "the projected gradient vanished");
  } catch (const optim_detail::StopRun& stop) {
    return driver.finish(stop.reason, stop.message);
  } catch (const optim_detail::ObjectiveThrew&) {
    return driver.finish(StopReason::stopped, "");  // rethrows the objective's exception
  }
}

}  // namespace neurocloth
