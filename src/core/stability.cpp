#include "stability.h"

#include <cmath>
#include <limits>
#include <vector>

namespace neurocloth {

double stable_step_bound(const ClothNetwork& net, double limit) {
  const double inf = std::numeric_limits<double>::infinity();
  if (!std::isfinite(limit)) return inf;
  const std::size_t n = net.node_count();
  std::vector<double> k_sum(n, 0.0), d_sum(n, 0.0);
  const double slope = net.springs.function.max_slope();
  for (std::size_t s = 0; s < net.spring_count(); ++s) {
    for (int end : {net.springs.node_a[s], net.springs.node_b[s]}) {
      k_sum[end] += std::abs(net.springs.stiffness[s]) * slope;
      d_sum[end] += std::abs(net.springs.damping[s]);
    }
  }
  double bound = inf;
  for (std::size_t i = 0; i < n; ++i) {
    if (net.masses.free[i] == 0.0) continue;
    const double w = std::abs(net.masses.inverse_mass[i]);
    const double omega2 = 2.0 * w * k_sum[i];
    const double gamma = 2.0 * w * d_sum[i];
    const double denom = gamma + std::sqrt(gamma * gamma + limit * limit * omega2);
    if (denom > 0.0) bound = std::min(bound, limit * limit / denom);
  }
  return bound;
}

}  // namespace neurocloth
