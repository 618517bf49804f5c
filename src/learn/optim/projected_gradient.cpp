// The spectral projected gradient method (SPG; optimizer.h's
// minimize_projected): descent over a convex set for unknowns with bounds,
// on its own because its search and its stop test differ from the
// unconstrained methods'.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "learn/optim/optimizer_driver.h"

namespace neurocloth {
namespace optim_detail {

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
      throw StopRun{
          StopReason::line_search_failed,
          "the projected step does not lower the loss (a constrained optimum, to rounding)"};
    const double reference = *std::max_element(recent.begin(), recent.end());
    double t = 1, trial_f = 0;
    for (int tries = 0;; ++tries) {
      trial_f = driver.evaluate(x + t * d, &trial_g);
      if (trial_f <= reference + kArmijo * t * slope) break;
      if (tries == 40)
        throw StopRun{StopReason::line_search_failed,
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

}  // namespace optim_detail
}  // namespace neurocloth
