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
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "integrators.h"
#include "reciprocal_sqrt.h"
#include "spring_laplacian.h"

namespace neurocloth {
namespace {

class Projective final : public Integrator {
 public:
  Projective(const ClothNetwork& net, int iterations)
      : iterations_((refuse_beyond_limit(net), std::max(1, iterations))),
        n_(net.node_count()),
        y_(3 * n_),
        x_(3 * n_),
        prev_(3 * n_),
        rhs_(3 * n_),
        other_force_(n_) {}
  IntegratorKind kind() const override { return IntegratorKind::projective; }
  std::unique_ptr<Integrator> clone() const override { return std::make_unique<Projective>(*this); }
  int order() const override { return 1; }
  double stability_limit() const override { return std::numeric_limits<double>::infinity(); }

  StepReport step(const ClothNetwork& net, const ForceInputs& inputs, const ClothState& in,
                  const NodeVectors&, double h, ClothState& out) override {
    refactor_if_needed(net, h);
    inertial_target(net, inputs, in, h);
    x_ = y_;
    // Without a factor (a matrix that is not positive definite: no weight can
    // make one in range) the step is the inertial one, and says it did not converge.
    const int iterations = factored_ ? iterations_ : 0;
    // Chebyshev needs the rate at which plain iterations converge. It depends
    // on the cloth and the step, not on the state much, so it is measured once,
    // on a step of plain iterations, and kept; an update that grows (the
    // estimate was too bold) restarts from a plain iteration and lowers it.
    const bool measure = rho_ == 0 && iterations > 0;
    double omega = 1, last_update = 0, first_half = 0;
    for (int it = 0; it < iterations; ++it) {
      local_global(net, in, h);  // rhs_ now holds the global step's answer
      double update = 0;
      for (std::size_t i = 0; i < rhs_.size(); ++i)
        update += (rhs_[i] - x_[i]) * (rhs_[i] - x_[i]);
      update = std::sqrt(update);
      if (measure) {
        omega = 1;
        if (it == iterations_ / 2) first_half = update;
      } else if (it == 0) {
        omega = 1;
      } else if (update > last_update) {
        omega = 1;
        rho_ *= kRhoBackoff;
      } else {
        omega = omega == 1 ? 2 / (2 - rho_ * rho_) : 4 / (4 - rho_ * rho_ * omega);
      }
      last_update = update;
      for (std::size_t i = 0; i < x_.size(); ++i) {
        const double next = omega * (rhs_[i] - prev_[i]) + prev_[i];
        prev_[i] = x_[i];
        x_[i] = omega == 1 ? rhs_[i] : next;
      }
    }
    const int span = iterations_ - 1 - iterations_ / 2;
    if (measure && span >= 2 && first_half > 0 && last_update > 0 && last_update < first_half)
      rho_ = std::min(kMaxRho, std::pow(last_update / first_half, 1.0 / span));
    for (std::size_t i = 0; i < n_; ++i) {
      const bool pinned = net.masses.free[i] == 0.0;  // moves on at its own velocity
      out.vx[i] = pinned ? in.vx[i] : x_[3 * i] / h;
      out.vy[i] = pinned ? in.vy[i] : x_[3 * i + 1] / h;
      out.vz[i] = pinned ? in.vz[i] : x_[3 * i + 2] / h;
      out.x[i] = in.x[i] + h * out.vx[i];
      out.y[i] = in.y[i] + h * out.vy[i];
      out.z[i] = in.z[i] + h * out.vz[i];
    }
    StepReport report{1, 0, true};
    report.cg_iterations = iterations;  // local-global iterations, for the same tallies
    report.cg_converged = factored_ && near_converged_;
    return report;
  }

 private:
  static constexpr double kMaxRho = 0.999;
  static constexpr double kNearTolerance = 1e-13;
  static constexpr int kNearIterations = 200;
  // The factor's fill grows faster than the nodes (1.15 M entries at 128 x 128,
  // about 25 M at 512 x 512, a few seconds to make): beyond this a cloth is
  // refused rather than left to exhaust memory.
  static constexpr std::size_t kMaxNodes = 512 * 512;
  static void refuse_beyond_limit(const ClothNetwork& net) {
    if (net.node_count() > kMaxNodes)
      throw std::invalid_argument("projective: a cloth of " + std::to_string(net.node_count()) +
                                  " nodes is beyond its prefactored solve's limit of " +
                                  std::to_string(kMaxNodes) +
                                  " (512 x 512); choose another integrator");
  }
  static constexpr double kRhoBackoff = 0.99;

  // The global matrix's weights in the h^2-scaled form: M, and h^2 (k + k') + h d per
  // spring. A factor costs what hundreds of solves cost (340 ms at 128 x 128), so it
  // is made for the matrix a run keeps: one asked for twice in a row. A one-off
  // step (the end of a frame, a trial of the adaptive step, a slider being
  // dragged) solves its own matrix by conjugate gradient with the factor it has
  // as preconditioner, exactly, in a few iterations.
  void refactor_if_needed(const ClothNetwork& net, double h) {
    const SpringLayer& L = net.springs;
    node_weight_.resize(n_);
    for (std::size_t i = 0; i < n_; ++i)
      node_weight_[i] = 1.0 / net.masses.inverse_mass[i];
    spring_weight_.resize(L.size());
    for (std::size_t s = 0; s < L.size(); ++s)
      spring_weight_[s] = h * h * (L.stiffness[s] + extra_stiffness(net, s)) + h * L.damping[s];
    near_ = false;
    near_converged_ = true;
    if (laplacian_.same_as(node_weight_, spring_weight_, net.masses.free)) return;
    const bool asked_before = spring_weight_ == last_asked_;
    last_asked_ = spring_weight_;
    if (factored_ && !asked_before && laplacian_.same_nodes(node_weight_, net.masses.free)) {
      near_ = true;
      return;
    }
    rho_ = 0;  // another matrix converges at another rate
    factored_ = laplacian_.factor(L, node_weight_, spring_weight_, net.masses.free);
  }

  static double extra_stiffness(const ClothNetwork& net, std::size_t s) {
    const SpringFunction& f = net.springs.function;
    return f.kind == SpringFunctionKind::stiffening
               ? net.springs.stiffness[s] * (f.stiffening_factor - 1.0)
               : 0.0;
  }

  // The inertial displacement y - x0 = h v0 + h^2 M^-1 (f_other + m g) on free
  // nodes; a pinned node moves h v0.
  void inertial_target(const ClothNetwork& net, const ForceInputs& inputs, const ClothState& in,
                       double h) {
    net.other_forces(in, inputs, other_force_);
    const double* const v[3] = {in.vx.data(), in.vy.data(), in.vz.data()};
    const double* const f[3] = {other_force_.x.data(), other_force_.y.data(),
                                other_force_.z.data()};
    const double g[3] = {net.gravity.x(), net.gravity.y(), net.gravity.z()};
    for (std::size_t i = 0; i < n_; ++i) {
      const double free = net.masses.free[i], w = net.masses.inverse_mass[i];
      for (int c = 0; c < 3; ++c)
        y_[3 * i + c] = h * v[c][i] + free * h * h * (w * f[c][i] + g[c]);
    }
    prev_ = y_;
  }

  // One local step at x_ and one global solve: rhs_ <- P^-1 (M y + sum_s A_s^T c_s),
  // all in displacements.
  void local_global(const ClothNetwork& net, const ClothState& in, double h) {
    const SpringLayer& L = net.springs;
    const std::vector<double>& free = net.masses.free;
    for (std::size_t i = 0; i < n_; ++i) {
      const double m = free[i] != 0.0 ? node_weight_[i] : 1.0;  // a pinned row is x = y
      for (int c = 0; c < 3; ++c)
        rhs_[3 * i + c] = m * y_[3 * i + c];
    }
    const double threshold = 1.0 + L.function.strain_threshold;
    for (std::size_t s = 0; s < L.size(); ++s) {
      const std::int32_t a = L.node_a[s], b = L.node_b[s];
      const Vec3 u(x_[3 * b] - x_[3 * a], x_[3 * b + 1] - x_[3 * a + 1],
                   x_[3 * b + 2] - x_[3 * a + 2]);  // x_ab - x0_ab
      const Vec3 d0 = in.position(b) - in.position(a);
      const Vec3 d = d0 + u;
      const double len2 = d.squaredNorm();
      const double k = h * h * L.stiffness[s], k2 = h * h * extra_stiffness(net, s);
      const double damping = h * L.damping[s];
      Vec3 c;
      if (len2 > kMinSpringLength * kMinSpringLength) {
        // Without the divider: a square root and three divisions were a third of the step.
        const double inv_len = reciprocal_sqrt(len2);
        const double len = len2 * inv_len;
        const Vec3 n = inv_len * d;
        const double rest = L.rest_length[s];
        const Vec3 q = len > threshold * rest ? Vec3(threshold * rest * n) : d;
        // The terms' targets for u (a target for x_ab less x0_ab).
        c = k * (rest * n - d0) + k2 * (q - d0) + damping * (u - u.dot(n) * n);
      } else {  // no direction: no force, as in the network
        c = (k + k2 + damping) * u;
      }
      // A_s^T c: u is x_b - x_a less its start. A spring to a pinned node moves its known
      // end to the free node's side; the pinned row itself stays x = y.
      const double w = spring_weight_[s];
      const bool fa = free[a] != 0.0, fb = free[b] != 0.0;
      for (int i = 0; i < 3; ++i) {
        if (fa) rhs_[3 * a + i] -= c[i] - (fb ? 0.0 : w * y_[3 * b + i]);
        if (fb) rhs_[3 * b + i] += c[i] + (fa ? 0.0 : w * y_[3 * a + i]);
      }
    }
    if (!factored_) return;
    if (near_)
      near_converged_ = laplacian_.solve3_near(L, spring_weight_, rhs_.data(), kNearTolerance,
                                               kNearIterations) >= 0 &&
                        near_converged_;
    else
      laplacian_.solve3(rhs_.data());
  }

  int iterations_;
  std::size_t n_;
  std::vector<double> y_, x_, prev_, rhs_;
  NodeVectors other_force_;
  std::vector<double> node_weight_, spring_weight_;
  SpringLaplacian laplacian_;
  bool factored_ = false;
  double rho_ = 0;                  // plain iterations' convergence rate; 0 until measured
  bool near_ = false;               // this step's matrix is not the factored one
  bool near_converged_ = true;      // and its solves converged
  std::vector<double> last_asked_;  // the spring weights the last step asked for
};

}  // namespace

std::unique_ptr<Integrator> make_projective(const ClothNetwork& net, int iterations) {
  return std::make_unique<Projective>(net, iterations);
}

}  // namespace neurocloth
