#include "core/integrators/implicit_system.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "core/network/spring_chunks.h"

namespace neurocloth {
namespace {

// Interleaved (x0 y0 z0 x1 ...) to planar (x0 x1 ... y0 ... z0 ...) and back.
void to_planar(const double* in, double* out, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t c = 0; c < 3; ++c)
      out[c * n + i] = in[3 * i + c];
}
void to_interleaved(const double* in, double* out, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t c = 0; c < 3; ++c)
      out[3 * i + c] = in[c * n + i];
}

// Serial, in one order, so that the sums do not depend on a team.
double dot(const std::vector<double>& a, const std::vector<double>& b) {
  double s = 0;
  for (std::size_t i = 0; i < a.size(); ++i)
    s += a[i] * b[i];
  return s;
}

// fn(k) for every planar entry k of nodes [begin, end): the three components.
template <class Fn>
void for_entries(std::size_t n, std::size_t begin, std::size_t end, Fn&& fn) {
  for (std::size_t c = 0; c < 3; ++c)
    for (std::size_t k = c * n + begin, stop = c * n + end; k < stop; ++k)
      fn(k);
}

}  // namespace

ImplicitSystem::ImplicitSystem(const ClothNetwork& net)
    : k_(6 * net.spring_count(), 0.0),
      dir_(3 * net.spring_count(), 0.0),
      springs_(net.spring_count()),
      nodes_(net.node_count()) {
  const std::size_t dofs = 3 * net.node_count();
  for (auto* v : {&r_, &z_, &p_, &q_, &x_, &b_, &diag_, &t_, &u_})
    v->assign(dofs, 0.0);
}

void ImplicitSystem::invert_diagonal_blocks(const ClothNetwork& net, const ProductOperands& A,
                                            StepThreads* team) {
  const std::size_t n = net.node_count();
  blocks_.resize(9 * n);
  const SpringLayer& L = net.springs;
  const std::size_t S = springs_;
  const double* const B = operand_blocks(A);
  for_node_parts(team, n, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i)
      for (int e = 0; e < 9; ++e)
        blocks_[9 * i + e] = e % 4 == 0 ? A.mass[i] : 0.0;
    const auto lo = static_cast<std::int32_t>(begin), hi = static_cast<std::int32_t>(end);
    spring_chunks::for_each_chunk(
        L, [&](std::int32_t first, std::int32_t count, std::int32_t a, std::int32_t b, bool) {
          if (!((a < hi && a + count > lo) || (b < hi && b + count > lo))) return;
          for (std::int32_t j = 0; j < count; ++j) {
            const auto s = static_cast<std::size_t>(first + j);
            const double e[6] = {B[s],         B[S + s],     B[2 * S + s],
                                 B[3 * S + s], B[4 * S + s], B[5 * S + s]};
            const double block[9] = {e[0], e[1], e[2], e[1], e[3], e[4], e[2], e[4], e[5]};
            for (const std::int32_t node : {a + j, b + j}) {
              if (node < lo || node >= hi) continue;
              double* D = &blocks_[9 * static_cast<std::size_t>(node)];
              for (int k = 0; k < 9; ++k)
                D[k] += block[k];
            }
          }
        });
    for (std::size_t i = begin; i < end; ++i)
      if (net.masses.free[i] == 0.0)
        for (int e = 0; e < 9; ++e)
          blocks_[9 * i + e] = e % 4 == 0 ? 1.0 : 0.0;
  });
  ImplicitMultigrid::invert_blocks(blocks_);
}

void ImplicitSystem::linearise(const ClothNetwork& net, const ClothState& s, bool exact_hessian,
                               StepThreads* team) {
  const SpringLayer& L = net.springs;
  for (ProductOperands& o : operands_)
    o.stale = true;
  for_parts(team, net.node_count(), L.size(), [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      const Vec3 d = s.position(L.node_b[i]) - s.position(L.node_a[i]);
      const double len = d.norm();
      const std::size_t S = springs_;
      if (!(len > kMinSpringLength)) {  // no direction: no linearisation either
        for (std::size_t e = 0; e < 6; ++e)
          k_[e * S + i] = 0.0;
        for (std::size_t c = 0; c < 3; ++c)
          dir_[c * S + i] = 0.0;
        continue;
      }
      const Vec3 n = d / len;
      const double e = len - L.rest_length[i];
      const double axial = L.stiffness[i] * L.function.slope(e, L.rest_length[i]);
      const double tension = L.stiffness[i] * L.function.force(e, L.rest_length[i]) / len;
      const double transverse = exact_hessian ? tension : std::max(0.0, tension);
      // K = axial n n^T + transverse (I - n n^T)
      const double a = axial - transverse;
      k_[i] = a * n.x() * n.x() + transverse;
      k_[S + i] = a * n.x() * n.y();
      k_[2 * S + i] = a * n.x() * n.z();
      k_[3 * S + i] = a * n.y() * n.y() + transverse;
      k_[4 * S + i] = a * n.y() * n.z();
      k_[5 * S + i] = a * n.z() * n.z() + transverse;
      dir_[i] = n.x();
      dir_[S + i] = n.y();
      dir_[2 * S + i] = n.z();
    }
  });
}

const ImplicitSystem::ProductOperands& ImplicitSystem::prepare_product(const ClothNetwork& net,
                                                                       double alpha, double beta,
                                                                       double gamma,
                                                                       StepThreads* team) {
  ++product_calls_;
  for (ProductOperands& o : operands_)
    if (!o.stale && o.alpha == alpha && o.beta == beta && o.gamma == gamma) {
      o.used = product_calls_;
      return o;
    }
  ProductOperands& o = operands_[0].used <= operands_[1].used ? operands_[0] : operands_[1];
  const std::size_t n = net.node_count();
  o.mass.resize(n);
  for (std::size_t i = 0; i < n; ++i)
    o.mass[i] = alpha / net.masses.inverse_mass[i];
  const SpringLayer& L = net.springs;
  const std::size_t S = springs_;
  o.stiffness_only = beta == 0.0 && gamma == 1.0;
  if (!o.stiffness_only) {
    o.own_blocks.resize(6 * S);
    double* B = o.own_blocks.data();
    const double* K = k_.data();
    const double *dx = dir_.data(), *dy = dx + S, *dz = dy + S;
    for_parts(team, n, S, [&](std::size_t begin, std::size_t end) {
      for (std::size_t s = begin; s < end; ++s) {
        const double c = beta * L.damping[s];
        B[s] = gamma * K[s] + c * dx[s] * dx[s];
        B[S + s] = gamma * K[S + s] + c * dx[s] * dy[s];
        B[2 * S + s] = gamma * K[2 * S + s] + c * dx[s] * dz[s];
        B[3 * S + s] = gamma * K[3 * S + s] + c * dy[s] * dy[s];
        B[4 * S + s] = gamma * K[4 * S + s] + c * dy[s] * dz[s];
        B[5 * S + s] = gamma * K[5 * S + s] + c * dz[s] * dz[s];
      }
    });
  }
  o.alpha = alpha;
  o.beta = beta;
  o.gamma = gamma;
  o.stale = false;
  o.used = product_calls_;
  return o;
}

// Walked as the force is (spring_chunks.h): a chunk of springs whose ends are
// runs of consecutive nodes is one pass of vector lanes over u, and its
// outputs reach the nodes through accumulate_chunk, clipped to the part's
// nodes, so every node sums the same terms in the same order whatever the
// parts. A chunk reads u at nodes of other parts: u must be whole before.
template <class Tail>
void ImplicitSystem::product(const ClothNetwork& net, const ProductOperands& A, const double* u,
                             double* y, StepThreads* team, Tail&& tail) {
  const std::size_t n = net.node_count();
  const SpringLayer& L = net.springs;
  const std::size_t springs = L.size();
  const double* const ux = u;
  const double* const uy = u + n;
  const double* const uz = u + 2 * n;
  double* const yx = y;
  double* const yy = y + n;
  double* const yz = y + 2 * n;
  for_node_parts(team, n, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      const double m = A.mass[i];
      yx[i] = m * ux[i];
      yy[i] = m * uy[i];
      yz[i] = m * uz[i];
    }
    const auto lo = static_cast<std::int32_t>(begin), hi = static_cast<std::int32_t>(end);
    spring_chunks::Chunk chunk;
    spring_chunks::for_each_chunk(
        L, [&](std::int32_t first, std::int32_t count, std::int32_t a, std::int32_t b, bool) {
          if (!((a < hi && a + count > lo) || (b < hi && b + count > lo))) return;
          const double* bxx = operand_blocks(A) + first;
          const double* bxy = bxx + springs;
          const double* bxz = bxy + springs;
          const double* byy = bxz + springs;
          const double* byz = byy + springs;
          const double* bzz = byz + springs;
          for (std::int32_t j = 0; j < count; ++j) {
            const double dx = ux[a + j] - ux[b + j];
            const double dy = uy[a + j] - uy[b + j];
            const double dz = uz[a + j] - uz[b + j];
            chunk.fx[j] = bxx[j] * dx + bxy[j] * dy + bxz[j] * dz;
            chunk.fy[j] = bxy[j] * dx + byy[j] * dy + byz[j] * dz;
            chunk.fz[j] = bxz[j] * dx + byz[j] * dy + bzz[j] * dz;
          }
          spring_chunks::accumulate_chunk(count, a, b, chunk.fx, chunk.fy, chunk.fz, {yx, yy, yz},
                                          lo, hi);
        });
    for (std::size_t i = begin; i < end; ++i)
      if (net.masses.free[i] == 0.0) yx[i] = yy[i] = yz[i] = 0.0;
    tail(begin, end);
  });
}

void ImplicitSystem::apply(const ClothNetwork& net, double alpha, double beta, double gamma,
                           const double* u, double* y, StepThreads* team) {
  const ProductOperands& A = prepare_product(net, alpha, beta, gamma, team);
  const std::size_t n = net.node_count();
  to_planar(u, t_.data(), n);
  product(net, A, t_.data(), u_.data(), team, [](std::size_t, std::size_t) {});
  to_interleaved(u_.data(), y, n);
}

CgResult ImplicitSystem::solve(const ClothNetwork& net, double alpha, double beta, double gamma,
                               const std::vector<double>& b, std::vector<double>& x,
                               double tolerance, int max_iterations,
                               const ImplicitMultigrid* multigrid, const SpringLaplacian* laplacian,
                               StepThreads* team) {
  const std::size_t n = net.node_count();
  const SpringLayer& L = net.springs;
  if (laplacian != nullptr && (!laplacian->factored() || laplacian->nodes() != n))
    laplacian = nullptr;
  const bool cycled = laplacian == nullptr && multigrid != nullptr && multigrid->built();
  ImplicitMultigrid::FineLevel fine;
  if (cycled || laplacian != nullptr) {
    invert_diagonal_blocks(net, prepare_product(net, alpha, beta, gamma, team), team);
    fine.block_inverse = &blocks_;
    fine.apply = [&](const double* u, double* y) { apply(net, alpha, beta, gamma, u, y); };
  }
  if (laplacian == nullptr && !cycled) {  // Jacobi: the diagonal of A
    for (std::size_t i = 0; i < n; ++i) {
      const double m = alpha / net.masses.inverse_mass[i];
      diag_[i] = diag_[n + i] = diag_[2 * n + i] = m;
    }
    for (std::size_t s = 0; s < L.size(); ++s) {
      const double c = beta * L.damping[s];
      const double dd[3] = {gamma * stiffness(s, 0) + c * direction(s, 0) * direction(s, 0),
                            gamma * stiffness(s, 3) + c * direction(s, 1) * direction(s, 1),
                            gamma * stiffness(s, 5) + c * direction(s, 2) * direction(s, 2)};
      for (std::size_t k = 0; k < 3; ++k) {
        diag_[k * n + static_cast<std::size_t>(L.node_a[s])] += dd[k];
        diag_[k * n + static_cast<std::size_t>(L.node_b[s])] += dd[k];
      }
    }
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t k = 0; k < 3; ++k) {
        double& dk = diag_[k * n + i];
        dk = (net.masses.free[i] == 0.0 || !(dk > 0.0)) ? 1.0 : dk;
      }
  }
  to_planar(b.data(), b_.data(), n);
  to_planar(x.data(), x_.data(), n);
  for (std::size_t i = 0; i < n; ++i)
    if (net.masses.free[i] == 0.0) x_[i] = x_[n + i] = x_[2 * n + i] = 0.0;

  CgResult result;
  const double b_norm = std::sqrt(dot(b_, b_));
  if (b_norm == 0.0) {
    std::fill(x.begin(), x.end(), 0.0);
    return result;
  }
  const ProductOperands& A = prepare_product(net, alpha, beta, gamma, team);
  product(net, A, x_.data(), q_.data(), team, [&](std::size_t begin, std::size_t end) {
    for_entries(n, begin, end, [&](std::size_t k) { r_[k] = b_[k] - q_[k]; });
    for (std::size_t i = begin; i < end; ++i)
      if (net.masses.free[i] == 0.0) r_[i] = r_[n + i] = r_[2 * n + i] = 0.0;
  });
  auto precondition_any = [&] {
    if (laplacian != nullptr)
      precondition_laplacian(net, A, *laplacian, team);
    else
      precondition(net, cycled ? multigrid : nullptr, fine, team);
  };
  precondition_any();
  p_ = z_;
  double rz = dot(r_, z_);
  double r_norm = std::sqrt(dot(r_, r_));
  int it = 0;
  while (r_norm > tolerance * b_norm && it < max_iterations) {
    product(net, A, p_.data(), q_.data(), team, [](std::size_t, std::size_t) {});
    const double pq = dot(p_, q_);
    // Negative curvature (an indefinite system, or NaN): stop with the iterate
    // so far, which is still a descent direction for a relaxation (Steihaug).
    if (!(pq > 0.0)) break;
    const double step = rz / pq;
    for_node_parts(team, n, [&](std::size_t begin, std::size_t end) {
      for_entries(n, begin, end, [&](std::size_t k) {
        x_[k] += step * p_[k];
        r_[k] -= step * q_[k];
      });
    });
    precondition_any();
    const double rz_new = dot(r_, z_);
    const double beta_cg = rz_new / rz;
    rz = rz_new;
    for_node_parts(team, n, [&](std::size_t begin, std::size_t end) {
      for_entries(n, begin, end, [&](std::size_t k) { p_[k] = z_[k] + beta_cg * p_[k]; });
    });
    r_norm = std::sqrt(dot(r_, r_));
    ++it;
  }
  to_interleaved(x_.data(), x.data(), n);
  result.iterations = it;
  result.relative_residual = r_norm / b_norm;
  result.converged = r_norm <= tolerance * b_norm;
  return result;
}

void ImplicitSystem::block_jacobi(const double* x, double* y, std::size_t begin,
                                  std::size_t end) const {
  const std::size_t n = nodes_;
  for (std::size_t i = begin; i < end; ++i) {
    const double* B = &blocks_[9 * i];
    const double u0 = x[i], u1 = x[n + i], u2 = x[2 * n + i];
    y[i] = B[0] * u0 + B[1] * u1 + B[2] * u2;
    y[n + i] = B[3] * u0 + B[4] * u1 + B[5] * u2;
    y[2 * n + i] = B[6] * u0 + B[7] * u1 + B[8] * u2;
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
void ImplicitSystem::precondition_laplacian(const ClothNetwork& net, const ProductOperands& A,
                                            const SpringLaplacian& laplacian, StepThreads* team) {
  const std::size_t n = nodes_;
  for_node_parts(team, n, [&](std::size_t begin, std::size_t end) {
    block_jacobi(r_.data(), z_.data(), begin, end);
  });
  product(net, A, z_.data(), t_.data(), team, [&](std::size_t begin, std::size_t end) {
    for_entries(n, begin, end, [&](std::size_t k) { t_[k] = r_[k] - t_[k]; });
  });
  laplacian.solve3(t_.data(), team);  // in place: t <- P^-1 t
  for_node_parts(team, n, [&](std::size_t begin, std::size_t end) {
    for_entries(n, begin, end, [&](std::size_t k) { z_[k] += t_[k]; });
  });
  // The product reads z at every part's nodes until all parts are done, so
  // the new z goes to u, which then trades places with z.
  product(net, A, z_.data(), t_.data(), team, [&](std::size_t begin, std::size_t end) {
    for_entries(n, begin, end, [&](std::size_t k) { t_[k] = r_[k] - t_[k]; });
    block_jacobi(t_.data(), u_.data(), begin, end);
    for_entries(n, begin, end, [&](std::size_t k) { u_[k] += z_[k]; });
  });
  z_.swap(u_);
}

void ImplicitSystem::precondition(const ClothNetwork& net, const ImplicitMultigrid* multigrid,
                                  const ImplicitMultigrid::FineLevel& fine, StepThreads* team) {
  const std::size_t n = net.node_count();
  if (multigrid != nullptr) {
    interleaved_r_.resize(3 * n);
    interleaved_z_.resize(3 * n);
    to_interleaved(r_.data(), interleaved_r_.data(), n);
    multigrid->solve(fine, interleaved_r_, interleaved_z_);
    to_planar(interleaved_z_.data(), z_.data(), n);
    return;
  }
  for_node_parts(team, n, [&](std::size_t begin, std::size_t end) {
    for_entries(n, begin, end, [&](std::size_t k) { z_[k] = r_[k] / diag_[k]; });
  });
}

}  // namespace neurocloth
