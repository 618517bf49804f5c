#include "core/integrators/stability.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/network/scene_module.h"

namespace neurocloth {

double stable_step_bound(const ClothNetwork& net, double limit) {
  std::vector<double> k_sum, d_sum;
  return stable_step_bound(net, limit, k_sum, d_sum);
}

double stable_step_bound(const ClothNetwork& net, double limit, std::vector<double>& k_sum,
                         std::vector<double>& d_sum, bool with_damping) {
  const double inf = std::numeric_limits<double>::infinity();
  if (!std::isfinite(limit)) return inf;
  const std::size_t n = net.node_count();
  k_sum.assign(n, 0.0);
  d_sum.assign(n, 0.0);
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
    const double gamma = with_damping ? 2.0 * w * d_sum[i] : 0.0;
    const double denom = gamma + std::sqrt(gamma * gamma + limit * limit * omega2);
    if (denom > 0.0) bound = std::min(bound, limit * limit / denom);
  }
  return bound;
}

double explicit_euler_step_bound(const ClothNetwork& net) {
  std::vector<double> d_sum;
  return explicit_euler_step_bound(net, d_sum);
}

double explicit_euler_step_bound(const ClothNetwork& net, std::vector<double>& d_sum) {
  double bound = std::numeric_limits<double>::infinity();
  const double slope = net.springs.function.max_slope();
  d_sum.assign(net.node_count(), 0.0);
  for (std::size_t s = 0; s < net.spring_count(); ++s) {
    const double k = std::abs(net.springs.stiffness[s]) * slope;
    const double d = std::abs(net.springs.damping[s]);
    if (k > 0) bound = std::min(bound, d / k);  // underdamped modes: h < gamma / omega^2
    for (int end : {net.springs.node_a[s], net.springs.node_b[s]})
      d_sum[end] += d;
  }
  for (std::size_t i = 0; i < net.node_count(); ++i) {  // overdamped: h < 2 / gamma_i
    const double gamma = 2.0 * std::abs(net.masses.inverse_mass[i]) * d_sum[i];
    if (net.masses.free[i] != 0.0 && gamma > 0) bound = std::min(bound, 2.0 / gamma);
  }
  return bound;
}

double integrator_step_bound(const ClothNetwork& net, const Integrator& integrator,
                             StepBoundScratch& scratch, StepBound kind) {
  const double limit = integrator.stability_limit();
  const bool with_damping = !integrator.damps_springs();
  double bound = kind == StepBound::spectral
                     ? spectral_step_bound(net, limit, scratch.spectral, with_damping)
                     : stable_step_bound(net, limit, scratch.k_sum, scratch.d_sum, with_damping);
  // A force module that stiffens the cloth (bending's hinges) is explicit in
  // every integrator, implicit ones included. The largest eigenvalue of a sum
  // is at most the sum of the largest (Weyl): omega^2 grows by the module's,
  // and h = L / omega shrinks to match.
  double module_omega2 = 0;
  for (const auto& m : net.force_modules)
    module_omega2 += m->stiffness_bound(net);
  if (module_omega2 > 0) {
    if (std::isfinite(limit) && std::isfinite(bound))
      bound = bound / std::sqrt(1.0 + bound * bound * module_omega2 / (limit * limit));
    else
      bound = std::min(bound, 2.0 / std::sqrt(module_omega2));
  }
  if (integrator.kind() != IntegratorKind::explicit_euler) return bound;
  const double damped = explicit_euler_step_bound(net, scratch.d_sum);
  return damped > 0.0 ? std::min(bound, damped) : bound;
}

double integrator_step_bound(const ClothNetwork& net, const Integrator& integrator,
                             StepBound kind) {
  StepBoundScratch scratch;
  return integrator_step_bound(net, integrator, scratch, kind);
}

}  // namespace neurocloth
