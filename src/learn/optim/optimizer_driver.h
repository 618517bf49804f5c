#pragma once
// What every method behind minimize() and minimize_projected() shares,
// private to optim/: the Driver that every evaluation and every accepted
// point go through, so that each method keeps the best point, honours the
// budgets and stops for the same reasons without repeating them; and the
// methods' entry points, so that optimizer.cpp can dispatch to them.
#include <exception>
#include <string>

#include <Eigen/Core>

#include "learn/optim/optimizer.h"

namespace neurocloth {
namespace optim_detail {

using Vector = Eigen::VectorXd;

// Thrown through LBFGSpp (or the descent loop) to end the run: the driver has
// already kept the best point, this carries why.
struct StopRun {
  StopReason reason;
  std::string message;
};
// The objective itself threw: passed on once the run is unwound.
struct ObjectiveThrew {};

// What all methods share: every evaluation goes through evaluate() (the best
// point, the budgets, NaN), every accepted point through accept() (history,
// callback, the stop tests).
class Driver {
 public:
  Driver(const Objective& objective, const OptimizerOptions& options,
         const IterationCallback& callback);

  double evaluate(const Vector& theta, Vector* gradient);
  // The point the current iteration ended at (the start for iteration 0).
  void accept(const Vector& theta, double loss, const Vector& gradient);
  OptimizerResult finish(StopReason reason, std::string why);

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

// The methods, one file each: lbfgs.cpp, gradient_descent.cpp and
// projected_gradient.cpp. Each runs from `start` until the driver or the
// method itself throws StopRun (or ObjectiveThrew); a return means the
// gradient vanished (only LBFGSpp ever returns by itself).
void run_lbfgs(Driver& driver, const Vector& start);
void run_gradient_descent(Driver& driver, const Vector& start);
void run_projected(Driver& driver, const Projection& project, const Vector& start);

}  // namespace optim_detail
}  // namespace neurocloth
