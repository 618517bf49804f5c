#include "learn/fit/online_adaptation.h"

#include <cmath>
#include <stdexcept>

namespace neurocloth {

OnlineAdaptation::OnlineAdaptation(FitProblem& problem, const OnlineSettings& settings)
    : problem_(problem),
      settings_(settings),
      theta_(problem.initial()),
      state_(problem.initial_state()) {
  if (settings.window == 0) throw std::invalid_argument("the online window must be >= 1 step");
  if (!(settings.learning_rate > 0 && settings.learning_rate <= 10))
    throw std::invalid_argument("the online learning rate must be in (0, 10]");
  step_ = Eigen::VectorXd::Constant(theta_.size(), settings.learning_rate);
  last_gradient_ = Eigen::VectorXd::Zero(theta_.size());
}

OnlineAdaptation::Update OnlineAdaptation::advance() {
  Update u;
  if (done()) return u;
  const std::size_t count = std::min(settings_.window, problem_.step_count() - next_);
  if (settings_.follow_reference)
    u.followed = problem_.reference_state(problem_.step_time(next_), state_);
  Eigen::VectorXd g;
  ClothState end;
  u.loss = problem_.window_loss(theta_, state_, next_, count, &g, &end);
  u.observed = problem_.window_observations(next_, count);
  if (u.observed > 0) u.rms_m = std::sqrt(2.0 * u.loss / static_cast<double>(u.observed));
  next_ += count;
  u.time = next_ < problem_.step_count() ? problem_.step_time(next_) : problem_.duration();
  // A non-finite window (the cloth blew up with these weights) ends the run:
  // no finite state is left to go on from. The weights stay as they were.
  if (!std::isfinite(u.loss) || !g.allFinite()) {
    next_ = problem_.step_count();
    return u;
  }
  state_ = std::move(end);
  const double lo = settings_.learning_rate * 1e-3, hi = settings_.learning_rate;
  bool any = false;
  for (Eigen::Index i = 0; i < theta_.size(); ++i) {
    if (g[i] == 0.0) continue;
    any = true;
    const double agree = g[i] * last_gradient_[i];
    if (agree > 0) step_[i] = std::min(hi, step_[i] * 1.2);
    if (agree < 0) step_[i] = std::max(lo, step_[i] * 0.5);
    theta_[i] -= (g[i] > 0 ? 1.0 : -1.0) * step_[i];
    last_gradient_[i] = g[i];
  }
  u.updated = any;
  return u;
}

}  // namespace neurocloth
