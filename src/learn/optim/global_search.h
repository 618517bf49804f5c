#pragma once
// A global first stage for fits whose gradients stall: a rough loss (a cloth
// flung hard enough to crumple), plateaus, several valleys. A small evolution
// strategy — separable CMA-ES (Hansen's CMA-ES with a diagonal covariance,
// Ros and Hansen 2008: linear cost in the dimension, for the tens of unknowns
// a family fit has) — samples the box around the start with forward runs
// alone, and the best points it found become the gradient fit's starts
// (minimize_from). Like optimizer.h, nothing here knows of cloth.
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace neurocloth {

struct GlobalSearchOptions {
  int evaluations = 200;  // objective runs in all (> 0)
  int population = 0;     // lambda, per generation; 0: 4 + 3 ln n
  int keep = 3;           // distinct best points returned
  unsigned seed = 1;      // the same seed, the same search
  // Asked before every evaluation: true ends the search there (Ctrl-C).
  std::function<bool()> should_stop;
};

struct GlobalSearchResult {
  std::vector<Eigen::VectorXd> best;  // lowest loss first, at most `keep`
  std::vector<double> losses;         // of `best`
  int evaluations = 0;
  int generations = 0;
  std::string message;  // one line: what it ran and found
};

// Minimises f (a NaN or infinite loss ranks last) over the box start ± width
// (every width > 0): the search works in the box's own coordinates (each
// unknown over its width), starts at `start` with a step of half the box, and
// keeps each sample inside it. Points closer than 5% of the box to a better
// one are not returned twice. Throws std::invalid_argument on options or
// widths out of range.
GlobalSearchResult global_search(const std::function<double(const Eigen::VectorXd&)>& f,
                                 const Eigen::VectorXd& start, const Eigen::VectorXd& width,
                                 const GlobalSearchOptions& options);

}  // namespace neurocloth
