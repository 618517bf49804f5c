#include "learn/fit/fit_columns.h"

#include <cmath>

namespace neurocloth {

std::vector<std::string> block_names(const FitProblem& problem) {
  std::vector<std::string> names;
  for (const FitBlock& b : problem.blocks())
    names.push_back(b.count == 1 ? b.name : b.name + (b.log_space ? "_geomean" : "_mean"));
  return names;
}

std::vector<double> block_values(const FitProblem& problem, const Eigen::VectorXd& theta) {
  const Eigen::VectorXd v = problem.values(theta);
  std::vector<double> out;
  for (const FitBlock& b : problem.blocks()) {
    if (b.count == 1) {
      out.push_back(v[Eigen::Index(b.offset)]);
      continue;
    }
    double sum = 0;  // a plain loop: GCC 12 misreads Eigen's AVX-512 reductions
    for (std::size_t i = b.offset; i < b.offset + b.count; ++i)
      sum += b.log_space ? std::log(v[Eigen::Index(i)]) : v[Eigen::Index(i)];
    const double mean = sum / double(b.count);
    out.push_back(b.log_space ? std::exp(mean) : mean);
  }
  return out;
}

}  // namespace neurocloth
