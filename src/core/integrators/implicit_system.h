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

#include "core/base/step_threads.h"
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
  // With a team the springs are split among its threads (each spring's blocks
  // are its own: the same bits).
  void linearise(const ClothNetwork& net, const ClothState& state, bool exact_hessian = false,
                 StepThreads* team = nullptr);

  // y = alpha M u + beta D u + gamma K u on free nodes, 0 on pinned ones.
  // Vectors are 3N, interleaved (x0 y0 z0 x1 ...). With a team the nodes are
  // split among its threads; every node sums the same terms in the same order
  // whatever the split (the spring chunks' order, spring_chunks.h), so the
  // result is bit-identical to one thread's.
  void apply(const ClothNetwork& net, double alpha, double beta, double gamma,
             const std::vector<double>& u, std::vector<double>& y, StepThreads* team = nullptr) {
    apply(net, alpha, beta, gamma, u.data(), y.data(), team);
  }
  void apply(const ClothNetwork& net, double alpha, double beta, double gamma, const double* u,
             double* y, StepThreads* team = nullptr);

  // Solves A x = b; x holds the initial guess on entry. Stops when
  // |r| <= tolerance * |b| or after max_iterations. Preconditioned with the
  // factored `laplacian` between block-Jacobi sweeps when it holds a factor of
  // this cloth (precondition_laplacian), else with a V-cycle of `multigrid` when it
  // holds one, else with the diagonal of A.
  CgResult solve(const ClothNetwork& net, double alpha, double beta, double gamma,
                 const std::vector<double>& b, std::vector<double>& x, double tolerance,
                 int max_iterations, const ImplicitMultigrid* multigrid = nullptr,
                 const SpringLaplacian* laplacian = nullptr, StepThreads* team = nullptr);

  // The blocks of the last linearise(): spring s's stiffness entry e of K
  // (xx xy xz yy yz zz) and component c of the unit direction of its damping block.
  double stiffness(std::size_t s, int e) const {
    return k_[static_cast<std::size_t>(e) * springs_ + s];
  }
  double direction(std::size_t s, int c) const {
    return dir_[static_cast<std::size_t>(c) * springs_ + s];
  }

 private:
  // Inside solve() every 3N vector is planar (every node's x, then y, then z):
  // the product's chunks and the factor's solve read it so, and nothing is
  // reordered per iteration. The public apply() and solve() take interleaved
  // vectors and convert at their ends.
  //
  // The product's operands for (alpha, beta, gamma) at the last linearise(),
  // of the network as it was then (a caller changing masses or dampings
  // linearises again):
  // per spring the whole block gamma K + beta d u u^T, one array per entry so
  // that a chunk of springs is a run of vector lanes, and per node alpha m.
  // Two sets are kept: the implicit step asks for K v0 and for its system's
  // product at every step. For K alone the blocks are k_ itself.
  struct ProductOperands {
    // 6 arrays of one entry per spring (xx xy xz yy yz zz), or none when the
    // blocks are K itself (operand_blocks()): no pointer, so a copy is whole.
    std::vector<double> own_blocks;
    bool stiffness_only = false;
    std::vector<double> mass;  // alpha m per node
    double alpha = 0, beta = 0, gamma = 0;
    bool stale = true;  // made before the last linearise()
    unsigned used = 0;  // when last asked for: the older set is remade
  };
  const double* operand_blocks(const ProductOperands& o) const {
    return o.stiffness_only ? k_.data() : o.own_blocks.data();
  }
  const ProductOperands& prepare_product(const ClothNetwork& net, double alpha, double beta,
                                         double gamma, StepThreads* team = nullptr);
  // y = A u (planar) with the prepared operands; then tail(begin, end) on the
  // same part of the nodes, which may read and write any part-local vector.
  template <class Tail>
  void product(const ClothNetwork& net, const ProductOperands& A, const double* u, double* y,
               StepThreads* team, Tail&& tail);
  // z_ <- P^-1 r_: one V-cycle (through interleaved copies), or Jacobi's diag_.
  void precondition(const ClothNetwork& net, const ImplicitMultigrid* multigrid,
                    const ImplicitMultigrid::FineLevel& fine, StepThreads* team);
  // z_ <- the factored Laplacian between block-Jacobi sweeps, r_ given.
  void precondition_laplacian(const ClothNetwork& net, const ProductOperands& A,
                              const SpringLaplacian& laplacian, StepThreads* team);
  // y <- (the inverted diagonal blocks) x on nodes [begin, end), planar.
  void block_jacobi(const double* x, double* y, std::size_t begin, std::size_t end) const;
  // blocks_ <- the inverses of A's 3x3 diagonal blocks (the identity on pinned nodes).
  // Summed node by node over the spring chunks, so a team's parts give one
  // thread's bits.
  void invert_diagonal_blocks(const ClothNetwork& net, const ProductOperands& A, StepThreads* team);
  // Per spring: K block (xx xy xz yy yz zz) and D block = d * u u^T stored as the
  // unit direction u and the damping weight; planar, one array per entry (so K
  // alone is a product's operands as it is).
  std::vector<double> k_;    // 6 arrays of one entry per spring
  std::vector<double> dir_;  // 3 arrays of one entry per spring
  std::size_t springs_ = 0;
  ProductOperands operands_[2];
  unsigned product_calls_ = 0;
  std::size_t nodes_ = 0;
  // Planar scratch: the CG's vectors, the right-hand side and solution, the
  // preconditioners' and apply()'s.
  std::vector<double> r_, z_, p_, q_, x_, b_, diag_, t_, u_;
  std::vector<double> interleaved_r_, interleaved_z_;  // the multigrid's operands
  std::vector<double> blocks_;                         // 9 per node: the block-Jacobi inverses
};

}  // namespace neurocloth
