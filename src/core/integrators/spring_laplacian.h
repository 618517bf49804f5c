#pragma once
// The constant matrix of a cloth's large steps (Liu et al. 2013, "Fast
// simulation of mass-spring systems"):
//   P = diag(node_weight) + sum_s w_s (e_a - e_b)(e_a - e_b)^T
// one scalar row per node, the same for x, y and z: the springs' graph
// Laplacian weighted per spring, plus a mass term. Pinned nodes are fixed, so
// their rows are the identity and a spring to one adds only to the free end's
// diagonal; with every node massive or anchored, P is symmetric positive
// definite. Factored once by a sparse Cholesky (fill-reducing order) and then
// solved for the three components at a time, reading the factor once.
//
// It is the global step of the `projective` integrator, refactored only when
// what built it changes (`same_as`): a weight, a mass, a pin, or the step.
#include <cstdint>
#include <vector>

#include "core/base/step_threads.h"
#include "core/network/cloth_network.h"

namespace neurocloth {

class SpringLaplacian {
 public:
  // node_weight and free are per node, spring_weight per spring of `layer`.
  // Returns false (and holds no factor) when P is not positive definite, e.g. a
  // free node without mass or anchor.
  bool factor(const SpringLayer& layer, const std::vector<double>& node_weight,
              const std::vector<double>& spring_weight, const std::vector<double>& free);
  bool factored() const { return n_ > 0; }
  std::size_t nodes() const { return static_cast<std::size_t>(n_); }

  // xyz <- P^-1 xyz for the three components stored one after another
  // (x0 x1 ... y0 y1 ... z0 z1 ...): 3 * nodes() values. Planar, as the
  // cloth's state is, so the local step's spring loops read whole vectors.
  // On a cloth of kMinThreadedNodes nodes or more the factor is ordered as two
  // halves and the separator between them, and a team's first two threads
  // solve the halves at once; the result does not depend on the team.
  void solve3(double* xyz, StepThreads* team = nullptr) const;

  // True when factor() was last called with exactly these arguments.
  bool same_as(const std::vector<double>& node_weight, const std::vector<double>& spring_weight,
               const std::vector<double>& free) const {
    return n_ > 0 && node_weight == node_weight_ && spring_weight == spring_weight_ &&
           free == free_;
  }
  // True when the factor was made for these masses and pins (its springs' weights may differ).
  bool same_nodes(const std::vector<double>& node_weight, const std::vector<double>& free) const {
    return n_ > 0 && node_weight == node_weight_ && free == free_;
  }
  // Solves P' x = b for the matrix P' of (node_weight_, spring_weight) — another step
  // or other weights on the same nodes — by conjugate gradient with this factor
  // as the preconditioner: exact to `tolerance` (relative residual) in a few
  // iterations when P' is close to the factored P. `xyz` (planar, as solve3's)
  // holds b on entry, x on return. Returns the iterations taken, or -1 when it did not converge.
  int solve3_near(const SpringLayer& layer, const std::vector<double>& spring_weight, double* xyz,
                  double tolerance, int max_iterations, StepThreads* team = nullptr) const;
  // True when the factor is ordered as two halves and a separator (solve3).
  bool dissected() const { return half_ > 0; }
  // Entries of the factor (a cost figure: each solve reads them once).
  std::size_t factor_entries() const { return row_.size(); }

 private:
  std::int32_t n_ = 0;
  // The lower factor L of the permuted P, column by column (CSC), the diagonal
  // first in every column; P = perm^T L L^T perm (perm: node_at_).
  std::vector<std::int32_t> col_start_, row_;
  std::vector<double> value_;
  std::vector<std::int32_t> node_at_;  // row j of the factor is node node_at_[j]
  std::vector<double> inv_pivot_;      // 1 / the diagonal of L
  // The dissection (spring_laplacian_order.cpp): columns [0, half_) are one
  // half of the nodes, [half_, separator_) the other, [separator_, n_) the
  // nodes between them, which neither half's columns pass over. A half's
  // column j has its rows in its own half up to separator_rows_[j], then in
  // the separator. half_ == 0: not dissected.
  std::int32_t half_ = 0, separator_ = 0;
  std::vector<std::int32_t> separator_rows_;
  // A node's x, y, z and a pad, for the solves (a GCC/Clang vector: the
  // compilers we build with).
  typedef double Node4 __attribute__((vector_size(32)));
  mutable std::vector<Node4> work4_;
  // What each half subtracts from the separator's rows in the forward solve,
  // kept apart so the halves never write one row (added in a fixed order).
  mutable std::vector<Node4> separator_sums_[2];
  // The forward solve's columns [begin, end) of one half, and the backward's.
  void forward_half(std::int32_t begin, std::int32_t end, std::vector<Node4>& sums) const;
  void backward(std::int32_t begin, std::int32_t end) const;
  mutable std::vector<double> r_, z_, p_, q_;
  // y = P' x for the matrix with these spring weights (on this factor's nodes).
  void multiply3(const SpringLayer& layer, const std::vector<double>& spring_weight,
                 const double* x, double* y) const;
  std::vector<double> node_weight_, spring_weight_, free_;
};

// The weights of a large step h on `net`, the matrix both large-step
// integrators factor: node_weight the masses, spring_weight h^2 (k + k') + h d
// per spring, k' the stiffening function's extra stiffness beyond its threshold
// (projective's global step; implicit_euler's preconditioner).
void large_step_weights(const ClothNetwork& net, double h, std::vector<double>& node_weight,
                        std::vector<double>& spring_weight);

}  // namespace neurocloth
