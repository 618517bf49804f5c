#pragma once
// Where a fit of a material's inputs (input.NAME) starts. A rule base with MIN
// and MAX is flat in places (a rule whose activation another input decides
// does not feel this one) and need not be monotone (cloth.fcl's spring
// constant is 428 N/m at elasticity 0.45 and at 0.575), so one descent from
// the scene's own inputs can stop on a plateau or in the other valley. The fit
// descends from several starts (optimizer.h, minimize_from): the scene's own
// inputs, then the best few points of a coarse grid over the inputs' ranges
// (n per input at (i + 1/2) / n of the range: on the terms' slopes more than
// at their peaks, where a membership is flat), found by forward runs alone.
// Any other fit may ask for the same from a global search (global_fit_starts).
#include <string>
#include <vector>

#include <Eigen/Core>

#include "learn/fit/fit_problem.h"

namespace neurocloth {

// At most this many grid points are evaluated (4 per input for three inputs).
inline constexpr std::size_t kMaxInputGridPoints = 64;

struct InputStarts {
  std::vector<Eigen::VectorXd> starts;  // the scene's own first; just it for other fits
  std::size_t evaluated = 0;            // grid points run
  std::string said;                     // one line for the terminal ("" for other fits)
};

// The scene's own start and the `extra` grid points of lowest loss (those
// with a finite one).
InputStarts input_fit_starts(FitProblem& problem, std::size_t extra = 3);

// For any fit (`fit --global es`): the scene's own start and the best points a
// global search (global_search.h) found in the box FitProblem::search_width
// gives, by forward runs alone. At most kMaxGlobalUnknowns unknowns: an
// evolution strategy's samples grow with the dimension (refused by name beyond).
inline constexpr std::size_t kMaxGlobalUnknowns = 64;
struct GlobalSearchOptions;
InputStarts global_fit_starts(FitProblem& problem, const GlobalSearchOptions& options);

}  // namespace neurocloth
