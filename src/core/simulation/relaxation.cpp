#include "core/simulation/relaxation.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "core/integrators/implicit_system.h"

namespace neurocloth {
namespace {

// Potential energy, including the external forces' potential -f.p.
double potential(const ClothNetwork& net, const ClothState& s, const ForceInputs& in) {
  return net.energy(s).potential() + net.external_potential(s, in);
}

// Total force on every free node (springs, external, weight), interleaved; 0 on pins.
double total_force(const ClothNetwork& net, const ClothState& s, const ForceInputs& in,
                   const ForceContext& context, NodeVectors& F, std::vector<double>& out) {
  net.net_forces(s, in, context, F);
  double worst = 0;
  for (std::size_t i = 0; i < net.node_count(); ++i) {
    const double free = net.masses.free[i];
    const Vec3 f = free * (F.at(i) + net.mass(i) * net.gravity);
    for (int c = 0; c < 3; ++c)
      out[3 * i + c] = f[c];
    worst = std::max(worst, f.norm());
  }
  return worst;
}

}  // namespace

RelaxReport relax(const ClothNetwork& net, ClothState& state, const RelaxSettings& settings,
                  const ForceInputs& inputs, const ForceContext& context) {
  const std::size_t n = net.node_count();
  std::fill(state.vx.begin(), state.vx.end(), 0.0);
  std::fill(state.vy.begin(), state.vy.end(), 0.0);
  std::fill(state.vz.begin(), state.vz.end(), 0.0);

  double force_tol = settings.force_tolerance;
  if (force_tol < 0) {
    double heaviest = 0;
    for (std::size_t i = 0; i < n; ++i)
      if (net.masses.free[i] != 0.0)
        heaviest = std::max(heaviest, net.mass(i) * net.gravity.norm());
    force_tol = std::max(1e-10 * heaviest, 1e-12);
  }

  ImplicitSystem system(net);
  NodeVectors F(n);
  std::vector<double> f(3 * n), dx(3 * n);
  ClothState trial = state;

  RelaxReport report;
  for (std::size_t i = 0; i < n; ++i)
    report.free_nodes += net.masses.free[i] != 0.0 ? 1 : 0;
  if (report.free_nodes == 0) {  // every node pinned: no force can move anything
    report.converged = true;
    return report;
  }
  // No step taken yet counts as an unbounded one: convergence needs a step.
  double last_step = std::numeric_limits<double>::infinity();
  double mu = 100.0;  // 1/h^2 for h = 0.1 s: a cautious first step
  double energy = potential(net, state, inputs);
  report.residual_force = total_force(net, state, inputs, context, F, f);
  for (int it = 0; it < settings.max_iterations; ++it) {
    if (report.residual_force <= force_tol && last_step <= settings.position_tolerance) {
      report.converged = true;
      break;
    }
    report.iterations = it + 1;
    system.linearise(net, state, /*exact_hessian=*/true);
    std::fill(dx.begin(), dx.end(), 0.0);
    const CgResult cg = system.solve(net, mu, 0.0, 1.0, f, dx, settings.cg_tolerance,
                                     static_cast<int>(std::max<std::size_t>(200, 6 * n)));
    report.cg_iterations += cg.iterations;
    double step = 0;
    for (std::size_t i = 0; i < n; ++i) {
      trial.x[i] = state.x[i] + dx[3 * i];
      trial.y[i] = state.y[i] + dx[3 * i + 1];
      trial.z[i] = state.z[i] + dx[3 * i + 2];
      step = std::max(step, Vec3(dx[3 * i], dx[3 * i + 1], dx[3 * i + 2]).norm());
    }
    const double trial_energy = potential(net, trial, inputs);
    // Accept when the energy does not rise beyond round-off.
    // (A zero step — CG met negative curvature at once — is no progress: more
    // regularisation, like a rise.)
    if (step > 0 && std::isfinite(trial_energy) &&
        trial_energy <= energy + 1e-13 * std::abs(energy)) {
      state = trial;
      energy = trial_energy;
      last_step = report.last_step = step;
      ++report.accepted_steps;
      report.residual_force = total_force(net, state, inputs, context, F, f);
      mu = std::max(mu * 0.25, 1e-9);
    } else {
      mu = mu * 8.0;
      if (mu > 1e30) break;  // no descent left: stuck (reported as not converged)
    }
  }
  if (!report.converged && report.residual_force <= force_tol &&
      last_step <= settings.position_tolerance)
    report.converged = true;
  return report;
}

}  // namespace neurocloth
