// Fast mass-spring / projective dynamics (Liu et al. 2013), with Chebyshev
// acceleration (Wang 2015): backward Euler written as a minimisation over the
// end positions x,
//   1/(2h^2) |x - y|_M^2 + sum_s k_s/2 |x_ab - r_s n_s|^2 + ...,
// y = x0 + h v0 + h^2 M^-1 f_other the inertial target, x_ab = x_b - x_a and n_s its
// direction. Alternating a local step (each spring's nearest term at fixed x)
// and a global step (a linear solve with the constant matrix
// M + sum_s (h^2 k_s + h d_s) L_s, prefactored) descends that energy; its fixed
// point is backward Euler on the network's springs, exactly. The iterations per
// step are the accuracy knob: few give a stable, too-soft cloth, many the
// implicit Euler solution.
//
// Every term of the spring layer is such a projection, on the same weights:
//   stiffness  k/2 |x_ab - r n|^2                  (the linear spring: e = l - r)
//   stiffening k (f-1)/2 |x_ab - q|^2, q = x_ab clipped to length (1 + threshold) r
//              (beyond the threshold the spring is f times stiffer; nothing below)
//   damping    d/(2h) |u_ab - t|^2,   u_ab = x_ab - x0_ab, t = u_ab without its part
//              along n; at the fixed point its gradient is d (n . v_ab) n, the
//              network's velocity-force neuron at the end of the step.
// Forces that are not springs (gravity, the external force, the scene's air and
// wind) enter y, evaluated at the start of the step; colliders and the strain
// limit act after it, as for every integrator. The unknowns are the
// displacements x - x0 (so the new velocity, displacement / h, carries no
// cancellation of positions).
#include "core/integrators/projective.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "core/integrators/inertial_target.h"
#include "core/integrators/integrator_factory.h"
#include "core/network/reciprocal_sqrt.h"

namespace neurocloth {

ProjectiveIntegrator::ProjectiveIntegrator(const ClothNetwork& net, int iterations)
    : iterations_((refuse_beyond_limit(net), std::max(1, iterations))),
      n_(net.node_count()),
      y_(3 * n_),
      x_(3 * n_),
      prev_(3 * n_),
      rhs_(3 * n_),
      base_(3 * n_),
      other_force_(n_) {}

std::unique_ptr<Integrator> ProjectiveIntegrator::clone() const {
  auto copy = std::make_unique<ProjectiveIntegrator>(*this);
  copy->replay_ = nullptr;
  return copy;
}

double ProjectiveIntegrator::stability_limit() const {
  return std::numeric_limits<double>::infinity();
}

void ProjectiveIntegrator::refuse_beyond_limit(const ClothNetwork& net) {
  if (net.node_count() > kMaxNodes)
    throw std::invalid_argument("projective: a cloth of " + std::to_string(net.node_count()) +
                                " nodes is beyond its prefactored solve's limit of " +
                                std::to_string(kMaxNodes) +
                                " (512 x 512); choose another integrator");
}

StepReport ProjectiveIntegrator::step(const ClothNetwork& net, const ForceInputs& inputs,
                                      const ForceContext& context, const ClothState& in,
                                      const NodeVectors&, double h, ClothState& out) {
  refactor_if_needed(net, h);
  start_step(net, inputs, context, in, h);
  const int iterations = iterate(net, in, h, context.threads, false);
  for (std::size_t i = 0; i < n_; ++i) {
    const bool pinned = net.masses.free[i] == 0.0;  // moves on at its own velocity
    out.vx[i] = pinned ? in.vx[i] : x_[i] / h;
    out.vy[i] = pinned ? in.vy[i] : x_[n_ + i] / h;
    out.vz[i] = pinned ? in.vz[i] : x_[2 * n_ + i] / h;
    out.x[i] = in.x[i] + h * out.vx[i];
    out.y[i] = in.y[i] + h * out.vy[i];
    out.z[i] = in.z[i] + h * out.vz[i];
  }
  StepReport report{1, 0, true};
  report.cg_iterations = iterations;  // local-global iterations, for the same tallies
  report.cg_converged = factored_ && near_converged_;
  return report;
}

void ProjectiveIntegrator::start_step(const ClothNetwork& net, const ForceInputs& inputs,
                                      const ForceContext& context, const ClothState& in, double h) {
  inertial_displacement(net, inputs, context, in, h, other_force_, y_);
  prev_ = y_;
  step_base(net);
  x_ = y_;
}

int ProjectiveIntegrator::iterate(const ClothNetwork& net, const ClothState& in, double h,
                                  StepThreads* team, bool keep) {
  // Without a factor (a matrix that is not positive definite: no weight can
  // make one in range) the step is the inertial one, and says it did not converge.
  const int iterations = factored_ ? iterations_ : 0;
  const double* const replay = replay_;
  replay_ = nullptr;
  if (keep) kept_x_.resize(static_cast<std::size_t>(iterations));
  if (!replay) chebyshev_.begin(iterations);
  const bool record = fit_run_ && !replay;
  for (int it = 0; it < iterations; ++it) {
    local_global(net, in, h, team);  // rhs_ now holds the global step's answer
    double omega;
    if (replay) {
      omega = replay[it];
    } else {
      double update = 0;
      for (std::size_t i = 0; i < rhs_.size(); ++i)
        update += (rhs_[i] - x_[i]) * (rhs_[i] - x_[i]);
      omega = chebyshev_.weight(it, std::sqrt(update));
      if (record) {
        omegas_.push_back(omega);
        d_omegas_.push_back(chebyshev_.d_omega());
      }
    }
    for (std::size_t i = 0; i < x_.size(); ++i) {
      const double next = omega * (rhs_[i] - prev_[i]) + prev_[i];
      prev_[i] = x_[i];
      x_[i] = omega == 1 ? rhs_[i] : next;
    }
    if (keep) kept_x_[static_cast<std::size_t>(it)] = x_;
    if (record && tape_iterates_) iterate_tape_.insert(iterate_tape_.end(), x_.begin(), x_.end());
  }
  if (!replay) chebyshev_.end();
  if (record) {
    // A run without a factor took no iterations: its omegas are padded so
    // that step k's are always at k * iterations_.
    omegas_.resize((fit_steps_ + 1) * std::size_t(iterations_), 1.0);
    d_omegas_.resize(omegas_.size(), 0.0);
    if (chebyshev_.measured()) {
      measuring_step_ = fit_steps_;
      half_iteration_ = chebyshev_.half_iteration();
      last_iteration_ = chebyshev_.last_iteration();
      d_rate_d_half_ = chebyshev_.d_rate_d_half();
      d_rate_d_last_ = chebyshev_.d_rate_d_last();
    }
    ++fit_steps_;
  }
  return iterations;
}

// The global matrix's weights in the h^2-scaled form: M, and h^2 (k + k') + h d per
// spring. A factor costs what hundreds of solves cost (340 ms at 128 x 128), so it
// is made for the matrix a run keeps: one asked for twice in a row. A one-off
// step (the end of a frame, a trial of the adaptive step, a slider being
// dragged) solves its own matrix by conjugate gradient with the factor it has
// as preconditioner, exactly, in a few iterations. A fit's run keeps the
// factor begin_fit_run made.
void ProjectiveIntegrator::refactor_if_needed(const ClothNetwork& net, double h) {
  const SpringLayer& L = net.springs;
  large_step_weights(net, h, node_weight_, spring_weight_);
  near_ = false;
  near_converged_ = true;
  if (laplacian_.same_as(node_weight_, spring_weight_, net.masses.free)) return;
  if (fit_run_) {
    if (!laplacian_.same_nodes(node_weight_, net.masses.free))
      throw std::logic_error("projective: a fit's run changed its masses or pins mid-run");
    near_ = true;
    return;
  }
  const bool asked_before = spring_weight_ == last_asked_;
  last_asked_ = spring_weight_;
  if (factored_ && !asked_before && laplacian_.same_nodes(node_weight_, net.masses.free)) {
    near_ = true;
    return;
  }
  chebyshev_.forget();  // another matrix converges at another rate
  factored_ = laplacian_.factor(L, node_weight_, spring_weight_, net.masses.free);
}

void ProjectiveIntegrator::begin_fit_run(const ClothNetwork& net, double h, bool tape_iterates) {
  fit_run_ = false;
  large_step_weights(net, h, node_weight_, spring_weight_);
  if (!laplacian_.same_as(node_weight_, spring_weight_, net.masses.free))
    factored_ = laplacian_.factor(net.springs, node_weight_, spring_weight_, net.masses.free);
  last_asked_ = spring_weight_;
  if (!factored_)
    throw std::runtime_error(
        "projective: the step's matrix is not positive definite (a free node without mass)");
  fit_run_ = true;
  chebyshev_.forget();  // measured afresh, as a new simulation measures it
  omegas_.clear();
  d_omegas_.clear();
  fit_steps_ = 0;
  measuring_step_ = SIZE_MAX;
  tape_iterates_ = tape_iterates;
  iterate_tape_.clear();
  replay_ = nullptr;
}

void ProjectiveIntegrator::solve(const SpringLayer& L, double* rhs, StepThreads* team) {
  if (near_)
    near_converged_ = laplacian_.solve3_near(L, spring_weight_, rhs, kNearTolerance,
                                             kNearIterations, team) >= 0 &&
                      near_converged_;
  else
    laplacian_.solve3(rhs, team);
}

// One local step at x_ and one global solve: rhs_ <- P^-1 (M y + sum_s A_s^T c_s),
// all in displacements. The springs are visited chunk by chunk as the
// network's force sweep visits them (spring_chunks.h), so each chunk's
// targets are computed in one vectorisable loop and added in another.
void ProjectiveIntegrator::local_global(const ClothNetwork& net, const ClothState& in, double h,
                                        StepThreads* team) {
  const SpringLayer& L = net.springs;
  rhs_ = base_;
  double* const dst = rhs_.data();
  const std::array<double*, 3> rows = {dst, dst + n_, dst + 2 * n_};
  spring_chunks::Chunk& c = chunk_;
  const bool stiffening = L.function.kind == SpringFunctionKind::stiffening;
  spring_chunks::for_each_chunk(
      L, [&](std::int32_t first, std::int32_t count, std::int32_t a, std::int32_t b, bool) {
        if (stiffening)
          spring_targets<SpringFunctionKind::stiffening>(L, first, count, a, b, in, h, c);
        else
          spring_targets<SpringFunctionKind::linear>(L, first, count, a, b, in, h, c);
        spring_chunks::accumulate_chunk(count, a, b, c.fx, c.fy, c.fz, rows);
      });
  // A pinned row is x = y whatever its springs asked.
  for (const std::int32_t p : pinned_)
    for (std::size_t k = 0; k < 3; ++k)
      rhs_[k * n_ + std::size_t(p)] = y_[k * n_ + std::size_t(p)];
  if (factored_) solve(L, rhs_.data(), team);
}

// The springs' terms of a chunk at x_: -c_s, the target every term of spring
// s asks for u (x_ab less x0_ab), negated so that accumulate_chunk's +1 at a
// and -1 at b give A_s^T c_s.
template <SpringFunctionKind K>
void ProjectiveIntegrator::spring_targets(const SpringLayer& L, std::int32_t first,
                                          std::int32_t count, std::int32_t a, std::int32_t b,
                                          const ClothState& in, double h,
                                          spring_chunks::Chunk& out) const {
  const double* const ux_a = x_.data() + a;
  const double* const uy_a = x_.data() + n_ + a;
  const double* const uz_a = x_.data() + 2 * n_ + a;
  const double* const ux_b = x_.data() + b;
  const double* const uy_b = x_.data() + n_ + b;
  const double* const uz_b = x_.data() + 2 * n_ + b;
  const double* const px_a = in.x.data() + a;
  const double* const py_a = in.y.data() + a;
  const double* const pz_a = in.z.data() + a;
  const double* const px_b = in.x.data() + b;
  const double* const py_b = in.y.data() + b;
  const double* const pz_b = in.z.data() + b;
  const double* const rest = L.rest_length.data() + first;
  const double* const stiffness = L.stiffness.data() + first;
  const double* const damping = L.damping.data() + first;
  const double h2 = h * h, threshold = 1.0 + L.function.strain_threshold;
  const double extra = L.function.stiffening_factor - 1.0;
  double* const cx = out.fx;
  double* const cy = out.fy;
  double* const cz = out.fz;
#pragma GCC ivdep
  for (std::int32_t j = 0; j < count; ++j) {
    const double ux = ux_b[j] - ux_a[j], uy = uy_b[j] - uy_a[j], uz = uz_b[j] - uz_a[j];
    const double d0x = px_b[j] - px_a[j], d0y = py_b[j] - py_a[j], d0z = pz_b[j] - pz_a[j];
    const double dx = d0x + ux, dy = d0y + uy, dz = d0z + uz;
    const double len2 = dx * dx + dy * dy + dz * dz;
    const bool has_direction = len2 > kMinSpringLength * kMinSpringLength;
    // Without the divider: a square root and three divisions were a third of the step.
    const double inv_len = reciprocal_sqrt(has_direction ? len2 : 1.0);
    const double nx = inv_len * dx, ny = inv_len * dy, nz = inv_len * dz;
    const double k = h2 * stiffness[j], d = h * damping[j], r = rest[j];
    const double along = ux * nx + uy * ny + uz * nz;
    // stiffness: rest-length along n; damping: u without its part along n.
    double tx = k * (r * nx - d0x) + d * (ux - along * nx);
    double ty = k * (r * ny - d0y) + d * (uy - along * ny);
    double tz = k * (r * nz - d0z) + d * (uz - along * nz);
    double k_all = k + d;
    if constexpr (K == SpringFunctionKind::stiffening) {
      // stiffening: x_ab clipped to (1 + threshold) rest.
      const double k2 = k * extra, limit = threshold * r;
      const bool clip = len2 * inv_len > limit;
      tx += k2 * ((clip ? limit * nx : dx) - d0x);
      ty += k2 * ((clip ? limit * ny : dy) - d0y);
      tz += k2 * ((clip ? limit * nz : dz) - d0z);
      k_all += k2;
    }
    // No direction: no force, as in the network.
    cx[j] = -(has_direction ? tx : k_all * ux);
    cy[j] = -(has_direction ? ty : k_all * uy);
    cz[j] = -(has_direction ? tz : k_all * uz);
  }
}

// What every iteration of a step starts its right-hand side from: M y on
// free rows, y on pinned ones, and on a free node the pull w y_p of each
// spring to a pinned node p (A_s^T moves the known end to its side).
void ProjectiveIntegrator::step_base(const ClothNetwork& net) {
  const std::vector<double>& free = net.masses.free;
  if (free != pins_of_) {
    pins_of_ = free;
    pinned_.clear();
    pin_springs_.clear();
    for (std::size_t i = 0; i < n_; ++i)
      if (free[i] == 0.0) pinned_.push_back(std::int32_t(i));
    const SpringLayer& L = net.springs;
    for (std::size_t s = 0; s < L.size(); ++s)
      if ((free[std::size_t(L.node_a[s])] == 0.0) != (free[std::size_t(L.node_b[s])] == 0.0))
        pin_springs_.push_back(std::int32_t(s));
  }
  for (std::size_t i = 0; i < n_; ++i) {
    const double m = free[i] != 0.0 ? node_weight_[i] : 1.0;
    for (std::size_t k = 0; k < 3; ++k)
      base_[k * n_ + i] = m * y_[k * n_ + i];
  }
  for (const std::int32_t s : pin_springs_) {
    std::size_t a = std::size_t(net.springs.node_a[std::size_t(s)]);
    std::size_t b = std::size_t(net.springs.node_b[std::size_t(s)]);
    if (free[a] == 0.0) std::swap(a, b);  // a: the free end
    for (std::size_t k = 0; k < 3; ++k)
      base_[k * n_ + a] += spring_weight_[std::size_t(s)] * y_[k * n_ + b];
  }
}

std::unique_ptr<Integrator> make_projective(const ClothNetwork& net, int iterations) {
  return std::make_unique<ProjectiveIntegrator>(net, iterations);
}

}  // namespace neurocloth
