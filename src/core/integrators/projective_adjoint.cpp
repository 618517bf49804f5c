// The adjoint of one `projective` step of a fit's run (projective.h): the
// step's iterations read backwards, exactly as they ran (a fixed number, with
// the omegas the forward pass took), not the implicit-function adjoint of a
// converged minimum — so the gradient is that of the step the cloth takes
// after its few iterations, and equals differences of the run.
//
// Forward, in displacements u = x - x0 (planar, every node's x, then y, then z):
//   y     = h v0 + free h^2 (w F_other + g)             (inertial_target.h)
//   base  = M y  (+ W_s y_p on a free node of each spring to a pin p)
//   x^0   = x^-1 = y
//   r^i   = base + sum_s A_s^T T_s(x^i, x0)  (pinned rows: y)
//   xb^i  = P^-1 r^i,  P = M + sum_s W_s A_s^T A_s
//   x^i+1 = omega_i (xb^i - x^i-1) + x^i-1
//   v'    = x^I / h,  p' = x0 + x^I  (pinned: v' = v0, p' = x0 + h v0)
// Backward, from lambda = dE/dx^I: lambda_xb = omega lambda, lambda_r = P^-1
// lambda_xb — P is symmetric, so the factor the forward pass made solves it
// (the near matrix of a one-off step by the same conjugate gradient) — and
// dE/dP from -lambda_r xb^T: for spring s, -(lambda_r,a - lambda_r,b).(xb_a -
// xb_b), for a node's mass, -lambda_r,i.xb_i; then the local step's targets
// T_s read backwards (spring_targets_adjoint) into dE/dx^i, dE/dx0 and the
// springs' weights.
#include <algorithm>
#include <cmath>

#include "core/integrators/projective.h"
#include "core/network/reciprocal_sqrt.h"

namespace neurocloth {

void ProjectiveIntegrator::step_adjoint(const ClothNetwork& net, const ForceInputs& inputs,
                                        const ForceContext& context, const ClothState& in, double h,
                                        std::size_t k, ClothState& adj,
                                        NodeVectors& adj_other_force, SpringGradients& g,
                                        double* adj_inverse_mass, double& rate_adjoint) {
  const SpringLayer& L = net.springs;
  const std::size_t n = n_, N = 3 * n;
  const std::vector<double>& free = net.masses.free;
  const double* const omegas = &omegas_[k * std::size_t(iterations_)];
  const double* const d_omegas = &d_omegas_[k * std::size_t(iterations_)];
  // The step's start again; its iterates from the tape, or the step again.
  refactor_if_needed(net, h);
  start_step(net, inputs, context, in, h);
  const std::size_t per_step = std::size_t(iterations_) * N;
  const bool taped = tape_iterates_ && iterate_tape_.size() >= (k + 1) * per_step;
  if (!taped) replay_ = omegas;
  const int I = taped ? iterations_ : iterate(net, in, h, nullptr, true);
  // x^j, j = -1 .. I (x^-1 = x^0 = y).
  auto x_of = [&](int j) -> const double* {
    if (j <= 0) return y_.data();
    const auto i = static_cast<std::size_t>(j - 1);
    return taped ? iterate_tape_.data() + k * per_step + i * N : kept_x_[i].data();
  };
  // The global answer xbar^i, from x^i+1 = omega (xbar^i - x^i-1) + x^i-1 (exactly
  // x^i+1 where omega is 1; to rounding elsewhere, whichever way the iterates came).
  auto xbar_of = [&](int i) -> const double* {
    const double omega = omegas[i];
    if (omega == 1.0) return x_of(i + 1);
    const double *next = x_of(i + 1), *prev = x_of(i - 1);
    xbar_.resize(N);
    for (std::size_t q = 0; q < N; ++q)
      xbar_[q] = (next[q] - prev[q]) / omega + prev[q];
    return xbar_.data();
  };
  // The step that measured the rate: dE/d(rate) enters through the norms of
  // two of its updates, |xb^i - x^i| (chebyshev.h).
  const bool measuring = k == measuring_step_ && rate_adjoint != 0.0;

  for (std::vector<double>& v : lam_x_)
    v.assign(N, 0.0);
  for (std::vector<double>* v : {&lam_y_, &lam_base_, &lam_p0_})
    v->assign(N, 0.0);
  lam_w_.assign(L.size(), 0.0);
  lam_m_.assign(n, 0.0);
  // dE/dx^j lives in lam_x_[(j + 1) % 3], for j = -1 .. I.
  auto lam_of = [&](int j) -> std::vector<double>& {
    return lam_x_[static_cast<std::size_t>((j + 1) % 3)];
  };
  const double* const out_p[3] = {adj.x.data(), adj.y.data(), adj.z.data()};
  const double* const out_v[3] = {adj.vx.data(), adj.vy.data(), adj.vz.data()};
  {
    std::vector<double>& top = lam_of(I);
    for (std::size_t c = 0; c < 3; ++c)
      for (std::size_t i = 0; i < n; ++i)
        top[c * n + i] = free[i] == 0.0 ? 0.0 : out_p[c][i] + out_v[c][i] / h;
  }
  for (int it = I - 1; it >= 0; --it) {
    const double omega = omegas[it];
    std::vector<double>& next = lam_of(it + 1);
    std::vector<double>& before = lam_of(it - 1);
    const double* const xb = xbar_of(it);
    const double* const x_before = x_of(it - 1);
    // x^i+1 = omega (xb - x^i-1) + x^i-1, and omega moves with the measured rate.
    double d_omega = 0;
    lam_r_.resize(N);
    for (std::size_t q = 0; q < N; ++q) {
      d_omega += next[q] * (xb[q] - x_before[q]);
      lam_r_[q] = omega * next[q];
      before[q] += (1.0 - omega) * next[q];
    }
    rate_adjoint += d_omega * d_omegas[it];
    if (measuring && (it == half_iteration_ || it == last_iteration_)) {
      const double* const x_it = x_of(it);
      double norm = 0;
      for (std::size_t q = 0; q < N; ++q)
        norm += (xb[q] - x_it[q]) * (xb[q] - x_it[q]);
      norm = std::sqrt(norm);
      const double c =
          rate_adjoint * (it == half_iteration_ ? d_rate_d_half_ : d_rate_d_last_) / norm;
      std::vector<double>& here = lam_of(it);
      for (std::size_t q = 0; q < N; ++q) {
        lam_r_[q] += c * (xb[q] - x_it[q]);
        here[q] -= c * (xb[q] - x_it[q]);
      }
    }
    solve(L, lam_r_.data(), nullptr);
    // dE/dP = -lambda_r xb^T on the matrix's weights.
    const double* const lr = lam_r_.data();
    for (std::size_t s = 0; s < L.size(); ++s) {
      const auto a = static_cast<std::size_t>(L.node_a[s]);
      const auto b = static_cast<std::size_t>(L.node_b[s]);
      const bool fa = free[a] != 0.0, fb = free[b] != 0.0;
      double sum = 0;
      for (std::size_t c = 0; c < 3; ++c) {
        const double la = fa ? lr[c * n + a] : 0.0, lb = fb ? lr[c * n + b] : 0.0;
        const double xa = fa ? xb[c * n + a] : 0.0, xbb = fb ? xb[c * n + b] : 0.0;
        sum += (la - lb) * (xa - xbb);
      }
      lam_w_[s] -= sum;
    }
    for (std::size_t i = 0; i < n; ++i) {
      if (free[i] == 0.0) continue;
      lam_m_[i] -= lr[i] * xb[i] + lr[n + i] * xb[n + i] + lr[2 * n + i] * xb[2 * n + i];
    }
    // A pinned row of r was y itself.
    for (const std::int32_t p : pinned_)
      for (std::size_t c = 0; c < 3; ++c) {
        const std::size_t q = c * n + static_cast<std::size_t>(p);
        lam_y_[q] += lam_r_[q];
        lam_r_[q] = 0.0;
      }
    for (std::size_t q = 0; q < N; ++q)
      lam_base_[q] += lam_r_[q];
    spring_targets_adjoint(L, x_of(it), in, h, lam_r_.data(), lam_of(it).data(), lam_p0_.data(), g);
    std::fill(next.begin(), next.end(), 0.0);  // next holds x^it-2 from here
  }
  {
    const std::vector<double>& l0 = lam_of(0);
    const std::vector<double>& lm = lam_of(-1);
    for (std::size_t q = 0; q < N; ++q)
      lam_y_[q] += l0[q] + lm[q];
  }
  // base = M y on free rows, + W_s y_p on the free end of a spring to a pin.
  for (std::size_t i = 0; i < n; ++i) {
    if (free[i] == 0.0) continue;
    for (std::size_t c = 0; c < 3; ++c) {
      const std::size_t q = c * n + i;
      lam_y_[q] += node_weight_[i] * lam_base_[q];
      lam_m_[i] += lam_base_[q] * y_[q];
    }
  }
  for (const std::int32_t s : pin_springs_) {
    auto a = static_cast<std::size_t>(L.node_a[static_cast<std::size_t>(s)]);
    auto b = static_cast<std::size_t>(L.node_b[static_cast<std::size_t>(s)]);
    if (free[a] == 0.0) std::swap(a, b);
    const double W = spring_weight_[static_cast<std::size_t>(s)];
    for (std::size_t c = 0; c < 3; ++c) {
      lam_y_[c * n + b] += W * lam_base_[c * n + a];
      lam_w_[static_cast<std::size_t>(s)] += lam_base_[c * n + a] * y_[c * n + b];
    }
  }
  // W_s = h^2 k_s (1 + extra) + h d_s (large_step_weights), m_i = 1 / w_i.
  const double extra =
      L.function.kind == SpringFunctionKind::stiffening ? L.function.stiffening_factor - 1.0 : 0.0;
  for (std::size_t s = 0; s < L.size(); ++s) {
    g.stiffness[s] += h * h * (1.0 + extra) * lam_w_[s];
    g.damping[s] += h * lam_w_[s];
  }
  const double* const w = net.masses.inverse_mass.data();
  // y = h v0 + free h^2 (w F_other + g).
  double* const lf[3] = {adj_other_force.x.data(), adj_other_force.y.data(),
                         adj_other_force.z.data()};
  const double* const fo[3] = {other_force_.x.data(), other_force_.y.data(), other_force_.z.data()};
  for (std::size_t i = 0; i < n; ++i) {
    double dw = 0;
    for (std::size_t c = 0; c < 3; ++c) {
      const double ly = lam_y_[c * n + i];
      lf[c][i] = free[i] * h * h * w[i] * ly;
      dw += fo[c][i] * ly;
    }
    if (adj_inverse_mass && free[i] != 0.0)
      adj_inverse_mass[i] += free[i] * h * h * dw - lam_m_[i] * node_weight_[i] * node_weight_[i];
  }
  // dE/d(the step's start): p' = x0 + x^I (free) or x0 + h v0 (pinned).
  double* const in_p[3] = {adj.x.data(), adj.y.data(), adj.z.data()};
  double* const in_v[3] = {adj.vx.data(), adj.vy.data(), adj.vz.data()};
  for (std::size_t c = 0; c < 3; ++c)
    for (std::size_t i = 0; i < n; ++i) {
      const double lp = in_p[c][i], lv = in_v[c][i];
      const double own = free[i] == 0.0 ? h * lp + lv : 0.0;
      in_p[c][i] = lp + lam_p0_[c * n + i];
      in_v[c][i] = own + h * lam_y_[c * n + i];
    }
}

// T_s, what spring s asks of u_ab at iterate x (spring_targets, projective.cpp):
//   T = k (r n - d0) + d (u - (u.n) n)  [+ k2 (clip ? L n - d0 : u)],
// k = h^2 k_s, d = h d_s, D = d0 + u, n = D / |D|, L = (1 + threshold) r;
// without a direction T = (k + d [+ k2]) u. It entered r as -T at a and +T at b.
void ProjectiveIntegrator::spring_targets_adjoint(const SpringLayer& L, const double* x,
                                                  const ClothState& in, double h, const double* lr,
                                                  double* lx, double* lp,
                                                  SpringGradients& g) const {
  const std::size_t n = n_;
  const bool stiffening = L.function.kind == SpringFunctionKind::stiffening;
  const double h2 = h * h, threshold = 1.0 + L.function.strain_threshold;
  const double extra = stiffening ? L.function.stiffening_factor - 1.0 : 0.0;
  spring_chunks::for_each_chunk(
      L, [&](std::int32_t first, std::int32_t count, std::int32_t a0, std::int32_t b0, bool) {
        for (std::int32_t j = 0; j < count; ++j) {
          const auto s = static_cast<std::size_t>(first + j);
          const auto a = static_cast<std::size_t>(a0 + j), b = static_cast<std::size_t>(b0 + j);
          double u[3], d0[3], D[3], lt[3];
          double len2 = 0;
          for (std::size_t c = 0; c < 3; ++c) {
            u[c] = x[c * n + b] - x[c * n + a];
            const double* p = c == 0 ? in.x.data() : c == 1 ? in.y.data() : in.z.data();
            d0[c] = p[b] - p[a];
            D[c] = d0[c] + u[c];
            len2 += D[c] * D[c];
            lt[c] = lr[c * n + b] - lr[c * n + a];
          }
          const double k = h2 * L.stiffness[s], d = h * L.damping[s], r = L.rest_length[s];
          const double lt_u = lt[0] * u[0] + lt[1] * u[1] + lt[2] * u[2];
          double gu[3], gd0[3];
          if (!(len2 > kMinSpringLength * kMinSpringLength)) {
            const double k_all = k + d + k * extra;
            for (std::size_t c = 0; c < 3; ++c) {
              gu[c] = k_all * lt[c];
              gd0[c] = 0.0;
            }
            g.stiffness[s] += h2 * (1.0 + extra) * lt_u;
            g.damping[s] += h * lt_u;
          } else {
            const double inv_len = reciprocal_sqrt(len2);
            double nv[3];
            for (std::size_t c = 0; c < 3; ++c)
              nv[c] = inv_len * D[c];
            const double along = u[0] * nv[0] + u[1] * nv[1] + u[2] * nv[2];
            const double lt_n = lt[0] * nv[0] + lt[1] * nv[1] + lt[2] * nv[2];
            double dk = 0, gn[3];
            for (std::size_t c = 0; c < 3; ++c) {
              dk += lt[c] * (r * nv[c] - d0[c]);
              gn[c] = k * r * lt[c] - d * (along * lt[c] + lt_n * u[c]);
              gu[c] = d * (lt[c] - lt_n * nv[c]);
              gd0[c] = -k * lt[c];
            }
            double dr = k * lt_n;
            g.damping[s] += h * (lt_u - along * lt_n);
            if (stiffening) {
              const double k2 = k * extra, limit = threshold * r;
              if (len2 * inv_len > limit) {
                for (std::size_t c = 0; c < 3; ++c) {
                  dk += extra * lt[c] * (limit * nv[c] - d0[c]);
                  gn[c] += k2 * limit * lt[c];
                  gd0[c] -= k2 * lt[c];
                }
                dr += k2 * threshold * lt_n;
              } else {
                dk += extra * lt_u;
                for (std::size_t c = 0; c < 3; ++c)
                  gu[c] += k2 * lt[c];
              }
            }
            g.stiffness[s] += h2 * dk;
            g.rest_length[s] += dr;
            // Through n = D / |D|: the part of dE/dn across n, over |D|.
            const double gn_n = gn[0] * nv[0] + gn[1] * nv[1] + gn[2] * nv[2];
            for (std::size_t c = 0; c < 3; ++c) {
              const double gD = inv_len * (gn[c] - gn_n * nv[c]);
              gu[c] += gD;
              gd0[c] += gD;
            }
          }
          for (std::size_t c = 0; c < 3; ++c) {
            lx[c * n + b] += gu[c];
            lx[c * n + a] -= gu[c];
            lp[c * n + b] += gd0[c];
            lp[c * n + a] -= gd0[c];
          }
        }
      });
}

}  // namespace neurocloth
