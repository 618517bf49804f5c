// The paper's plain gradient descent (optimizer.h): Armijo backtracking, the
// step doubled after every accepted one, so there is no step size to tune and
// no step ever raises the loss.
#include <cmath>

#include "learn/optim/optimizer_driver.h"

namespace neurocloth {
namespace optim_detail {

// Plain gradient descent with the Armijo backtracking rule (optimizer.h).
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
        throw StopRun{StopReason::line_search_failed,
                      "no step along the gradient lowered the loss (the step fell below rounding)"};
    }
    driver.accept(x, f, g);
    step *= 2;
  }
}

}  // namespace optim_detail
}  // namespace neurocloth
