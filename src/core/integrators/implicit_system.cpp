#include "core/integrators/implicit_system.h"

#include <algorithm>
#include <cmath>

namespace neurocloth {

ImplicitSystem::ImplicitSystem(const ClothNetwork& net)
    : k_(6 * net.spring_count(), 0.0), dir_(3 * net.spring_count(), 0.0) {
  const std::size_t dofs = 3 * net.node_count();
  for (auto* v : {&r_, &z_, &p_, &q_, &diag_, &planar_, &t_, &u_})
    v->assign(dofs, 0.0);
}

void ImplicitSystem::invert_diagonal_blocks(const ClothNetwork& net, double alpha, double beta,
                                            double gamma) {
  const std::size_t n = net.node_count();
  blocks_.assign(9 * n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const double m = alpha / net.masses.inverse_mass[i];
    for (int c = 0; c < 3; ++c)
      blocks_[9 * i + 4 * c] = m;
  }
  const SpringLayer& L = net.springs;
  for (std::size_t s = 0; s < L.size(); ++s) {
    const double* K = &k_[6 * s];
    const double* d = &dir_[3 * s];
    const double c = beta * L.damping[s];
    const double k[9] = {K[0], K[1], K[2], K[1], K[3], K[4], K[2], K[4], K[5]};
    for (const std::int32_t node : {L.node_a[s], L.node_b[s]}) {
      double* B = &blocks_[9 * static_cast<std::size_t>(node)];
      for (int r = 0; r < 3; ++r)
        for (int col = 0; col < 3; ++col)
          B[3 * r + col] += gamma * k[3 * r + col] + c * d[r] * d[col];
    }
  }
  for (std::size_t i = 0; i < n; ++i)
    if (net.masses.free[i] == 0.0)
      for (int e = 0; e < 9; ++e)
        blocks_[9 * i + e] = e % 4 == 0 ? 1.0 : 0.0;
  ImplicitMultigrid::invert_blocks(blocks_);
}

void ImplicitSystem::linearise(const ClothNetwork& net, const ClothState& s, bool exact_hessian) {
  const SpringLayer& L = net.springs;
  for (std::size_t i = 0; i < L.size(); ++i) {
    const Vec3 d = s.position(L.node_b[i]) - s.position(L.node_a[i]);
    const double len = d.norm();
    double* K = &k_[6 * i];
    double* u = &dir_[3 * i];
    if (!(len > kMinSpringLength)) {  // no direction: no linearisation either
      std::fill(K, K + 6, 0.0);
      std::fill(u, u + 3, 0.0);
      continue;
    }
    const Vec3 n = d / len;
    const double e = len - L.rest_length[i];
    const double axial = L.stiffness[i] * L.function.slope(e, L.rest_length[i]);
    const double tension = L.stiffness[i] * L.function.force(e, L.rest_length[i]) / len;
    const double transverse = exact_hessian ? tension : std::max(0.0, tension);
    // K = axial n n^T + transverse (I - n n^T)
    const double a = axial - transverse;
    K[0] = a * n.x() * n.x() + transverse;
    K[1] = a * n.x() * n.y();
    K[2] = a * n.x() * n.z();
    K[3] = a * n.y() * n.y() + transverse;
    K[4] = a * n.y() * n.z();
    K[5] = a * n.z() * n.z() + transverse;
    u[0] = n.x();
    u[1] = n.y();
    u[2] = n.z();
  }
}

void ImplicitSystem::apply(const ClothNetwork& net, double alpha, double beta, double gamma,
                           const double* u, double* y) const {
  const std::size_t n = net.node_count();
  for (std::size_t i = 0; i < n; ++i) {
    const double m = alpha / net.masses.inverse_mass[i];
    y[3 * i] = m * u[3 * i];
    y[3 * i + 1] = m * u[3 * i + 1];
    y[3 * i + 2] = m * u[3 * i + 2];
  }
  const SpringLayer& L = net.springs;
  for (std::size_t s = 0; s < L.size(); ++s) {
    const std::size_t a = 3 * static_cast<std::size_t>(L.node_a[s]);
    const std::size_t b = 3 * static_cast<std::size_t>(L.node_b[s]);
    const double dx = u[a] - u[b], dy = u[a + 1] - u[b + 1], dz = u[a + 2] - u[b + 2];
    const double* K = &k_[6 * s];
    const double* d = &dir_[3 * s];
    const double proj = beta * L.damping[s] * (d[0] * dx + d[1] * dy + d[2] * dz);
    const double fx = gamma * (K[0] * dx + K[1] * dy + K[2] * dz) + proj * d[0];
    const double fy = gamma * (K[1] * dx + K[3] * dy + K[4] * dz) + proj * d[1];
    const double fz = gamma * (K[2] * dx + K[4] * dy + K[5] * dz) + proj * d[2];
    y[a] += fx;
    y[a + 1] += fy;
    y[a + 2] += fz;
    y[b] -= fx;
    y[b + 1] -= fy;
    y[b + 2] -= fz;
  }
  for (std::size_t i = 0; i < n; ++i)
    if (net.masses.free[i] == 0.0) y[3 * i] = y[3 * i + 1] = y[3 * i + 2] = 0.0;
}

namespace {
double dot(const std::vector<double>& a, const std::vector<double>& b) {
  double s = 0;
  for (std::size_t i = 0; i < a.size(); ++i)
    s += a[i] * b[i];
  return s;
}
}  // namespace

CgResult ImplicitSystem::solve(const ClothNetwork& net, double alpha, double beta, double gamma,
                               const std::vector<double>& b, std::vector<double>& x,
                               double tolerance, int max_iterations,
                               const ImplicitMultigrid* multigrid,
                               const SpringLaplacian* laplacian) {
  const std::size_t n = net.node_count();
  const SpringLayer& L = net.springs;
  if (laplacian != nullptr && (!laplacian->factored() || laplacian->nodes() != n))
    laplacian = nullptr;
  const bool cycled = laplacian == nullptr && multigrid != nullptr && multigrid->built();
  ImplicitMultigrid::FineLevel fine;
  if (cycled || laplacian != nullptr) {
    invert_diagonal_blocks(net, alpha, beta, gamma);
    fine.block_inverse = &blocks_;
    fine.apply = [&](const double* u, double* y) { apply(net, alpha, beta, gamma, u, y); };
  }
  // Jacobi preconditioner: the diagonal of A.
  for (std::size_t i = 0; i < n; ++i) {
    const double m = alpha / net.masses.inverse_mass[i];
    diag_[3 * i] = diag_[3 * i + 1] = diag_[3 * i + 2] = m;
  }
  for (std::size_t s = 0; s < L.size(); ++s) {
    const double* K = &k_[6 * s];
    const double* d = &dir_[3 * s];
    const double c = beta * L.damping[s];
    const double dd[3] = {gamma * K[0] + c * d[0] * d[0], gamma * K[3] + c * d[1] * d[1],
                          gamma * K[5] + c * d[2] * d[2]};
    for (int k = 0; k < 3; ++k) {
      diag_[3 * L.node_a[s] + k] += dd[k];
      diag_[3 * L.node_b[s] + k] += dd[k];
    }
  }
  for (std::size_t i = 0; i < n; ++i) {
    const bool pinned = net.masses.free[i] == 0.0;
    for (int k = 0; k < 3; ++k) {
      double& dk = diag_[3 * i + k];
      dk = (pinned || !(dk > 0.0)) ? 1.0 : dk;
      if (pinned) x[3 * i + k] = 0.0;
    }
  }

  CgResult result;
  const double b_norm = std::sqrt(dot(b, b));
  if (b_norm == 0.0) {
    std::fill(x.begin(), x.end(), 0.0);
    return result;
  }
  apply(net, alpha, beta, gamma, x, q_);
  for (std::size_t i = 0; i < r_.size(); ++i)
    r_[i] = b[i] - q_[i];
  for (std::size_t i = 0; i < n; ++i)
    if (net.masses.free[i] == 0.0) r_[3 * i] = r_[3 * i + 1] = r_[3 * i + 2] = 0.0;
  auto precondition_any = [&] {
    if (laplacian != nullptr)
      precondition_laplacian(net, alpha, beta, gamma, *laplacian);
    else
      precondition(cycled ? multigrid : nullptr, fine);
  };
  precondition_any();
  p_ = z_;
  double rz = dot(r_, z_);
  double r_norm = std::sqrt(dot(r_, r_));
  int it = 0;
  while (r_norm > tolerance * b_norm && it < max_iterations) {
    apply(net, alpha, beta, gamma, p_, q_);
    const double pq = dot(p_, q_);
    // Negative curvature (an indefinite system, or NaN): stop with the iterate
    // so far, which is still a descent direction for a relaxation (Steihaug).
    if (!(pq > 0.0)) break;
    const double step = rz / pq;
    for (std::size_t i = 0; i < x.size(); ++i) {
      x[i] += step * p_[i];
      r_[i] -= step * q_[i];
    }
    precondition_any();
    const double rz_new = dot(r_, z_);
    const double beta_cg = rz_new / rz;
    rz = rz_new;
    for (std::size_t i = 0; i < p_.size(); ++i)
      p_[i] = z_[i] + beta_cg * p_[i];
    r_norm = std::sqrt(dot(r_, r_));
    ++it;
  }
  result.iterations = it;
  result.relative_residual = r_norm / b_norm;
  result.converged = r_norm <= tolerance * b_norm;
  return result;
}

void ImplicitSystem::laplacian_solve(const SpringLaplacian& laplacian, const double* x, double* y) {
  const std::size_t n = laplacian.nodes();
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t c = 0; c < 3; ++c)
      planar_[c * n + i] = x[3 * i + c];
  laplacian.solve3(planar_.data());
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t c = 0; c < 3; ++c)
      y[3 * i + c] = planar_[c * n + i];
}

void ImplicitSystem::block_jacobi(const double* x, double* y) const {
  const std::size_t n = blocks_.size() / 9;
  for (std::size_t i = 0; i < n; ++i) {
    const double* B = &blocks_[9 * i];
    const double* u = x + 3 * i;
    double* v = y + 3 * i;
    v[0] = B[0] * u[0] + B[1] * u[1] + B[2] * u[2];
    v[1] = B[3] * u[0] + B[4] * u[1] + B[5] * u[2];
    v[2] = B[6] * u[0] + B[7] * u[1] + B[8] * u[2];
  }
}

// z <- B r, a symmetric two-part cycle: a block-Jacobi sweep S, the factored
// Laplacian P's correction of what is left, and S again:
//   z = S r;  z += P^-1 (r - A z);  z += S (r - A z).
// P = M + h^2 L holds every spring at its full stiffness in every direction,
// while A's springs are stiff only along themselves: alone, P is far too stiff
// for the cloth's transverse motion (477 iterations a step at 128 x 128, tol
// 1e-10), which A sees as little more than its mass, and which S, each node's
// own 3x3 block, solves nearly exactly. The stiff smooth motion along the
// springs is P's, as a coarse level's in a multigrid (docs/network.md).
void ImplicitSystem::precondition_laplacian(const ClothNetwork& net, double alpha, double beta,
                                            double gamma, const SpringLaplacian& laplacian) {
  const std::size_t m = r_.size();
  block_jacobi(r_.data(), z_.data());
  apply(net, alpha, beta, gamma, z_.data(), t_.data());
  for (std::size_t i = 0; i < m; ++i)
    t_[i] = r_[i] - t_[i];
  laplacian_solve(laplacian, t_.data(), u_.data());
  for (std::size_t i = 0; i < m; ++i)
    z_[i] += u_[i];
  apply(net, alpha, beta, gamma, z_.data(), t_.data());
  for (std::size_t i = 0; i < m; ++i)
    t_[i] = r_[i] - t_[i];
  block_jacobi(t_.data(), u_.data());
  for (std::size_t i = 0; i < m; ++i)
    z_[i] += u_[i];
}

void ImplicitSystem::precondition(const ImplicitMultigrid* multigrid,
                                  const ImplicitMultigrid::FineLevel& fine) {
  if (multigrid != nullptr) {
    multigrid->solve(fine, r_, z_);
    return;
  }
  for (std::size_t i = 0; i < r_.size(); ++i)
    z_[i] = r_[i] / diag_[i];
}

}  // namespace neurocloth
