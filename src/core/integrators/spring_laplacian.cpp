#include "core/integrators/spring_laplacian.h"

#include <Eigen/SparseCholesky>
#include <cmath>
#include <stdexcept>

#include "core/integrators/spring_laplacian_order.h"

namespace neurocloth {

bool SpringLaplacian::factor(const SpringLayer& layer, const std::vector<double>& node_weight,
                             const std::vector<double>& spring_weight,
                             const std::vector<double>& free) {
  const std::size_t n = node_weight.size();
  if (free.size() != n || spring_weight.size() != layer.size())
    throw std::invalid_argument("SpringLaplacian::factor: one weight per node and per spring");
  n_ = 0;
  half_ = separator_ = 0;
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
  LaplacianPattern P(n, n);
  P.setFromTriplets(entries.begin(), entries.end());  // sums duplicates
  // From kMinThreadedNodes nodes the order is a dissection (laplacian_order)
  // and the factor is of the reordered matrix in its natural order; below, or
  // when the graph does not split, Eigen's minimum-degree order as it always
  // was (the shipped scenes keep their bits).
  std::int32_t half = 0, separator = 0;
  std::vector<std::int32_t> place;
  if (n >= kMinThreadedNodes) laplacian_order(P, place, half, separator);
  auto take = [&](const auto& llt) {
    if (llt.info() != Eigen::Success) return false;
    const auto& L = llt.matrixL().nestedExpression();
    col_start_.assign(L.outerIndexPtr(), L.outerIndexPtr() + n + 1);
    row_.assign(L.innerIndexPtr(), L.innerIndexPtr() + L.nonZeros());
    value_.assign(L.valuePtr(), L.valuePtr() + L.nonZeros());
    return true;
  };
  if (half > 0) {
    Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, std::int32_t> to_place(
        static_cast<std::int32_t>(n));
    for (std::size_t i = 0; i < n; ++i)
      to_place.indices()[static_cast<std::int32_t>(i)] = place[i];
    LaplacianPattern ordered(n, n);
    ordered.selfadjointView<Eigen::Lower>() = P.selfadjointView<Eigen::Lower>().twistedBy(to_place);
    if (!take(Eigen::SimplicialLLT<LaplacianPattern, Eigen::Lower,
                                   Eigen::NaturalOrdering<std::int32_t>>(ordered)))
      return false;
  } else {
    const Eigen::SimplicialLLT<LaplacianPattern, Eigen::Lower, Eigen::AMDOrdering<std::int32_t>>
        llt(P);
    if (!take(llt)) return false;
    const auto& p = llt.permutationP().indices();
    place.assign(p.data(), p.data() + n);
    separator = 0;
  }
  for (std::size_t j = 0; j < n; ++j)  // the solve divides by the first entry of each column
    if (col_start_[j] >= col_start_[j + 1] || row_[col_start_[j]] != static_cast<std::int32_t>(j) ||
        !(value_[col_start_[j]] > 0.0))
      return false;
  node_at_.resize(n);
  for (std::size_t i = 0; i < n; ++i)
    node_at_[static_cast<std::size_t>(place[i])] = static_cast<std::int32_t>(i);
  // Where each half's column passes into the separator's rows; a column of
  // one half with a row in the other would break the dissection (it cannot:
  // no edge crosses the separator, and elimination only joins nodes through
  // eliminated ones), so it is checked, and the factor kept whole if it does.
  half_ = half;
  separator_ = separator;
  separator_rows_.assign(static_cast<std::size_t>(separator), 0);
  for (std::int32_t j = 0; j < separator && half_ > 0; ++j) {
    const std::int32_t own_end = j < half ? half : separator;
    std::int32_t k = col_start_[j] + 1;
    while (k < col_start_[j + 1] && row_[k] < own_end)
      ++k;
    separator_rows_[static_cast<std::size_t>(j)] = k;
    for (std::int32_t e = k; e < col_start_[j + 1]; ++e)
      if (row_[e] < separator) half_ = 0;
  }
  if (half_ == 0) separator_ = 0;
  for (auto& sums : separator_sums_)
    sums.assign(static_cast<std::size_t>(n) - static_cast<std::size_t>(separator_),
                Node4{0.0, 0.0, 0.0, 0.0});
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

void SpringLaplacian::forward_half(std::int32_t begin, std::int32_t end,
                                   std::vector<Node4>& sums) const {
  Node4* y = work4_.data();
  for (Node4& v : sums)
    v = Node4{0.0, 0.0, 0.0, 0.0};
  for (std::int32_t j = begin; j < end; ++j) {
    const std::int32_t own_end = separator_rows_[static_cast<std::size_t>(j)];
    const Node4 yj = y[j] * inv_pivot_[j];
    y[j] = yj;
    for (std::int32_t k = col_start_[j] + 1; k < own_end; ++k)
      y[row_[k]] -= value_[k] * yj;
    for (std::int32_t k = own_end; k < col_start_[j + 1]; ++k)
      sums[static_cast<std::size_t>(row_[k] - separator_)] += value_[k] * yj;
  }
}

// L^T z = y' over columns [begin, end), last to first: each column's entries
// below are the row of L^T right of the pivot; two partial sums halve the
// chain of dependent subtractions. The columns are read last to first, a
// pattern the hardware prefetcher follows badly: the column two ahead is
// asked for by hand.
void SpringLaplacian::backward(std::int32_t begin, std::int32_t end) const {
  Node4* y = work4_.data();
  constexpr std::int32_t kAhead = 2;
  for (std::int32_t j = end - 1; j >= begin; --j) {
    const std::int32_t first = col_start_[j] + 1, last = col_start_[j + 1];
    if (j >= kAhead) {
      for (std::int32_t k = col_start_[j - kAhead], e = col_start_[j - kAhead + 1]; k < e; k += 8)
        __builtin_prefetch(&value_[k]);
      for (std::int32_t k = col_start_[j - kAhead], e = col_start_[j - kAhead + 1]; k < e; k += 16)
        __builtin_prefetch(&row_[k]);
    }
    Node4 even = y[j], odd = Node4{0.0, 0.0, 0.0, 0.0};
    std::int32_t k = first;
    for (; k + 1 < last; k += 2) {
      even -= value_[k] * y[row_[k]];
      odd -= value_[k + 1] * y[row_[k + 1]];
    }
    if (k < last) even -= value_[k] * y[row_[k]];
    y[j] = (even + odd) * inv_pivot_[j];
  }
}

void SpringLaplacian::solve3(double* xyz, StepThreads* team) const {
  // x, y, z and a pad per node: one 4-wide multiply and subtract per factor
  // entry instead of three scalar ones.
  Node4* y = work4_.data();
  // Rows [begin, end) of the factor from their nodes, and back: each part
  // moves its own rows.
  auto load = [&](std::int32_t begin, std::int32_t end) {
    for (std::int32_t j = begin; j < end; ++j) {
      const std::int32_t i = node_at_[static_cast<std::size_t>(j)];
      y[j] = Node4{xyz[i], xyz[n_ + i], xyz[2 * n_ + i], 0.0};
    }
  };
  auto store = [&](std::int32_t begin, std::int32_t end) {
    for (std::int32_t j = begin; j < end; ++j) {
      const std::int32_t i = node_at_[static_cast<std::size_t>(j)];
      xyz[i] = y[j][0];
      xyz[n_ + i] = y[j][1];
      xyz[2 * n_ + i] = y[j][2];
    }
  };
  // L y' = y: each column's pivot, then its entries below. The halves first
  // (at once on a team), their sums into the separator's rows added after, in
  // one order whatever the team.
  auto forward = [&](std::int32_t begin, std::int32_t end) {
    for (std::int32_t j = begin; j < end; ++j) {
      const Node4 yj = y[j] * inv_pivot_[j];
      y[j] = yj;
      for (std::int32_t k = col_start_[j] + 1; k < col_start_[j + 1]; ++k)
        y[row_[k]] -= value_[k] * yj;
    }
  };
  if (half_ > 0) {
    const std::int32_t begin[2] = {0, half_}, end[2] = {half_, separator_};
    run_halves(team, [&](int p) {
      load(begin[p], end[p]);
      forward_half(begin[p], end[p], separator_sums_[p]);
    });
    load(separator_, n_);
    for (std::int32_t r = separator_; r < n_; ++r) {
      const auto s = static_cast<std::size_t>(r - separator_);
      y[r] = (y[r] - separator_sums_[0][s]) - separator_sums_[1][s];
    }
    forward(separator_, n_);
    backward(separator_, n_);
    store(separator_, n_);
    run_halves(team, [&](int p) {
      backward(begin[p], end[p]);
      store(begin[p], end[p]);
    });
  } else {
    load(0, n_);
    forward(0, n_);
    backward(0, n_);
    store(0, n_);
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
                                 double* xyz, double tolerance, int max_iterations,
                                 StepThreads* team) const {
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
  solve3(z_.data(), team);  // the first guess: the factored matrix's answer
  std::copy(z_.begin(), z_.end(), xyz);
  if (b_norm == 0.0) return 0;
  multiply3(layer, spring_weight, xyz, q_.data());
  for (std::size_t i = 0; i < m; ++i)
    r_[i] -= q_[i];
  z_ = r_;
  solve3(z_.data(), team);
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
    solve3(z_.data(), team);
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
