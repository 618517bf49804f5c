// minimize_from (optimizer.h): minimize() from several starts, one run after
// another, as one search to its caller (iterations numbered on, one time
// budget); apart from the methods, as it only calls minimize().
#include <chrono>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "learn/optim/optimizer.h"

namespace neurocloth {

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
