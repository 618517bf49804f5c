#include "core/integrators/spectral_bound.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "core/integrators/stability.h"

namespace neurocloth {
namespace {

constexpr double kLanczosDelta = 0.02;        // relative error allowed from below
constexpr double kLanczosMissChance = 1e-12;  // chance the error exceeds it
constexpr double kLanczosBreakdown =
    1e-13;  // |beta| / |alpha_1| at which the Krylov space is whole

// y = S L S x over every node (S = 0 on pinned nodes, so they stay at 0).
void laplacian_apply(const ClothNetwork& net, const SpectralScratch& s,
                     const std::vector<double>& x, std::vector<double>& y,
                     std::vector<double>& spread) {
  const std::size_t n = net.node_count();
  for (std::size_t i = 0; i < n; ++i)
    spread[i] = s.scale[i] * x[i];
  std::fill(y.begin(), y.end(), 0.0);
  const auto& a = net.springs.node_a;
  const auto& b = net.springs.node_b;
  for (std::size_t k = 0; k < net.spring_count(); ++k) {
    const double f = s.weight[k] * (spread[a[k]] - spread[b[k]]);
    y[a[k]] += f;
    y[b[k]] -= f;
  }
  for (std::size_t i = 0; i < n; ++i)
    y[i] *= s.scale[i];
}

double lanczos_dot(const std::vector<double>& x, const std::vector<double>& y) {
  double sum = 0;
  for (std::size_t i = 0; i < x.size(); ++i)
    sum += x[i] * y[i];
  return sum;
}

// A fixed start, spread over every free node (splitmix64), so the bound is a
// function of the network alone: the same cloth gives the same bits.
void lanczos_start(const SpectralScratch& s, std::vector<double>& q) {
  std::uint64_t state = 0x9e3779b97f4a7c15ull;
  for (std::size_t i = 0; i < q.size(); ++i) {
    std::uint64_t z = (state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    z ^= z >> 31;
    const double u = static_cast<double>(z >> 11) * 0x1.0p-53;  // [0, 1)
    q[i] = s.scale[i] != 0.0 ? u - 0.5 : 0.0;
  }
}

}  // namespace

double spectral_round_up(double x) {
  if (!(x > 0.0) || std::isinf(x)) return x;
  int exponent = 0;
  const double mantissa = std::frexp(x, &exponent);  // [0.5, 1)
  return std::ldexp(std::ceil(std::ldexp(mantissa, kSpectralBits)), exponent - kSpectralBits);
}

int spectral_lanczos_steps(std::size_t n) {
  if (n == 0) return 0;
  // 1.648 sqrt(n) exp(-sqrt(delta) (2k - 1)) <= kLanczosMissChance
  const double x = std::log(1.648 * std::sqrt(static_cast<double>(n)) / kLanczosMissChance);
  const double k = std::ceil((x / std::sqrt(kLanczosDelta) + 1.0) / 2.0);
  return static_cast<int>(std::min<double>(k, static_cast<double>(n)));
}

namespace {

// The top eigenvalue for the weights already in s.weight.
double lanczos_top_eigenvalue(const ClothNetwork& net, SpectralScratch& s) {
  const std::size_t n = net.node_count();
  // A free node counts when some weighted spring reaches it (spread marks them).
  s.spread.assign(n, 0.0);
  for (std::size_t k = 0; k < net.spring_count(); ++k) {
    if (s.weight[k] == 0.0) continue;
    s.spread[net.springs.node_a[k]] = s.spread[net.springs.node_b[k]] = 1.0;
  }
  s.scale.assign(n, 0.0);
  std::size_t free_nodes = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double w = std::abs(net.masses.inverse_mass[i]);
    if (net.masses.free[i] == 0.0 || s.spread[i] == 0.0 || w == 0.0) continue;
    s.scale[i] = std::sqrt(w);
    ++free_nodes;
  }
  if (free_nodes == 0) return 0.0;
  const int steps = spectral_lanczos_steps(free_nodes);
  s.prev.assign(n, 0.0);
  s.cur.assign(n, 0.0);
  s.next.assign(n, 0.0);
  s.spread.assign(n, 0.0);
  s.alpha.clear();
  s.beta.clear();
  lanczos_start(s, s.cur);
  const double norm = std::sqrt(lanczos_dot(s.cur, s.cur));
  for (double& v : s.cur)
    v /= norm;
  double beta = 0;
  for (int j = 0; j < steps; ++j) {
    laplacian_apply(net, s, s.cur, s.next, s.spread);
    const double alpha = lanczos_dot(s.cur, s.next);
    for (std::size_t i = 0; i < n; ++i)
      s.next[i] -= alpha * s.cur[i] + beta * s.prev[i];
    s.alpha.push_back(alpha);
    beta = std::sqrt(lanczos_dot(s.next, s.next));
    if (!(beta > kLanczosBreakdown * std::abs(s.alpha.front())))
      break;  // the Krylov space is whole
    if (j + 1 == steps) break;
    s.beta.push_back(beta);
    for (std::size_t i = 0; i < n; ++i) {
      s.prev[i] = s.cur[i];
      s.cur[i] = s.next[i] / beta;
    }
  }
  const Eigen::Index m = static_cast<Eigen::Index>(s.alpha.size());
  if (m == 0) return std::numeric_limits<double>::quiet_NaN();
  Eigen::VectorXd diagonal = Eigen::Map<const Eigen::VectorXd>(s.alpha.data(), m);
  Eigen::VectorXd sub(std::max<Eigen::Index>(m - 1, 0));
  for (Eigen::Index i = 0; i + 1 < m; ++i)
    sub[i] = s.beta[static_cast<std::size_t>(i)];
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen;
  eigen.computeFromTridiagonal(diagonal, sub, Eigen::EigenvaluesOnly);
  if (eigen.info() != Eigen::Success) return std::numeric_limits<double>::quiet_NaN();
  // Eigen returns the eigenvalues in increasing order; reading the last one also keeps
  // GCC 12's AVX-512 maxCoeff reduction (a maybe-uninitialized warning) out of the build.
  return spectral_round_up(eigen.eigenvalues()[m - 1] / (1.0 - kLanczosDelta));
}

}  // namespace

double laplacian_top_eigenvalue(const ClothNetwork& net, const std::vector<double>& weight,
                                SpectralScratch& s) {
  s.weight.resize(weight.size());
  for (std::size_t k = 0; k < weight.size(); ++k)
    s.weight[k] = std::abs(weight[k]);
  return lanczos_top_eigenvalue(net, s);
}

double spectral_step_bound(const ClothNetwork& net, double limit, SpectralScratch& s,
                           bool with_damping) {
  const double gershgorin = stable_step_bound(net, limit, s.k_sum, s.d_sum, with_damping);
  if (!std::isfinite(gershgorin) || !with_damping) return gershgorin;
  // The springs' part stays Gershgorin's (see the header): its largest disc
  // (k_sum already holds k |slope|).
  double omega2 = 0;
  for (std::size_t i = 0; i < net.node_count(); ++i)
    if (net.masses.free[i] != 0.0)
      omega2 = std::max(omega2, 2.0 * std::abs(net.masses.inverse_mass[i]) * s.k_sum[i]);
  s.weight.resize(net.spring_count());
  for (std::size_t k = 0; k < s.weight.size(); ++k)
    s.weight[k] = std::abs(net.springs.damping[k]);
  const double lambda_d = lanczos_top_eigenvalue(net, s);
  if (!std::isfinite(lambda_d) || !std::isfinite(omega2)) return gershgorin;
  const double denom = lambda_d + std::sqrt(lambda_d * lambda_d + limit * limit * omega2);
  if (!(denom > 0.0)) return gershgorin;
  return std::max(gershgorin, limit * limit / denom);
}

}  // namespace neurocloth
