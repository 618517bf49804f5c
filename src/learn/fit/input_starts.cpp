#include "learn/fit/input_starts.h"

#include "core/io/input_error.h"
#include "learn/optim/global_search.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

namespace neurocloth {

InputStarts input_fit_starts(FitProblem& problem, std::size_t extra) {
  InputStarts out;
  out.starts.push_back(problem.initial());
  std::vector<std::pair<std::size_t, const fuzzy::LinguisticVariable*>> inputs;
  for (const FitBlock& block : problem.blocks())
    if (const fuzzy::LinguisticVariable* v = problem.input_variable(block))
      inputs.emplace_back(block.offset, v);
  if (inputs.empty() || extra == 0) return out;
  std::size_t n = 1;  // points per input: the most with n^d <= kMaxInputGridPoints
  while (std::pow(double(n + 1), double(inputs.size())) <= double(kMaxInputGridPoints))
    ++n;
  std::size_t points = 1;
  for (std::size_t k = 0; k < inputs.size(); ++k)
    points *= n;
  std::vector<std::pair<double, Eigen::VectorXd>> tried;
  std::vector<std::size_t> at(inputs.size(), 0);
  for (std::size_t p = 0; p < points; ++p) {
    Eigen::VectorXd theta = out.starts.front();
    for (std::size_t k = 0; k < inputs.size(); ++k) {
      const fuzzy::LinguisticVariable& v = *inputs[k].second;
      theta[static_cast<Eigen::Index>(inputs[k].first)] =
          v.min + (v.max - v.min) * (double(at[k]) + 0.5) / double(n);
    }
    const double loss = problem.loss(theta, nullptr);
    if (std::isfinite(loss)) tried.emplace_back(loss, std::move(theta));
    for (std::size_t k = 0; k < inputs.size() && ++at[k] == n; ++k)
      at[k] = 0;  // the next grid point, odometer style
  }
  out.evaluated = points;
  std::stable_sort(tried.begin(), tried.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  for (std::size_t i = 0; i < tried.size() && i < extra; ++i)
    out.starts.push_back(std::move(tried[i].second));
  out.said = "a fit of the inputs: tried them on a grid of " + std::to_string(points) +
             " points; descending from the scene's own and the " +
             std::to_string(out.starts.size() - 1) + " best";
  return out;
}

InputStarts global_fit_starts(FitProblem& problem, const GlobalSearchOptions& options) {
  if (problem.size() > kMaxGlobalUnknowns)
    throw InputError("command line", "--global",
                     "a global search looks through at most " + std::to_string(kMaxGlobalUnknowns) +
                         " unknowns, and this fit has " + std::to_string(problem.size()) +
                         " (per-element weights): fit them without --global");
  InputStarts out;
  out.starts.push_back(problem.initial());
  const GlobalSearchResult r =
      global_search([&](const Eigen::VectorXd& theta) { return problem.loss(theta, nullptr); },
                    out.starts.front(), problem.search_width(), options);
  for (const Eigen::VectorXd& b : r.best)  // (!=, not a norm: GCC 12's AVX-512 reductions)
    if (b != out.starts.front()) out.starts.push_back(b);
  out.evaluated = static_cast<std::size_t>(r.evaluations);
  char best[64] = "no finite loss";
  if (!r.losses.empty()) std::snprintf(best, sizeof best, "best loss %.6g", r.losses.front());
  out.said = r.message + ", " + best + "; descending from the scene's own start and the " +
             std::to_string(out.starts.size() - 1) + " best";
  return out;
}

}  // namespace neurocloth
