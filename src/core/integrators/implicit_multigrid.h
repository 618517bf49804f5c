#pragma once
// Smoothed-aggregation algebraic multigrid (Vanek, Mandel & Brezina 1996; for
// cloth, Tamstorf, Jones & McCormick 2015) for the implicit step's matrix
//   A = alpha M + beta D + gamma K,
// assembled from ImplicitSystem's spring blocks at one state: 3N x 3N, every
// spring a 3x3 block along its direction, pinned rows and columns the identity.
// One V-cycle is the conjugate gradient's preconditioner.
//
// Why multigrid: on a stiff cloth the error the diagonal (Jacobi) cannot see is
// smooth along the springs and spans the whole cloth, so its iterations grow
// with the nodes per side. Aggregates of neighbouring nodes carry that smooth
// error on coarser and coarser levels, so the iterations stay nearly flat as
// the cloth is refined. The smoother is block Jacobi (each node's own 3x3
// block), which follows the springs' directions at that node.
//
// A hierarchy is made at one state and serves later steps: its finest level
// is smoothed with the present matrix and blocks, and only its coarse levels
// are of the state it was made at; they degrade as the springs turn, and the
// implicit step rebuilds them when that stops paying (implicit_euler.cpp).
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <functional>
#include <vector>

#include "core/network/cloth_network.h"

namespace neurocloth {

class ImplicitSystem;

class ImplicitMultigrid {
 public:
  // Above this the build's assembly (about 3.5 kB a node while it lasts) would
  // need hundreds of MB: the implicit step keeps Jacobi.
  static constexpr std::size_t kMaxNodes = 256 * 256;
  // Below this the implicit step keeps Jacobi, which was cheaper there: on the
  // hanging cloth at 32 x 32, 0.33 s per simulated second against the
  // multigrid's 0.82 (126 against 20 iterations that cost far more each);
  // at 64 x 64 and above the multigrid was cheaper (docs/network.md).
  static constexpr std::size_t kMinNodes = 48 * 48;

  // Builds the hierarchy of A at the blocks `system` holds. Returns false (and
  // holds none) beyond kMaxNodes or when the coarsest matrix is not definite.
  // A cloth small enough to be its own coarsest level is factored whole.
  bool build(const ClothNetwork& net, const ImplicitSystem& system, double alpha, double beta,
             double gamma);
  bool built() const { return !coarsest_.empty(); }

  // The finest level as it is now: y = A x for the present matrix, and the
  // inverses of its nodes' 3x3 diagonal blocks (9 per node, row major).
  struct FineLevel {
    std::function<void(const double* x, double* y)> apply;
    const std::vector<double>* block_inverse = nullptr;
  };
  // z = B r, one V-cycle from z = 0 (symmetric, positive definite): smoothed
  // with the present finest matrix, corrected on the coarse levels made at
  // build(). r and z are 3N, interleaved (x0 y0 z0 x1 ...).
  void solve(const FineLevel& fine, const std::vector<double>& r, std::vector<double>& z) const;

  // Inverts 3x3 blocks in place (9 per node, row major); a block that is not
  // positive definite gets the inverse of its diagonal (1 where that is not positive).
  static void invert_blocks(std::vector<double>& blocks);

  // True when the hierarchy was made with the network's present masses, pins,
  // stiffnesses and dampings (it may be of another state and other coefficients).
  bool made_for(const ClothNetwork& net) const;
  // ... and with these coefficients.
  bool made_for(const ClothNetwork& net, double alpha, double beta, double gamma) const {
    return made_for(net) && alpha == alpha_ && beta == beta_ && gamma == gamma_;
  }

  // Cost figures in multiply-adds, counted from the matrices (so a refresh
  // rule built on them gives the same bits on every machine).
  double cycle_cost() const { return cycle_cost_; }
  double build_cost() const { return build_cost_; }
  int levels() const { return static_cast<int>(levels_.size()) + 1; }

 private:
  using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;
  struct Level {
    SparseMatrix A;  // this level's matrix (both triangles); the finest's is not kept
    SparseMatrix P;  // prolongation from the next coarser level
    SparseMatrix R;  // P^T
    std::vector<double> block_inverse;  // 9 per node: the inverse of its 3x3 diagonal block
    double weight = 0;                  // smoother's damping: 4 / (3 rho(D^-1 A))
  };
  std::vector<Level> levels_;     // finest first; the coarsest matrix is factored densely
  std::vector<double> coarsest_;  // dense lower Cholesky factor of the coarsest matrix, row major
  mutable std::vector<Eigen::VectorXd> x_, b_, r_;  // per level, and the coarsest
  double cycle_cost_ = 0, build_cost_ = 0;
  double alpha_ = 0, beta_ = 0, gamma_ = 0;
  std::vector<double> inverse_mass_, free_, stiffness_, damping_;

  void cycle(std::size_t level, const FineLevel& fine) const;
  void smooth(std::size_t level, const FineLevel& fine) const;
  void residual(std::size_t level, const FineLevel& fine) const;  // r_ = b_ - A x_
};

}  // namespace neurocloth
