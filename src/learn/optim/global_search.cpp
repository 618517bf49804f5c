#include "learn/optim/global_search.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <stdexcept>

namespace neurocloth {
namespace {

// Reductions as plain loops: GCC 12's AVX-512 reductions in Eigen trip its
// -Wuninitialized at -O1 (bug 105593; src/learn/CMakeLists.txt).
double squared_norm(const Eigen::VectorXd& v) {
  double s = 0;
  for (Eigen::Index i = 0; i < v.size(); ++i)
    s += v[i] * v[i];
  return s;
}
double largest(const Eigen::VectorXd& v) {
  double m = -HUGE_VAL;
  for (Eigen::Index i = 0; i < v.size(); ++i)
    m = std::max(m, v[i]);
  return m;
}
double farthest_apart(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  double m = 0;
  for (Eigen::Index i = 0; i < a.size(); ++i)
    m = std::max(m, std::abs(a[i] - b[i]));
  return m;
}

}  // namespace

GlobalSearchResult global_search(const std::function<double(const Eigen::VectorXd&)>& f,
                                 const Eigen::VectorXd& start, const Eigen::VectorXd& width,
                                 const GlobalSearchOptions& o) {
  const auto n = static_cast<int>(start.size());
  if (n < 1 || width.size() != start.size())
    throw std::invalid_argument("global_search: start and width must be non-empty and alike");
  for (Eigen::Index i = 0; i < width.size(); ++i)
    if (!(width[i] > 0) || !std::isfinite(width[i]) || !std::isfinite(start[i]))
      throw std::invalid_argument("global_search: every width must be finite and > 0");
  if (o.evaluations < 1 || o.population < 0 || o.keep < 1)
    throw std::invalid_argument("global_search: evaluations and keep must be >= 1");

  // Parameters: Hansen's defaults; the covariance's learning rates scaled by
  // (n + 2) / 3 for the diagonal (Ros and Hansen 2008).
  const double dn = n;
  const int lambda = o.population > 0 ? o.population : 4 + int(std::floor(3 * std::log(dn)));
  const int mu = std::max(1, lambda / 2);
  Eigen::VectorXd w(mu);
  for (int i = 0; i < mu; ++i)
    w[i] = std::log(mu + 0.5) - std::log(i + 1.0);
  double w_sum = 0;
  for (int i = 0; i < mu; ++i)
    w_sum += w[i];
  w /= w_sum;
  const double mu_eff = 1 / squared_norm(w);
  const double c_sigma = (mu_eff + 2) / (dn + mu_eff + 5);
  const double d_sigma = 1 + 2 * std::max(0.0, std::sqrt((mu_eff - 1) / (dn + 1)) - 1) + c_sigma;
  const double c_c = (4 + mu_eff / dn) / (dn + 4 + 2 * mu_eff / dn);
  const double scale = (dn + 2) / 3;
  const double c_1 = std::min(1.0, scale * 2 / ((dn + 1.3) * (dn + 1.3) + mu_eff));
  const double c_mu =
      std::min(1 - c_1, scale * 2 * (mu_eff - 2 + 1 / mu_eff) / ((dn + 2) * (dn + 2) + mu_eff));
  const double chi_n = std::sqrt(dn) * (1 - 1 / (4 * dn) + 1 / (21 * dn * dn));

  // In box coordinates u: theta = start + u .* width, u in [-1, 1].
  Eigen::VectorXd m = Eigen::VectorXd::Zero(n), diag = Eigen::VectorXd::Ones(n);
  Eigen::VectorXd p_sigma = Eigen::VectorXd::Zero(n), p_c = Eigen::VectorXd::Zero(n);
  double sigma = 0.5;
  std::mt19937_64 rng(o.seed);
  std::normal_distribution<double> gauss(0.0, 1.0);

  struct Sample {
    double loss;
    Eigen::VectorXd u, z;
  };
  std::vector<Sample> seen;  // every evaluated point, for the best few
  GlobalSearchResult out;
  auto evaluate = [&](const Eigen::VectorXd& u) {
    const double loss = f(start + u.cwiseProduct(width));
    ++out.evaluations;
    return std::isfinite(loss) ? loss : HUGE_VAL;
  };
  auto stop = [&] { return o.should_stop && o.should_stop(); };

  if (!stop()) seen.push_back({evaluate(m), m, Eigen::VectorXd::Zero(n)});
  while (out.evaluations + lambda <= o.evaluations && !stop()) {
    std::vector<Sample> gen;
    for (int k = 0; k < lambda && !stop(); ++k) {
      Eigen::VectorXd z(n);
      for (int i = 0; i < n; ++i)
        z[i] = gauss(rng);
      // Kept inside the box: a coordinate beyond it is put on its face (the
      // step it took is what the update learns from).
      const Eigen::VectorXd u =
          (m + sigma * diag.cwiseSqrt().cwiseProduct(z)).cwiseMax(-1.0).cwiseMin(1.0);
      gen.push_back({evaluate(u), u, z});
    }
    if (static_cast<int>(gen.size()) < lambda) break;  // stopped mid-generation
    std::stable_sort(gen.begin(), gen.end(),
                     [](const Sample& a, const Sample& b) { return a.loss < b.loss; });
    for (const Sample& s : gen)
      seen.push_back(s);
    ++out.generations;
    // The steps y = (u - m) / sigma actually taken, best first.
    Eigen::VectorXd y_w = Eigen::VectorXd::Zero(n), z_w = Eigen::VectorXd::Zero(n);
    Eigen::VectorXd rank_mu = Eigen::VectorXd::Zero(n);
    for (int i = 0; i < mu; ++i) {
      const Eigen::VectorXd y = (gen[std::size_t(i)].u - m) / sigma;
      y_w += w[i] * y;
      z_w += w[i] * y.cwiseQuotient(diag.cwiseSqrt());
      rank_mu += w[i] * y.cwiseProduct(y);
    }
    m += sigma * y_w;
    p_sigma = (1 - c_sigma) * p_sigma + std::sqrt(c_sigma * (2 - c_sigma) * mu_eff) * z_w;
    const double lag = 1 - std::pow(1 - c_sigma, 2.0 * out.generations);
    const double p_sigma_norm = std::sqrt(squared_norm(p_sigma));
    const bool h_sigma = p_sigma_norm / std::sqrt(lag) < (1.4 + 2 / (dn + 1)) * chi_n;
    p_c = (1 - c_c) * p_c + (h_sigma ? std::sqrt(c_c * (2 - c_c) * mu_eff) : 0.0) * y_w;
    diag = (1 - c_1 - c_mu) * diag +
           c_1 * (p_c.cwiseProduct(p_c) + (h_sigma ? 0.0 : c_c * (2 - c_c)) * diag) +
           c_mu * rank_mu;
    diag = diag.cwiseMax(1e-20);
    sigma *= std::exp((c_sigma / d_sigma) * (p_sigma_norm / chi_n - 1));
    sigma = std::min(sigma, 2.0);                         // never wider than the box
    if (sigma * std::sqrt(largest(diag)) < 1e-12) break;  // converged to a point
  }

  std::stable_sort(seen.begin(), seen.end(),
                   [](const Sample& a, const Sample& b) { return a.loss < b.loss; });
  std::vector<Eigen::VectorXd> kept_u;
  for (const Sample& s : seen) {
    if (static_cast<int>(out.best.size()) == o.keep || !std::isfinite(s.loss)) break;
    bool near = false;
    for (const Eigen::VectorXd& k : kept_u)
      near = near || farthest_apart(s.u, k) < 0.05;
    if (near) continue;
    kept_u.push_back(s.u);
    out.best.push_back(start + s.u.cwiseProduct(width));
    out.losses.push_back(s.loss);
  }
  out.message = "global search (separable CMA-ES): " + std::to_string(out.evaluations) +
                " runs in " + std::to_string(out.generations) + " generations of " +
                std::to_string(lambda);
  return out;
}

}  // namespace neurocloth
