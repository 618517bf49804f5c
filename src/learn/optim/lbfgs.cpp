// L-BFGS (optimizer.h) through LBFGSpp: adapters that route LBFGSpp's
// evaluations and the end of each of its iterations through the Driver, and
// settings that leave every stop test to it, so L-BFGS stops for the same
// reasons as the other methods.
#include <LBFGS.h>

#include "learn/optim/optimizer_driver.h"

namespace neurocloth {
namespace optim_detail {
namespace {

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

}  // namespace

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

}  // namespace optim_detail
}  // namespace neurocloth
