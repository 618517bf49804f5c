#include "learn/optim/uncertainty.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace neurocloth {
namespace {

// Values and first-order standard deviations, with no verdict from the covariance.
ParameterUncertainty describe(const UncertainParameter& p, double theta) {
  ParameterUncertainty u;
  u.name = p.name;
  u.value = p.log_space ? std::exp(theta) : theta;
  u.sd = u.relative_sd = std::numeric_limits<double>::quiet_NaN();
  return u;
}

}  // namespace

const char* to_string(Determination d) {
  switch (d) {
    case Determination::determined:
      return "determined";
    case Determination::poorly_determined:
      return "poorly determined";
    case Determination::not_determined:
      return "not determined";
  }
  return "?";
}

UncertaintyReport estimate_uncertainty(const Objective& objective, const Eigen::VectorXd& theta,
                                       double loss, std::size_t data,
                                       const std::vector<UncertainParameter>& parameters,
                                       const UncertaintyOptions& options) {
  const std::size_t P = static_cast<std::size_t>(theta.size());
  if (parameters.size() != P)
    throw std::invalid_argument("estimate_uncertainty: one parameter description per unknown");
  UncertaintyReport r;
  r.data = data;
  for (std::size_t i = 0; i < P; ++i)
    r.parameters.push_back(describe(parameters[i], theta[Eigen::Index(i)]));
  if (P > options.max_parameters) {
    r.skipped = std::to_string(P) + " unknowns (more than " +
                std::to_string(options.max_parameters) +
                "): the Hessian would cost 2 gradients each; skipped";
    return r;
  }
  if (data <= P) {
    r.skipped = "no more data (" + std::to_string(data) + ") than unknowns (" + std::to_string(P) +
                "): the residual variance is not defined";
    return r;
  }
  if (!std::isfinite(loss)) {
    r.skipped = "the loss at the optimum is not finite";
    return r;
  }

  // H by central differences of the gradient, one column per unknown.
  const Eigen::Index n = Eigen::Index(P);
  Eigen::MatrixXd H(n, n);
  Eigen::VectorXd plus(n), minus(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double h = options.step * std::max(1.0, std::abs(theta[i]));
    Eigen::VectorXd x = theta;
    x[i] = theta[i] + h;
    const double fp = objective(x, &plus);
    x[i] = theta[i] - h;
    const double fm = objective(x, &minus);
    r.gradient_calls += 2;
    if (!std::isfinite(fp) || !std::isfinite(fm) || !plus.allFinite() || !minus.allFinite()) {
      r.skipped = "the gradient is not finite beside the optimum (" +
                  parameters[std::size_t(i)].name + " changed by " + std::to_string(h) + ")";
      return r;
    }
    H.col(i) = (plus - minus) / (2 * h);
  }
  r.hessian = 0.5 * (H + H.transpose());

  // covariance = s^2 H^-1 over the directions H sees; the flat ones are left out.
  r.residual_variance = 2 * loss / double(data - P);
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(r.hessian);
  const Eigen::VectorXd& lambda = eigen.eigenvalues();  // increasing
  const Eigen::MatrixXd& V = eigen.eigenvectors();
  const double largest = std::max(lambda.cwiseAbs().maxCoeff(), 0.0);
  r.covariance = Eigen::MatrixXd::Zero(n, n);
  Eigen::VectorXd flat_share = Eigen::VectorXd::Zero(n);
  for (Eigen::Index j = 0; j < n; ++j) {
    if (!(lambda[j] > options.flat_ratio * largest)) {
      ++r.flat_directions;
      flat_share += V.col(j).cwiseAbs2();
      continue;
    }
    r.covariance += V.col(j) * V.col(j).transpose() / lambda[j];
  }
  r.covariance *= r.residual_variance;
  r.computed = true;

  for (Eigen::Index i = 0; i < n; ++i) {
    ParameterUncertainty& u = r.parameters[std::size_t(i)];
    const double sd_theta = std::sqrt(std::max(0.0, r.covariance(i, i)));
    if (parameters[std::size_t(i)].log_space) {
      u.relative_sd = sd_theta;  // d(log v) = dv / v
      u.sd = u.value * sd_theta;
    } else {
      u.sd = sd_theta;
      u.relative_sd =
          u.value != 0 ? sd_theta / std::abs(u.value) : std::numeric_limits<double>::infinity();
    }
    if (flat_share[i] > options.flat_share)
      u.verdict = Determination::not_determined;
    else if (u.relative_sd > options.poor_relative_sd)
      u.verdict = Determination::poorly_determined;
  }
  return r;
}

}  // namespace neurocloth
