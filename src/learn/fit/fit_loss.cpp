// The loss a fit minimises (fit_problem.h, paper eq. 18-19): the data term of
// a run at theta (the whole plan, or an online fit's window of it), with its
// gradient back through the model's weights to theta, plus the regulariser
// on whole runs; and the measures of it a report gives (RMS error,
// observations, tape size).
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <stdexcept>

#include "learn/fit/fit_problem_impl.h"
#include "learn/fit/rollout.h"
#include "learn/fit/step_plan.h"

namespace neurocloth {

double FitProblem::loss(const Eigen::VectorXd& theta, Eigen::VectorXd* gradient) {
  Impl& m = *impl_;
  if (static_cast<std::size_t>(theta.size()) != m.size)
    throw std::invalid_argument("FitProblem::loss: theta has the wrong size");
  if (!theta.allFinite()) {
    if (gradient) gradient->setConstant(static_cast<Eigen::Index>(m.size), std::nan(""));
    return std::nan("");
  }
  const Eigen::VectorXd in = m.inside(theta);
  m.apply(in);
  const double data = m.rollout->run(m.model, gradient ? &m.gradients : nullptr);
  if (!gradient) return data + m.regulariser(in, nullptr);
  if (!std::isfinite(data)) {
    gradient->setConstant(static_cast<Eigen::Index>(m.size), std::nan(""));
    return data;
  }
  m.chain(in, *gradient);
  const double r = m.regulariser(in, gradient);
  m.zero_outside(theta, in, *gradient);
  return data + r;
}

double FitProblem::window_loss(const Eigen::VectorXd& theta, const ClothState& state,
                               std::size_t first, std::size_t count, Eigen::VectorXd* gradient,
                               ClothState* end) {
  Impl& m = *impl_;
  if (first >= m.steps.count() || count == 0)
    throw std::invalid_argument("FitProblem::window_loss: no such steps");
  count = std::min(count, m.steps.count() - first);
  const Eigen::VectorXd in = m.inside(theta);
  m.apply(in);
  Rollout window(state, window_of(m.steps, first, count), window_of(m.observed, first, count),
                 m.settings.tape_budget_bytes);
  const double data = window.run(m.model, gradient ? &m.gradients : nullptr);
  if (end) *end = window.final_state();
  if (gradient) {
    if (std::isfinite(data)) {
      m.chain(in, *gradient);
      m.zero_outside(theta, in, *gradient);
    } else
      gradient->setConstant(static_cast<Eigen::Index>(m.size), std::nan(""));
  }
  return data;
}

double FitProblem::rms_error(const Eigen::VectorXd& theta) {
  Impl& m = *impl_;
  m.apply(m.inside(theta));
  const double data = m.rollout->run(m.model, nullptr);
  return std::sqrt(2.0 * data / static_cast<double>(std::max<std::size_t>(1, observations())));
}

std::size_t FitProblem::observations() const {
  return impl_->rollout ? impl_->rollout->data_count() : 0;
}
std::size_t FitProblem::peak_tape_bytes() const {
  return impl_->rollout->peak_tape_bytes();
}

}  // namespace neurocloth
