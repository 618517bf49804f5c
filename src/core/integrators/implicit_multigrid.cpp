#include "core/integrators/implicit_multigrid.h"

#include <algorithm>
#include <cmath>

#include "core/integrators/implicit_system.h"

namespace neurocloth {
namespace {

using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;
using Triplet = Eigen::Triplet<double, int>;

constexpr int kSmoothingSweeps = 2;  // before and after the coarse correction
constexpr int kCoarsestNodes = 64;   // factored densely at or below this
constexpr int kMaxLevels = 12;
constexpr int kCoarsestRows = 3000;  // beyond, coarsening has stalled: no hierarchy
constexpr double kStrength = 0.08;   // a strong coupling: |a_ij| >= this * sqrt(a_ii a_jj)
constexpr double kSmootherOmega = 4.0 / 3.0;
// A build's multiply-adds are counted as the products' flops; assembling from
// triplets and Eigen's sparse products cost about this many times more per
// counted one than a cycle's matrix-vector products (measured at 32 x 32 and
// 128 x 128: a build took the time of about 100 cycles, its count said 4.5).
constexpr double kBuildOverhead = 20;

// A = alpha M + beta D + gamma K, both triangles; a spring's block
// B = gamma K + beta d u u^T couples its ends as [B -B; -B B], and nothing
// touches a pinned node, whose rows are the identity.
SparseMatrix assemble(const ClothNetwork& net, const ImplicitSystem& system, double alpha,
                      double beta, double gamma) {
  const std::size_t nodes = net.node_count();
  const SpringLayer& L = net.springs;
  const std::vector<double>& free = net.masses.free;
  std::vector<Triplet> entries;
  entries.reserve(3 * nodes + 36 * L.size());
  for (std::size_t i = 0; i < nodes; ++i) {
    const double m = free[i] != 0.0 ? alpha / net.masses.inverse_mass[i] : 1.0;
    for (int c = 0; c < 3; ++c)
      entries.emplace_back(3 * i + c, 3 * i + c, m);
  }
  for (std::size_t s = 0; s < L.size(); ++s) {
    const double K[6] = {system.stiffness(s, 0), system.stiffness(s, 1), system.stiffness(s, 2),
                         system.stiffness(s, 3), system.stiffness(s, 4), system.stiffness(s, 5)};
    const double u[3] = {system.direction(s, 0), system.direction(s, 1), system.direction(s, 2)};
    const double c = beta * L.damping[s];
    const double k[3][3] = {{K[0], K[1], K[2]}, {K[1], K[3], K[4]}, {K[2], K[4], K[5]}};
    const int a = L.node_a[s], b = L.node_b[s];
    const bool fa = free[a] != 0.0, fb = free[b] != 0.0;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        const double B = gamma * k[i][j] + c * u[i] * u[j];
        if (fa) entries.emplace_back(3 * a + i, 3 * a + j, B);
        if (fb) entries.emplace_back(3 * b + i, 3 * b + j, B);
        if (fa && fb) {
          entries.emplace_back(3 * a + i, 3 * b + j, -B);
          entries.emplace_back(3 * b + i, 3 * a + j, -B);
        }
      }
  }
  SparseMatrix A(static_cast<int>(3 * nodes), static_cast<int>(3 * nodes));
  A.setFromTriplets(entries.begin(), entries.end());  // sums duplicates
  return A;
}

// The inverse of every node's 3x3 diagonal block, 9 per node (row major).
// A block that is not positive definite is replaced by the inverse of its
// diagonal, or by the identity where that is not positive either. (Plain
// loops, here and below: Eigen's dense kernels trip GCC 12's
// -Wmaybe-uninitialized when built for AVX-512, cmake/compiler_workarounds.cmake.)
std::vector<double> block_inverses(const SparseMatrix& A) {
  const int nodes = A.cols() / 3;
  std::vector<double> blocks(9 * static_cast<std::size_t>(nodes), 0.0);
  for (int i = 0; i < nodes; ++i)
    for (int c = 0; c < 3; ++c)
      for (SparseMatrix::InnerIterator it(A, 3 * i + c); it; ++it)
        if (it.row() / 3 == i)
          blocks[9 * static_cast<std::size_t>(i) + 3 * (it.row() - 3 * i) + c] = it.value();
  ImplicitMultigrid::invert_blocks(blocks);
  return blocks;
}

void apply_block_inverse(const std::vector<double>& inv, const Eigen::VectorXd& r,
                         Eigen::VectorXd& z) {
  const Eigen::Index nodes = r.size() / 3;
  for (Eigen::Index i = 0; i < nodes; ++i) {
    const double* D = &inv[9 * static_cast<std::size_t>(i)];
    const double x = r[3 * i], y = r[3 * i + 1], w = r[3 * i + 2];
    z[3 * i] = D[0] * x + D[1] * y + D[2] * w;
    z[3 * i + 1] = D[3] * x + D[4] * y + D[5] * w;
    z[3 * i + 2] = D[6] * x + D[7] * y + D[8] * w;
  }
}

double norm(const Eigen::VectorXd& v) {
  double s = 0;
  for (Eigen::Index i = 0; i < v.size(); ++i)
    s += v[i] * v[i];
  return std::sqrt(s);
}

// The largest eigenvalue of D^-1 A (similar to a symmetric matrix, so real),
// by power iteration from a fixed vector; slightly over-estimated so that the
// smoother's weight stays on the safe side.
double spectral_radius(const SparseMatrix& A, const std::vector<double>& inv) {
  Eigen::VectorXd v(A.cols()), w(A.cols()), z(A.cols());
  for (Eigen::Index i = 0; i < v.size(); ++i)
    v[i] = 1.0 + static_cast<double>(i % 7) / 7.0;
  double rho = 1.0;
  for (int k = 0; k < 15; ++k) {
    v /= norm(v);
    w = A * v;
    apply_block_inverse(inv, w, z);
    rho = norm(z);
    if (!(rho > 0.0)) return 1.0;
    v = z;
  }
  return 1.1 * rho;
}

// Standard aggregation on the strong couplings between nodes: first every node
// whose neighbours are all free of an aggregate seeds one with them, then the
// rest join a neighbour's. A node without strong couplings (a pinned one) is
// in none (-1); the smoother alone solves it. Returns the number of aggregates.
int aggregate(const SparseMatrix& A, std::vector<int>& of) {
  const int nodes = A.cols() / 3;
  std::vector<double> diag(A.cols());
  for (int j = 0; j < A.cols(); ++j)
    diag[j] = std::abs(A.coeff(j, j));
  std::vector<std::vector<int>> neighbours(nodes);
  for (int j = 0; j < A.cols(); ++j)
    for (SparseMatrix::InnerIterator it(A, j); it; ++it) {
      const int I = static_cast<int>(it.row()) / 3, J = j / 3;
      if (I != J && std::abs(it.value()) >= kStrength * std::sqrt(diag[it.row()] * diag[j]))
        neighbours[J].push_back(I);
    }
  for (auto& n : neighbours) {
    std::sort(n.begin(), n.end());
    n.erase(std::unique(n.begin(), n.end()), n.end());
  }
  of.assign(nodes, -1);
  int count = 0;
  for (int i = 0; i < nodes; ++i) {
    if (of[i] >= 0 || neighbours[i].empty()) continue;
    if (std::any_of(neighbours[i].begin(), neighbours[i].end(), [&](int j) { return of[j] >= 0; }))
      continue;
    of[i] = count;
    for (int j : neighbours[i])
      of[j] = count;
    ++count;
  }
  const std::vector<int> seeded = of;
  for (int i = 0; i < nodes; ++i) {
    if (of[i] >= 0) continue;
    for (int j : neighbours[i])
      if (seeded[j] >= 0) {
        of[i] = seeded[j];
        break;
      }
    if (of[i] < 0 && !neighbours[i].empty()) of[i] = count++;  // neighbours only in pass two
  }
  return count;
}

// The dense lower Cholesky factor of a small matrix, row major in `L`; false
// when it is not positive definite.
bool factor_dense(const SparseMatrix& A, std::vector<double>& L) {
  const int n = A.rows();
  L.assign(static_cast<std::size_t>(n) * n, 0.0);
  for (int j = 0; j < n; ++j)
    for (SparseMatrix::InnerIterator it(A, j); it; ++it)
      if (it.row() >= j) L[static_cast<std::size_t>(it.row()) * n + j] = it.value();
  for (int j = 0; j < n; ++j) {
    double* Lj = &L[static_cast<std::size_t>(j) * n];
    double d = Lj[j];
    for (int k = 0; k < j; ++k)
      d -= Lj[k] * Lj[k];
    if (!(d > 0.0)) return false;
    Lj[j] = std::sqrt(d);
    for (int i = j + 1; i < n; ++i) {
      double* Li = &L[static_cast<std::size_t>(i) * n];
      double s = Li[j];
      for (int k = 0; k < j; ++k)
        s -= Li[k] * Lj[k];
      Li[j] = s / Lj[j];
    }
  }
  return true;
}

void solve_dense(const std::vector<double>& L, const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  const Eigen::Index n = b.size();
  for (Eigen::Index i = 0; i < n; ++i) {
    const double* Li = &L[static_cast<std::size_t>(i * n)];
    double s = b[i];
    for (Eigen::Index k = 0; k < i; ++k)
      s -= Li[k] * x[k];
    x[i] = s / Li[i];
  }
  for (Eigen::Index i = n - 1; i >= 0; --i) {
    double s = x[i];
    for (Eigen::Index k = i + 1; k < n; ++k)
      s -= L[static_cast<std::size_t>(k * n + i)] * x[k];
    x[i] = s / L[static_cast<std::size_t>(i * n + i)];
  }
}

}  // namespace

void ImplicitMultigrid::invert_blocks(std::vector<double>& blocks) {
  for (std::size_t i = 0; i < blocks.size(); i += 9) {
    double* out = &blocks[i];
    const double D[3][3] = {
        {out[0], out[1], out[2]}, {out[3], out[4], out[5]}, {out[6], out[7], out[8]}};
    // Cofactors; positive definite iff the leading minors are positive.
    const double c00 = D[1][1] * D[2][2] - D[1][2] * D[2][1];
    const double c01 = D[1][2] * D[2][0] - D[1][0] * D[2][2];
    const double c02 = D[1][0] * D[2][1] - D[1][1] * D[2][0];
    const double det = D[0][0] * c00 + D[0][1] * c01 + D[0][2] * c02;
    const double minor2 = D[0][0] * D[1][1] - D[0][1] * D[1][0];
    if (D[0][0] > 0.0 && minor2 > 0.0 && det > 0.0) {
      const double adj[3][3] = {
          {c00, D[0][2] * D[2][1] - D[0][1] * D[2][2], D[0][1] * D[1][2] - D[0][2] * D[1][1]},
          {c01, D[0][0] * D[2][2] - D[0][2] * D[2][0], D[0][2] * D[1][0] - D[0][0] * D[1][2]},
          {c02, D[0][1] * D[2][0] - D[0][0] * D[2][1], minor2}};
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c)
          out[3 * r + c] = adj[r][c] / det;
    } else {
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c)
          out[3 * r + c] = r != c ? 0.0 : D[c][c] > 0.0 ? 1.0 / D[c][c] : 1.0;
    }
  }
}

bool ImplicitMultigrid::build(const ClothNetwork& net, const ImplicitSystem& system, double alpha,
                              double beta, double gamma) {
  levels_.clear();
  coarsest_.clear();
  if (net.node_count() > kMaxNodes) return false;
  SparseMatrix A = assemble(net, system, alpha, beta, gamma);
  cycle_cost_ = 0;
  build_cost_ = 0;
  std::vector<int> of;
  while (static_cast<int>(levels_.size()) < kMaxLevels - 1 && A.cols() / 3 > kCoarsestNodes) {
    const int nodes = A.cols() / 3;
    const int coarse = aggregate(A, of);
    if (coarse == 0 || coarse > nodes * 3 / 4) break;  // no longer coarsening
    Level L;
    L.block_inverse = block_inverses(A);
    L.weight = kSmootherOmega / spectral_radius(A, L.block_inverse);
    // Tentative prolongation: each aggregate's three translations, normalised;
    // then smoothed by one damped block-Jacobi step, P = (I - w D^-1 A) P0.
    std::vector<int> size(coarse, 0);
    for (int i = 0; i < nodes; ++i)
      if (of[i] >= 0) ++size[of[i]];
    std::vector<Triplet> p0;
    std::vector<Triplet> dinv;
    for (int i = 0; i < nodes; ++i) {
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c)
          dinv.emplace_back(3 * i + r, 3 * i + c,
                            L.block_inverse[9 * static_cast<std::size_t>(i) + 3 * r + c]);
      if (of[i] < 0) continue;
      for (int c = 0; c < 3; ++c)
        p0.emplace_back(3 * i + c, 3 * of[i] + c, 1.0 / std::sqrt(size[of[i]]));
    }
    SparseMatrix P0(A.rows(), 3 * coarse), Dinv(A.rows(), A.cols());
    P0.setFromTriplets(p0.begin(), p0.end());
    Dinv.setFromTriplets(dinv.begin(), dinv.end());
    const SparseMatrix AP0 = A * P0;
    L.P = P0 - L.weight * (Dinv * AP0);
    L.R = L.P.transpose();
    const SparseMatrix AP = A * L.P;
    SparseMatrix coarse_A = L.R * AP;
    const SparseMatrix coarse_At = coarse_A.transpose();
    coarse_A = 0.5 * (coarse_A + coarse_At);  // symmetric to rounding, so the cycle is
    const double per_row = static_cast<double>(L.P.nonZeros()) / static_cast<double>(A.rows());
    build_cost_ += static_cast<double>(A.nonZeros()) * (1.0 + 2.0 * per_row) +
                   static_cast<double>(AP.nonZeros()) * per_row;
    cycle_cost_ += static_cast<double>(A.nonZeros()) * (2 * kSmoothingSweeps + 1) +
                   2.0 * static_cast<double>(L.P.nonZeros());
    if (!levels_.empty()) L.A = std::move(A);  // the finest is applied as it is now
    if (levels_.empty()) L.block_inverse.clear();
    A = std::move(coarse_A);
    levels_.push_back(std::move(L));
  }
  const bool definite = A.rows() <= kCoarsestRows && factor_dense(A, coarsest_);
  const double rows = static_cast<double>(A.rows());
  build_cost_ = kBuildOverhead * build_cost_ + rows * rows * rows / 3.0;
  cycle_cost_ += 2.0 * rows * rows;
  if (!definite) {
    levels_.clear();
    coarsest_.clear();
    return false;
  }
  x_.assign(levels_.size() + 1, Eigen::VectorXd());
  b_ = x_;
  r_ = x_;
  for (std::size_t l = 0; l < levels_.size(); ++l) {
    const Eigen::Index n = levels_[l].P.rows();
    x_[l].setZero(n);
    b_[l].setZero(n);
    r_[l].setZero(n);
  }
  x_.back().setZero(A.rows());
  b_.back().setZero(A.rows());
  alpha_ = alpha;
  beta_ = beta;
  gamma_ = gamma;
  inverse_mass_ = net.masses.inverse_mass;
  free_ = net.masses.free;
  stiffness_ = net.springs.stiffness;
  damping_ = net.springs.damping;
  return true;
}

bool ImplicitMultigrid::made_for(const ClothNetwork& net) const {
  return built() && net.masses.inverse_mass == inverse_mass_ && net.masses.free == free_ &&
         net.springs.stiffness == stiffness_ && net.springs.damping == damping_;
}

void ImplicitMultigrid::solve(const FineLevel& fine, const std::vector<double>& r,
                              std::vector<double>& z) const {
  b_[0] = Eigen::Map<const Eigen::VectorXd>(r.data(), static_cast<Eigen::Index>(r.size()));
  if (levels_.empty())
    solve_dense(coarsest_, b_[0], x_[0]);
  else
    cycle(0, fine);
  Eigen::Map<Eigen::VectorXd>(z.data(), static_cast<Eigen::Index>(z.size())) = x_[0];
}

// x += w D^-1 (b - A x), with the finest level's present operator and blocks.
void ImplicitMultigrid::smooth(std::size_t l, const FineLevel& fine) const {
  residual(l, fine);
  const std::vector<double>& inverse = l == 0 ? *fine.block_inverse : levels_[l].block_inverse;
  apply_block_inverse(inverse, r_[l], r_[l]);  // in place: a node reads only its own entries
  x_[l] += levels_[l].weight * r_[l];
}

void ImplicitMultigrid::residual(std::size_t l, const FineLevel& fine) const {
  if (l == 0) {
    fine.apply(x_[0].data(), r_[0].data());
    r_[0] = b_[0] - r_[0];
  } else {
    r_[l] = b_[l] - levels_[l].A * x_[l];
  }
}

void ImplicitMultigrid::cycle(std::size_t l, const FineLevel& fine) const {
  const Level& L = levels_[l];
  x_[l].setZero();
  for (int k = 0; k < kSmoothingSweeps; ++k)
    smooth(l, fine);
  residual(l, fine);
  b_[l + 1] = L.R * r_[l];
  if (l + 1 == levels_.size())
    solve_dense(coarsest_, b_[l + 1], x_[l + 1]);
  else
    cycle(l + 1, fine);
  x_[l] += L.P * x_[l + 1];
  for (int k = 0; k < kSmoothingSweeps; ++k)
    smooth(l, fine);
}

}  // namespace neurocloth
