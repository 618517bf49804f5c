#pragma once
// The network linearised about a state, as a sparse operator that is never
// assembled: per spring a symmetric 3x3 stiffness block and a damping block.
//   A u = alpha M u + beta D u + gamma K u,   K = -df/dx,  D = -df/dv
// Solved by conjugate gradient, preconditioned with the diagonal of A (Jacobi),
// with a multigrid cycle of A at an earlier state (ImplicitMultigrid), or with
// the large steps' factored M + h^2 L between block-Jacobi sweeps (SpringLaplacian). Pinned nodes
// are filtered (their rows and unknowns are zero), so A stays symmetric positive definite on the
// free nodes.
#include <vector>

#include "core/integrators/implicit_multigrid.h"
#include "core/integrators/spring_laplacian.h"
#include "core/network/cloth_network.h"

namespace neurocloth {

struct CgResult {
  int iterations = 0;
  bool converged = true;
  double relative_residual = 0;
};

class ImplicitSystem {
 public:
  explicit ImplicitSystem(const ClothNetwork& net);

  // Spring blocks at `state`. The transverse stiffness f/l of a compressed spring
  // is negative; it is dropped so that K stays positive semi-definite (the
  // standard remedy since Baraff & Witkin; it removes the buckling instability from
  // the linear solve, not from the dynamics).
  // exact_hessian keeps that negative part (relaxation: at a minimum the true
  // Hessian is positive semi-definite, and keeping it restores Newton's
  // quadratic convergence on a sagging cloth).
  void linearise(const ClothNetwork& net, const ClothState& state, bool exact_hessian = false);

  // y = alpha M u + beta D u + gamma K u on free nodes, 0 on pinned ones.
  // Vectors are 3N, interleaved (x0 y0 z0 x1 ...).
  void apply(const ClothNetwork& net, double alpha, double beta, double gamma,
             const std::vector<double>& u, std::vector<double>& y) const {
    apply(net, alpha, beta, gamma, u.data(), y.data());
  }
  void apply(const ClothNetwork& net, double alpha, double beta, double gamma, const double* u,
             double* y) const;

  // Solves A x = b; x holds the initial guess on entry. Stops when
  // |r| <= tolerance * |b| or after max_iterations. Preconditioned with the
  // factored `laplacian` between block-Jacobi sweeps when it holds a factor of
  // this cloth (precondition_laplacian), else with a V-cycle of `multigrid` when it
  // holds one, else with the diagonal of A.
  CgResult solve(const ClothNetwork& net, double alpha, double beta, double gamma,
                 const std::vector<double>& b, std::vector<double>& x, double tolerance,
                 int max_iterations, const ImplicitMultigrid* multigrid = nullptr,
                 const SpringLaplacian* laplacian = nullptr);

  // The blocks of the last linearise(), per spring: K (xx xy xz yy yz zz) and
  // the unit direction of its damping block.
  const std::vector<double>& stiffness_blocks() const { return k_; }
  const std::vector<double>& directions() const { return dir_; }

 private:
  // z_ <- P^-1 r_: one V-cycle, or Jacobi's diag_ when there is none.
  void precondition(const ImplicitMultigrid* multigrid, const ImplicitMultigrid::FineLevel& fine);
  void precondition_laplacian(const ClothNetwork& net, double alpha, double beta, double gamma,
                              const SpringLaplacian& laplacian);
  // y <- P^-1 x for the factored matrix, x and y interleaved.
  void laplacian_solve(const SpringLaplacian& laplacian, const double* x, double* y);
  // y <- (the inverted diagonal blocks) x.
  void block_jacobi(const double* x, double* y) const;
  // blocks_ <- the inverses of A's 3x3 diagonal blocks (the identity on pinned nodes).
  void invert_diagonal_blocks(const ClothNetwork& net, double alpha, double beta, double gamma);
  // Per spring: K block (xx xy xz yy yz zz) and D block = d * u u^T stored as the
  // unit direction u and the damping weight.
  std::vector<double> k_;    // 6 per spring
  std::vector<double> dir_;  // 3 per spring
  std::vector<double> r_, z_, p_, q_, diag_;
  std::vector<double> planar_, t_, u_;  // the Laplacian preconditioner's scratch
  std::vector<double> blocks_;          // 9 per node, for the multigrid's smoother
};

}  // namespace neurocloth
