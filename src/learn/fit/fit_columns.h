#pragma once
// Each block of a fit's unknowns as one column: what the progress line,
// FITTED.loss.csv, the uncertainty summary and the window's plot show. A
// block of one value is that value; a per-element block (one per spring or
// node) is its mean, geometric for a log-space block, and its name says
// which ("spring_constant_geomean", "rest_length_mean").
#include <string>
#include <vector>

#include <Eigen/Core>

#include "learn/fit/fit_problem.h"

namespace neurocloth {

std::vector<std::string> block_names(const FitProblem& problem);
// Of FitProblem::values(theta): the values inside the scene's limits.
std::vector<double> block_values(const FitProblem& problem, const Eigen::VectorXd& theta);

}  // namespace neurocloth
