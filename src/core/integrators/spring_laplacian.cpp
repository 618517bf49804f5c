#include "core/integrators/spring_laplacian.h"

#include <Eigen/SparseCholesky>
#include <cmath>
#include <stdexcept>

namespace neurocloth {

bool SpringLaplacian::factor(const SpringLayer& layer, const std::vector<double>& node_weight,
                             const std::vector<double>& spring_weight,
                             const std::vector<double>& free) {
  const std::size_t n = node_weight.size();
  if (free.size() != n || spring_weight.size() != layer.size())
    throw std::invalid_argument("SpringLaplacian::factor: one weight per node and per spring");
  n_ = 0;
  node_weight_.clear();
  using Triplet = Eigen::Triplet<double, std::int32_t>;
  std::vector<Triplet> entries;
  entries.reserve(n + 3 * layer.size());
  for (std::size_t i = 0; i < n; ++i)
    entries.emplace_back(i, i, free[i] != 0.0 ? node_weight[i] : 1.0);
  for (std::size_t s = 0; s < layer.size(); ++s) {
    const std::int32_t a = layer.node_a[s], b = layer.node_b[s];
    const double w = spring_weight[s];
    const bool fa = free[a] != 0.0, fb = free[b] != 0.0;
    if (fa) entries.emplace_back(a, a, w);
    if (fb) entries.emplace_back(b, b, w);
    if (fa && fb) entries.emplace_back(std::max(a, b), std::min(a, b), -w);  // lower triangle
  }
  Eigen::SparseMatrix<double, Eigen::ColMajor, std::int32_t> P(n, n);
  P.setFromTriplets(entries.begin(), entries.end());  // sums duplicates
  Eigen::SimplicialLLT<decltype(P), Eigen::Lower, Eigen::AMDOrdering<std::int32_t>> llt(P);
  if (llt.info() != Eigen::Success) return false;

  const auto& L = llt.matrixL().nestedExpression();
  col_start_.assign(L.outerIndexPtr(), L.outerIndexPtr() + n + 1);
  row_.assign(L.innerIndexPtr(), L.innerIndexPtr() + L.nonZeros());
  value_.assign(L.valuePtr(), L.valuePtr() + L.nonZeros());
  for (std::size_t j = 0; j < n; ++j)  // the solve divides by the first entry of each column
    if (col_start_[j] >= col_start_[j + 1] || row_[col_start_[j]] != static_cast<std::int32_t>(j) ||
        !(value_[col_start_[j]] > 0.0))
      return false;
  const auto& p = llt.permutationP().indices();
  perm_.assign(p.data(), p.data() + n);
  inv_pivot_.resize(n);
  for (std::size_t j = 0; j < n; ++j)
    inv_pivot_[j] = 1.0 / value_[col_start_[j]];
  work4_.assign(n, Node4{0.0, 0.0, 0.0, 0.0});
  for (auto* v : {&r_, &z_, &p_, &q_})
    v->assign(3 * n, 0.0);
  node_weight_ = node_weight;
  spring_weight_ = spring_weight;
  free_ = free;
  n_ = static_cast<std::int32_t>(n);
  return true;
}

void SpringLaplacian::solve3(double* xyz) const {
  // x, y, z and a pad per node: one 4-wide multiply and subtract per factor
  // entry instead of three scalar ones.
  Node4* y = work4_.data();
  const double* const x0 = xyz;
  const double* const y0 = xyz + n_;
  const double* const z0 = xyz + 2 * n_;
  for (std::int32_t i = 0; i < n_; ++i)
    y[perm_[i]] = Node4{x0[i], y0[i], z0[i], 0.0};
  // L y' = y: each column's pivot, then its entries below.
  for (std::int32_t j = 0; j < n_; ++j) {
    const std::int32_t begin = col_start_[j], end = col_start_[j + 1];
    const Node4 yj = y[j] * inv_pivot_[j];
    y[j] = yj;
    for (std::int32_t k = begin + 1; k < end; ++k)
      y[row_[k]] -= value_[k] * yj;
  }
  // L^T z = y': each column's entries below are the row of L^T right of the
  // pivot; two partial sums halve the chain of dependent subtractions.
  // The columns are read last to first, a pattern the hardware prefetcher
  // follows badly: the column two ahead is asked for by hand.
  constexpr std::int32_t kAhead = 2;
  for (std::int32_t j = n_ - 1; j >= 0; --j) {
    const std::int32_t begin = col_start_[j] + 1, end = col_start_[j + 1];
    if (j >= kAhead) {
      for (std::int32_t k = col_start_[j - kAhead], e = col_start_[j - kAhead + 1]; k < e; k += 8)
        __builtin_prefetch(&value_[k]);
      for (std::int32_t k = col_start_[j - kAhead], e = col_start_[j - kAhead + 1]; k < e; k += 16)
        __builtin_prefetch(&row_[k]);
    }
    Node4 even = y[j], odd = Node4{0.0, 0.0, 0.0, 0.0};
    std::int32_t k = begin;
    for (; k + 1 < end; k += 2) {
      even -= value_[k] * y[row_[k]];
      odd -= value_[k + 1] * y[row_[k + 1]];
    }
    if (k < end) even -= value_[k] * y[row_[k]];
    y[j] = (even + odd) * inv_pivot_[j];
  }
  for (std::int32_t i = 0; i < n_; ++i) {
    const Node4& t = y[perm_[i]];
    xyz[i] = t[0];
    xyz[n_ + i] = t[1];
    xyz[2 * n_ + i] = t[2];
  }
}

void SpringLaplacian::multiply3(const SpringLayer& layer, const std::vector<double>& spring_weight,
                                const double* x, double* y) const {
  const std::size_t n = static_cast<std::size_t>(n_);
  for (std::size_t i = 0; i < n; ++i) {
    const double d = free_[i] != 0.0 ? node_weight_[i] : 1.0;
    for (std::size_t c = 0; c < 3; ++c)
      y[c * n + i] = d * x[c * n + i];
  }
  for (std::size_t s = 0; s < layer.size(); ++s) {
    const std::size_t a = std::size_t(layer.node_a[s]), b = std::size_t(layer.node_b[s]);
    const bool fa = free_[a] != 0.0, fb = free_[b] != 0.0;
    const double w = spring_weight[s];
    for (std::size_t c = 0; c < 3; ++c) {
      if (fa) y[c * n + a] += w * (x[c * n + a] - (fb ? x[c * n + b] : 0.0));
      if (fb) y[c * n + b] += w * (x[c * n + b] - (fa ? x[c * n + a] : 0.0));
    }
  }
}

int SpringLaplacian::solve3_near(const SpringLayer& layer, const std::vector<double>& spring_weight,
                                 double* xyz, double tolerance, int max_iterations) const {
  const std::size_t m = 3 * static_cast<std::size_t>(n_);
  auto dot = [m](const std::vector<double>& u, const std::vector<double>& v) {
    double sum = 0;
    for (std::size_t i = 0; i < m; ++i)
      sum += u[i] * v[i];
    return sum;
  };
  r_.assign(xyz, xyz + m);  // b
  const double b_norm = std::sqrt(dot(r_, r_));
  z_ = r_;
  solve3(z_.data());  // the first guess: the factored matrix's answer
  std::copy(z_.begin(), z_.end(), xyz);
  if (b_norm == 0.0) return 0;
  multiply3(layer, spring_weight, xyz, q_.data());
  for (std::size_t i = 0; i < m; ++i)
    r_[i] -= q_[i];
  z_ = r_;
  solve3(z_.data());
  p_ = z_;
  double rz = dot(r_, z_);
  for (int it = 0; it < max_iterations; ++it) {
    if (std::sqrt(dot(r_, r_)) <= tolerance * b_norm) return it;
    multiply3(layer, spring_weight, p_.data(), q_.data());
    const double pq = dot(p_, q_);
    if (!(pq > 0.0)) return -1;
    const double step = rz / pq;
    for (std::size_t i = 0; i < m; ++i) {
      xyz[i] += step * p_[i];
      r_[i] -= step * q_[i];
    }
    z_ = r_;
    solve3(z_.data());
    const double rz_new = dot(r_, z_);
    for (std::size_t i = 0; i < m; ++i)
      p_[i] = z_[i] + rz_new / rz * p_[i];
    rz = rz_new;
  }
  return std::sqrt(dot(r_, r_)) <= tolerance * b_norm ? max_iterations : -1;
}

void large_step_weights(const ClothNetwork& net, double h, std::vector<double>& node_weight,
                        std::vector<double>& spring_weight) {
  const SpringLayer& L = net.springs;
  node_weight.resize(net.node_count());
  for (std::size_t i = 0; i < node_weight.size(); ++i)
    node_weight[i] = 1.0 / net.masses.inverse_mass[i];
  const bool stiffening = L.function.kind == SpringFunctionKind::stiffening;
  const double extra = stiffening ? L.function.stiffening_factor - 1.0 : 0.0;
  spring_weight.resize(L.size());
  for (std::size_t s = 0; s < L.size(); ++s)
    spring_weight[s] = h * h * (L.stiffness[s] + L.stiffness[s] * extra) + h * L.damping[s];
}

}  // namespace neurocloth
