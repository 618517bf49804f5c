#pragma once
// How well the data determined each fitted parameter. At the optimum of a
// least-squares loss E(theta) = 1/2 |r(theta)|^2 over N data, the Hessian H is
// close to the Gauss-Newton matrix J^T J, the residual variance is
// s^2 = 2E / (N - P) for P unknowns, and the parameters' covariance is
// s^2 H^-1. H comes from central differences of the exact gradient (2P
// gradient calls), so it costs P times a fit's iteration: it is skipped above
// a cap (per-element fits). A direction along which H is flat (an eigenvalue
// tiny against the largest) is one the data does not see: parameters lying
// along it are "not determined", whatever the arithmetic would say.
#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "learn/optim/optimizer.h"

namespace neurocloth {

enum class Determination { determined, poorly_determined, not_determined };
const char* to_string(Determination d);

// One unknown of theta, as a user knows it.
struct UncertainParameter {
  std::string name;
  bool log_space = false;  // theta holds log(value)
};

struct UncertaintyOptions {
  std::size_t max_parameters = 32;  // above: skipped
  // Central-difference step in theta: step * max(1, |theta_i|).
  double step = 1e-4;
  // A relative standard deviation above this is "poorly determined".
  double poor_relative_sd = 0.1;
  // An eigenvalue of H at most this times the largest (or negative) is a
  // direction the data does not determine.
  double flat_ratio = 1e-9;
  // A parameter whose axis has more than this share (squared cosine) in the
  // flat directions is "not determined".
  double flat_share = 0.01;
};

struct ParameterUncertainty {
  std::string name;
  double value = 0;        // exp(theta) for log-space parameters
  double sd = 0;           // standard deviation, in the value's unit (first order)
  double relative_sd = 0;  // sd / |value| (for log space: the sd of log(value))
  Determination verdict = Determination::determined;
};

struct UncertaintyReport {
  bool computed = false;
  std::string skipped;           // why not, when not computed
  std::size_t data = 0;          // N: scalar residuals
  double residual_variance = 0;  // s^2
  int gradient_calls = 0;
  int flat_directions = 0;
  Eigen::MatrixXd hessian;     // of E in theta, symmetrised
  Eigen::MatrixXd covariance;  // of theta, over the determined directions
  std::vector<ParameterUncertainty> parameters;
};

// At `theta` (an optimum of `objective`, whose value there is `loss`), with
// `data` scalar residuals (3 per observed node position). Throws
// std::invalid_argument when `parameters` does not match theta. A gradient
// that is not finite at a difference point makes the report skipped, not an
// exception.
UncertaintyReport estimate_uncertainty(const Objective& objective, const Eigen::VectorXd& theta,
                                       double loss, std::size_t data,
                                       const std::vector<UncertainParameter>& parameters,
                                       const UncertaintyOptions& options = {});

}  // namespace neurocloth
