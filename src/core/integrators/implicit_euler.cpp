// Linearised backward Euler in the style of Baraff & Witkin (1998):
//   (M + h D + h^2 K) dv = h (f0 + h (df/dx) v0),   v1 = v0 + dv,  p1 = p0 + h v1
// with K = -df/dx and D = -df/dv from ImplicitSystem, solved by conjugate
// gradient preconditioned (from 48 x 48 nodes) with projective's factored
// M + h^2 L between block-Jacobi sweeps, or as asked (ImplicitPreconditioner).
// One Newton iteration per step, first order.
//
// One Newton iteration is backward Euler only while the forces stay close to
// their linearisation over the step. On a very stiff, light cloth a large step
// breaks that: a flat cloth has no transverse stiffness, falls freely in the
// linear solve, and lands with its springs stretched a hundred-millionfold
// beyond their rest force; the next step turns that into runaway energy. So
// every step checks its linearisation against the forces where it landed and,
// where it did not hold, walks the step in pieces small enough that it does
// (the step controller's Table 1 rule, with the step as its cap). Where it holds — every ordinary
// cloth and step — the result is the single step, bit for bit, at the cost of one more force
// evaluation.
#include <algorithm>
#include <cmath>
#include <limits>

#include "core/integrators/implicit_system.h"
#include "core/integrators/integrator_factory.h"

namespace neurocloth {
namespace {

class ImplicitEuler final : public Integrator {
 public:
  ImplicitEuler(const ClothNetwork& net, double min_step_fraction, double linear_tolerance,
                ImplicitPreconditioner preconditioner)
      : min_step_fraction_(min_step_fraction),
        linear_tolerance_(linear_tolerance),
        preconditioner_(preconditioner),
        system_(net),
        rhs_(3 * net.node_count()),
        dv_(3 * net.node_count()),
        v0_(3 * net.node_count()),
        kv_(3 * net.node_count()),
        piece_a_(net.node_count()),
        piece_b_(net.node_count()),
        force_a_(net.node_count()),
        force_b_(net.node_count()) {}
  IntegratorKind kind() const override { return IntegratorKind::implicit_euler; }
  std::unique_ptr<Integrator> clone() const override {
    return std::make_unique<ImplicitEuler>(*this);
  }
  int order() const override { return 1; }
  double stability_limit() const override { return std::numeric_limits<double>::infinity(); }

  StepReport step(const ClothNetwork& net, const ForceInputs& inputs, const ForceContext& context,
                  const ClothState& in, const NodeVectors& F, double h, ClothState& out) override {
    StepReport report{0, 0, true};
    linear_step(net, in, F, h, out, report, context.threads);
    net.net_forces(out, inputs, context, force_a_);
    ++report.force_evaluations;
    if (!linearisation_holds(net, in, F, out, force_a_, h))
      split(net, inputs, context, in, F, h, out, report);
    return report;
  }

 private:
  // The forces where a step landed may differ from their linear prediction
  // at most this many times the largest force in play. Ordinary scenes stay
  // below 30 (wind and contact are not in the linearisation); the stiff,
  // light corner of the stability matrix starts at 5e9, and a threshold
  // anywhere from 10 to 1e7 keeps it stable (docs/stability.md).
  static constexpr double kLinearisationTolerance = 1000;
  // From this many nodes the automatic preconditioner is the Laplacian (below,
  // Jacobi, as the shipped 32 x 32 scenes always ran): docs/network.md.
  static constexpr std::size_t kMinLaplacianNodes = ImplicitMultigrid::kMinNodes;

  void linear_step(const ClothNetwork& net, const ClothState& in, const NodeVectors& F, double h,
                   ClothState& out, StepReport& report, StepThreads* team) {
    const std::size_t n = net.node_count();
    system_.linearise(net, in, /*exact_hessian=*/false, team);
    for (std::size_t i = 0; i < n; ++i) {
      v0_[3 * i] = in.vx[i];
      v0_[3 * i + 1] = in.vy[i];
      v0_[3 * i + 2] = in.vz[i];
    }
    system_.apply(net, 0.0, 0.0, 1.0, v0_, kv_, team);  // K v0
    for (std::size_t i = 0; i < n; ++i) {
      const double m = 1.0 / net.masses.inverse_mass[i];
      const double free = net.masses.free[i];
      const Vec3 f = F.at(i) + m * net.gravity;
      for (int c = 0; c < 3; ++c)
        rhs_[3 * i + c] = free * h * (f[c] - h * kv_[3 * i + c]);
    }
    const ImplicitPreconditioner use = chosen(n);
    // With the Laplacian the solve starts from the last step's dv when that
    // was a step of this length: the cloth's acceleration changes little from
    // step to step, and at tol 1e-3 on the 128 x 128 drape that saves a third
    // of the iterations (5.45 -> 3.68 a step). The others start from 0, as
    // they always did, so their runs keep their bits.
    if (use != ImplicitPreconditioner::laplacian || h != last_dv_h_)
      std::fill(dv_.begin(), dv_.end(), 0.0);
    last_dv_h_ = h;
    const bool cycled = use == ImplicitPreconditioner::multigrid;
    const bool fresh = cycled && refresh_multigrid(net, h);
    const bool factored = use == ImplicitPreconditioner::laplacian && refresh_laplacian(net, h);
    const CgResult cg =
        system_.solve(net, 1.0, h, h * h, rhs_, dv_, linear_tolerance_, cg_max_iterations(n),
                      cycled ? &multigrid_ : nullptr, factored ? &laplacian_ : nullptr, team);
    if (cycled) account(fresh, cg.iterations);
    for (std::size_t i = 0; i < n; ++i) {
      out.vx[i] = in.vx[i] + dv_[3 * i];
      out.vy[i] = in.vy[i] + dv_[3 * i + 1];
      out.vz[i] = in.vz[i] + dv_[3 * i + 2];
      out.x[i] = in.x[i] + h * out.vx[i];
      out.y[i] = in.y[i] + h * out.vy[i];
      out.z[i] = in.z[i] + h * out.vz[i];
    }
    report.force_evaluations += 1;
    report.cg_iterations += cg.iterations;
    report.cg_converged = report.cg_converged && cg.converged;
  }

  // The linear solve predicted the force m dv / h - m g on every free node;
  // `end_force` is the force where the step landed. They must agree within the
  // tolerance times the largest force in play (at the start, predicted, or a
  // node's weight). A NaN anywhere fails.
  static bool linearisation_holds(const ClothNetwork& net, const ClothState& in,
                                  const NodeVectors& start_force, const ClothState& out,
                                  const NodeVectors& end_force, double h) {
    double error = 0, scale = 0;
    for (std::size_t i = 0; i < net.node_count(); ++i) {
      if (net.masses.free[i] == 0.0) continue;
      const double m = 1.0 / net.masses.inverse_mass[i];
      const Vec3 predicted = m * (out.velocity(i) - in.velocity(i)) / h - m * net.gravity;
      error = std::max(error, (end_force.at(i) - predicted).norm());
      scale = std::max({scale, start_force.at(i).norm(), predicted.norm(), m * net.gravity.norm()});
    }
    return error <= kLinearisationTolerance * scale;
  }

  // From `in` to h in pieces over which the linearisation holds, each a
  // linearised step from where the last one landed; the end force of each
  // piece is the start force of the next.
  void split(const ClothNetwork& net, const ForceInputs& inputs, const ForceContext& context,
             const ClothState& in, const NodeVectors& F, double h, ClothState& out,
             StepReport& report) {
    ClothState* at = &piece_a_;
    ClothState* trial = &piece_b_;
    NodeVectors* at_force = &force_a_;
    NodeVectors* trial_force = &force_b_;
    *at = in;
    *at_force = F;
    StepController pieces(h, min_step_fraction_);
    pieces.reject();  // the whole step did not hold
    double t = 0;
    while (t < h) {
      const double p = pieces.trial(h - t);
      linear_step(net, *at, *at_force, p, *trial, report, context.threads);
      net.net_forces(*trial, inputs, context, *trial_force);
      ++report.force_evaluations;
      if (!pieces.at_floor() &&
          !linearisation_holds(net, *at, *at_force, *trial, *trial_force, p)) {
        pieces.reject();
        continue;
      }
      std::swap(at, trial);
      std::swap(at_force, trial_force);
      t = h - t - p <= 1e-12 * h ? h : t + p;
      pieces.accept();
    }
    out = *at;
  }

  // The CG preconditioner: a multigrid hierarchy of the step's matrix at an
  // earlier state (ImplicitMultigrid). It is built when there is none, when a
  // weight, mass or pin has changed, when a step length other than its own is
  // asked for twice in a row (a one-off, such as the end of a frame, is
  // preconditioned with the hierarchy there is), and when it has gone stale.
  // Returns true when it built one.
  bool refresh_multigrid(const ClothNetwork& net, double h) {
    const bool repeated = h == last_h_;
    last_h_ = h;
    if (net.node_count() > ImplicitMultigrid::kMaxNodes) return false;  // Jacobi, bounded memory
    if (net.node_count() < ImplicitMultigrid::kMinNodes) return false;  // Jacobi, cheaper there
    if (!stale_ && multigrid_.made_for(net, 1.0, h, h * h)) return false;
    if (!stale_ && multigrid_.made_for(net) && !repeated) return false;
    stale_ = false;
    extra_cost_ = 0;
    fresh_iterations_ = -1;
    // A hierarchy that cannot be built leaves none: Jacobi for this step.
    multigrid_.build(net, system_, 1.0, h, h * h);
    return true;
  }

  ImplicitPreconditioner chosen(std::size_t nodes) const {
    if (preconditioner_ != ImplicitPreconditioner::automatic) return preconditioner_;
    return nodes >= kMinLaplacianNodes ? ImplicitPreconditioner::laplacian
                                       : ImplicitPreconditioner::jacobi;
  }

  // The Laplacian preconditioner: projective's factored matrix M + h^2 L for
  // this step's weights (large_step_weights). A factor costs hundreds of
  // solves, so as in projective it is made for the weights a run keeps, asked
  // for twice in a row; a one-off step (the end of a frame, a changed step
  // tried once) is preconditioned with the factor there is, which any positive
  // definite matrix may be. Returns true when there is a factor for these
  // nodes (none when M + h^2 L is not positive definite: Jacobi then).
  bool refresh_laplacian(const ClothNetwork& net, double h) {
    large_step_weights(net, h, node_weight_, spring_weight_);
    if (laplacian_.same_as(node_weight_, spring_weight_, net.masses.free)) return true;
    const bool asked_before = spring_weight_ == last_asked_;
    last_asked_ = spring_weight_;
    const bool same_nodes = laplacian_.same_nodes(node_weight_, net.masses.free);
    if (same_nodes && !asked_before) return true;
    if (spring_weight_ == refused_) return false;  // not again at every step
    if (laplacian_.factor(net.springs, node_weight_, spring_weight_, net.masses.free)) return true;
    refused_ = spring_weight_;
    return false;
  }

  // Stale: the solves' iterations beyond those of a fresh hierarchy have cost,
  // in multiply-adds, more than a new one would (a rent-or-buy rule: at most
  // twice the cheapest work in hindsight). Counted, not timed, so that a run is
  // the same bits on every machine.
  void account(bool fresh, int iterations) {
    if (!multigrid_.built()) return;
    if (fresh || fresh_iterations_ < 0) fresh_iterations_ = iterations;
    extra_cost_ += std::max(0, iterations - fresh_iterations_) * multigrid_.cycle_cost();
    stale_ = extra_cost_ > multigrid_.build_cost();
  }

  static int cg_max_iterations(std::size_t nodes) {
    return static_cast<int>(std::max<std::size_t>(100, 3 * nodes));
  }
  double min_step_fraction_;
  double linear_tolerance_;
  ImplicitPreconditioner preconditioner_;
  ImplicitSystem system_;
  ImplicitMultigrid multigrid_;
  double last_h_ = 0;
  double last_dv_h_ = 0;  // the step length dv_ was last solved for
  bool stale_ = false;
  int fresh_iterations_ = -1;  // CG iterations of the first solve with this hierarchy
  double extra_cost_ = 0;      // multiply-adds of the iterations beyond those since
  std::vector<double> rhs_, dv_, v0_, kv_;
  SpringLaplacian laplacian_;
  std::vector<double> node_weight_, spring_weight_, last_asked_, refused_;
  // Scratch of a split step: where the pieces start and land, with their forces.
  ClothState piece_a_, piece_b_;
  NodeVectors force_a_, force_b_;
};

}  // namespace

std::unique_ptr<Integrator> make_implicit_euler(const ClothNetwork& net, double min_step_fraction,
                                                double linear_tolerance,
                                                ImplicitPreconditioner preconditioner) {
  return std::make_unique<ImplicitEuler>(net, min_step_fraction, linear_tolerance, preconditioner);
}

}  // namespace neurocloth
