#pragma once
// The `projective` integrator (projective.cpp says what it computes), public
// for learning: a fit runs it as a smooth function of the weights and takes
// its adjoint (projective_adjoint.cpp), reusing the prefactored matrix for the
// backward solves as DiffPD does (Du et al. 2021). The simulation reaches it
// through make_projective (integrator_factory.h) and sees only Integrator.
#include <array>
#include <cstdint>
#include <vector>

#include "core/integrators/chebyshev.h"
#include "core/integrators/integrator.h"
#include "core/integrators/spring_laplacian.h"
#include "core/network/spring_adjoint.h"
#include "core/network/spring_chunks.h"

namespace neurocloth {

class ProjectiveIntegrator final : public Integrator {
 public:
  // Throws std::invalid_argument beyond the factor's node limit (512 x 512).
  ProjectiveIntegrator(const ClothNetwork& net, int iterations);
  IntegratorKind kind() const override { return IntegratorKind::projective; }
  std::unique_ptr<Integrator> clone() const override;
  int order() const override { return 1; }
  double stability_limit() const override;
  bool reads_start_force() const override { return false; }  // other_forces() instead
  StepReport step(const ClothNetwork& net, const ForceInputs& inputs, const ForceContext& context,
                  const ClothState& in, const NodeVectors&, double h, ClothState& out) override;
  int iterations() const { return iterations_; }

  // --- Learning (learn/fit/rollout.h) ---
  // A fit's run is the simulation's: its first steps measure Chebyshev's rate
  // (chebyshev.h) as the simulation's do, and the rest take omegas from it. So
  // each omega moves with the weights through the measured rate, and the
  // adjoint follows it there (step_adjoint's rate_adjoint).
  //
  // Starts a fit's run at the network's current weights: factors the matrix of
  // steps of `h` (the run's usual step; another step is solved against this
  // factor by conjugate gradient, exactly, as in a simulation), never
  // refactors until the next call, measures the rate afresh, and keeps every
  // step's omegas for the adjoint.
  // With `tape_iterates`, the forward pass keeps every step's iterates
  // (iterations() x 3 x nodes doubles a step: iterate_bytes_per_step) and
  // the adjoint reads them instead of recomputing the step's iterations.
  void begin_fit_run(const ClothNetwork& net, double h, bool tape_iterates = false);
  std::size_t iterate_bytes_per_step() const {
    return std::size_t(iterations_) * 3 * n_ * sizeof(double);
  }
  // The next step() recomputes step k of the fit's run with the omegas it
  // took (a checkpointed segment's recomputation).
  void replay_next_step(std::size_t k) { replay_ = &omegas_[k * std::size_t(iterations_)]; }

  // The adjoint of step k of the fit's run (projective_adjoint.cpp), from
  // `in` over h. On entry `adj` holds dE/d(the step's result), on return
  // dE/d(in) except through the forces that are not springs, whose dE/dF is
  // `adj_other_force` (the caller hands it to the force modules' adjoints, as
  // for the network step). The springs' and the nodes' weight gradients are
  // added to `g` and (when not null) `adj_inverse_mass`. `rate_adjoint`
  // carries dE/d(the measured rate) back from the later steps' omegas to the
  // step that measured it: zero it before the run's last step.
  void step_adjoint(const ClothNetwork& net, const ForceInputs& inputs, const ForceContext& context,
                    const ClothState& in, double h, std::size_t k, ClothState& adj,
                    NodeVectors& adj_other_force, SpringGradients& g, double* adj_inverse_mass,
                    double& rate_adjoint);

 private:
  static constexpr double kNearTolerance = 1e-13;
  static constexpr int kNearIterations = 200;
  // The factor's fill grows faster than the nodes (1.15 M entries at 128 x 128,
  // about 25 M at 512 x 512, a few seconds to make): beyond this a cloth is
  // refused rather than left to exhaust memory.
  static constexpr std::size_t kMaxNodes = 512 * 512;
  static void refuse_beyond_limit(const ClothNetwork& net);

  void refactor_if_needed(const ClothNetwork& net, double h);
  // The step's start: y (the inertial displacement), the right-hand side's
  // base, x = prev = y.
  void start_step(const ClothNetwork& net, const ForceInputs& inputs, const ForceContext& context,
                  const ClothState& in, double h);
  // The step's iterations from start_step's x; with `keep`, every iterate and
  // every global solve's answer are kept for the adjoint.
  int iterate(const ClothNetwork& net, const ClothState& in, double h, StepThreads* team,
              bool keep);
  void local_global(const ClothNetwork& net, const ClothState& in, double h, StepThreads* team);
  // rhs <- P^-1 rhs with this step's matrix (the factor's, or near it).
  void solve(const SpringLayer& L, double* rhs, StepThreads* team);
  template <SpringFunctionKind K>
  void spring_targets(const SpringLayer& L, std::int32_t first, std::int32_t count, std::int32_t a,
                      std::int32_t b, const ClothState& in, double h,
                      spring_chunks::Chunk& out) const;
  void step_base(const ClothNetwork& net);
  // The adjoint of the springs' targets at iterate `x`: from dE/d(rhs) (lr),
  // adds dE/dx to `lx`, dE/d(start positions) to `lp` (planar) and the
  // springs' weight gradients to g.
  void spring_targets_adjoint(const SpringLayer& L, const double* x, const ClothState& in, double h,
                              const double* lr, double* lx, double* lp, SpringGradients& g) const;

  int iterations_;
  std::size_t n_;
  // Displacements and right-hand sides, planar (every node's x, then y, then z).
  std::vector<double> y_, x_, prev_, rhs_, base_;
  spring_chunks::Chunk chunk_;
  std::vector<double> pins_of_;  // the pins pinned_ and pin_springs_ were found for
  std::vector<std::int32_t> pinned_, pin_springs_;
  NodeVectors other_force_;
  std::vector<double> node_weight_, spring_weight_;
  SpringLaplacian laplacian_;
  bool factored_ = false;
  ChebyshevAcceleration chebyshev_;
  bool near_ = false;               // this step's matrix is not the factored one
  bool near_converged_ = true;      // and its solves converged
  std::vector<double> last_asked_;  // the spring weights the last step asked for
  // A fit's run (begin_fit_run): the factor is the run's; each step's omegas
  // and their derivatives in the measured rate are kept, and which step
  // measured it, with the rate's derivatives in its two updates.
  bool fit_run_ = false;
  std::vector<double> omegas_, d_omegas_;
  std::size_t fit_steps_ = 0;
  std::size_t measuring_step_ = SIZE_MAX;
  int half_iteration_ = 0, last_iteration_ = 0;
  double d_rate_d_half_ = 0, d_rate_d_last_ = 0;
  const double* replay_ = nullptr;
  // The iterates x^1..x^I of a recomputed step, or of every step of the run
  // (iterate_tape_, step k's from k * iterations_ * 3 n_).
  std::vector<std::vector<double>> kept_x_;
  bool tape_iterates_ = false;
  std::vector<double> iterate_tape_;
  std::vector<double> xbar_;  // a global answer, rebuilt from the iterates
  // The adjoint's scratch: dE/d(three consecutive iterates), dE/d(rhs), dE/dy.
  std::array<std::vector<double>, 3> lam_x_;
  std::vector<double> lam_r_, lam_y_, lam_base_, lam_p0_, lam_w_, lam_m_;
};

}  // namespace neurocloth
