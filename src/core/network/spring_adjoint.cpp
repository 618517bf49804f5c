#include "core/network/spring_adjoint.h"

#include <type_traits>

#include "core/network/position_neuron.h"
#include "core/network/spring_chunk_avx512.h"
#include "core/network/spring_chunks.h"
#include "core/network/spring_kernel.h"

namespace neurocloth {
namespace {

using namespace spring_chunks;

// What one chunk sends back to its springs' first nodes (n_i1): dE/dp_a and
// dE/dv_a. The second nodes receive the negatives (accumulate_chunk).
struct AdjointChunk {
  Chunk position, velocity;
};

// Per spring, with d = p_b - p_a, l = |d|, e = l - L (phi(e) for a stiffening
// spring), r = (v_b - v_a).d, m = b1 phi + b2 r / l and the force on n_i1
// f = (m / l) d, given lf = dE/df = adj_force[a] - adj_force[b]:
//   A = lf.d,  dE/dm = A / l,  dE/dl = -A m / l^2 - dE/dm b2 r / l^2 + dE/dm b1 phi'
//   dE/dd = (m / l) lf + (dE/dm b2 / l)(v_b - v_a) + (dE/dl / l) d
//   dE/d(v_b - v_a) = (dE/dm b2 / l) d
//   dE/db1 = dE/dm phi,  dE/db2 = dE/dm r / l,  dE/dL = dE/dm b1 dphi/dL
// where phi' = 1 and dphi/dL = -1; beyond a stiffening spring's threshold,
// phi' = 1 + extra and dphi/dL = -1 - extra (1 + threshold).
// Direct == true (the chunk's two node ranges are disjoint, as in the force
// evaluation): add into adj at both ends at once; else store n_i1's share in
// `out` for accumulate_chunk.
template <SpringFunctionKind K, bool Direct>
void adjoint_chunk(const SpringLayer& L, std::int32_t first, std::int32_t count, std::int32_t a,
                   std::int32_t b, const ClothState& s, const NodeVectors& lF, AdjointChunk& out,
                   ClothState& adj, SpringGradients& g) {
  double *px = adj.x.data() + a, *py = adj.y.data() + a, *pz = adj.z.data() + a;
  double *qx = adj.vx.data() + a, *qy = adj.vy.data() + a, *qz = adj.vz.data() + a;
  const std::int32_t o = b - a;
  const double *xa = s.x.data() + a, *ya = s.y.data() + a, *za = s.z.data() + a;
  const double *xb = s.x.data() + b, *yb = s.y.data() + b, *zb = s.z.data() + b;
  const double *vxa = s.vx.data() + a, *vya = s.vy.data() + a, *vza = s.vz.data() + a;
  const double *vxb = s.vx.data() + b, *vyb = s.vy.data() + b, *vzb = s.vz.data() + b;
  const double *lxa = lF.x.data() + a, *lya = lF.y.data() + a, *lza = lF.z.data() + a;
  const double *lxb = lF.x.data() + b, *lyb = lF.y.data() + b, *lzb = lF.z.data() + b;
  const double* rest = L.rest_length.data() + first;
  const double* b1 = L.stiffness.data() + first;
  const double* b2 = L.damping.data() + first;
  double* g1 = g.stiffness.data() + first;
  double* g2 = g.damping.data() + first;
  double* gL = g.rest_length.data() + first;
  const double threshold = L.function.strain_threshold;
  const double extra = L.function.stiffening_factor - 1.0;
  const double min_len2 = kMinSpringLength * kMinSpringLength;
#pragma GCC ivdep
  for (std::int32_t k = 0; k < count; ++k) {
    const double dx = xb[k] - xa[k], dy = yb[k] - ya[k], dz = zb[k] - za[k];
    const PositionNeuron<double> n =
        position_neuron<K>(dx, dy, dz, rest[k], threshold, extra, min_len2);
    const double mask = n.has_direction ? 1.0 : 0.0;
    const double inv_len = n.inv_len, phi = n.stretch;
    // phi' = dphi/dl and dphi/dL.
    const double slope = 1.0 + (n.stiffer ? extra : 0.0);
    const double rest_slope = -1.0 - (n.stiffer ? extra * (1.0 + threshold) : 0.0);
    const double dvx = vxb[k] - vxa[k], dvy = vyb[k] - vya[k], dvz = vzb[k] - vza[k];
    const double rel = dvx * dx + dvy * dy + dvz * dz;
    const double m = b1[k] * phi + b2[k] * rel * inv_len;
    const double scale = m * inv_len;
    const double lfx = lxa[k] - lxb[k], lfy = lya[k] - lyb[k], lfz = lza[k] - lzb[k];
    const double A = (lfx * dx + lfy * dy + lfz * dz) * mask;
    const double lm = A * inv_len;
    const double inv_len2 = inv_len * inv_len;
    const double l_len = -A * m * inv_len2 - lm * b2[k] * rel * inv_len2 + lm * b1[k] * slope;
    const double c_rel = lm * b2[k] * inv_len;
    const double c_d = l_len * inv_len;
    const double s_m = scale * mask;
    // dE/dp_a = -dE/dd, dE/dv_a = -dE/d(v_b - v_a); n_i2 gets the negatives.
    const double gx = s_m * lfx + c_rel * dvx + c_d * dx;
    const double gy = s_m * lfy + c_rel * dvy + c_d * dy;
    const double gz = s_m * lfz + c_rel * dvz + c_d * dz;
    if constexpr (Direct) {
      px[k] -= gx;
      py[k] -= gy;
      pz[k] -= gz;
      px[k + o] += gx;
      py[k + o] += gy;
      pz[k + o] += gz;
      qx[k] -= c_rel * dx;
      qy[k] -= c_rel * dy;
      qz[k] -= c_rel * dz;
      qx[k + o] += c_rel * dx;
      qy[k + o] += c_rel * dy;
      qz[k + o] += c_rel * dz;
    } else {
      out.position.fx[k] = -gx;
      out.position.fy[k] = -gy;
      out.position.fz[k] = -gz;
      out.velocity.fx[k] = -c_rel * dx;
      out.velocity.fy[k] = -c_rel * dy;
      out.velocity.fz[k] = -c_rel * dz;
    }
    g1[k] += lm * phi;
    g2[k] += lm * rel * inv_len;
    gL[k] += lm * b1[k] * rest_slope;
  }
}

#if defined(NEUROCLOTH_HAND_VECTORISED)
// The same for springs k..k+7 in AVX-512 (SpringKernel::avx512): the neurons
// as the forces' kernel forms them (Forces8::neurons), then the lines above,
// with explicit fused multiply-adds. With lf taken the other way round (lF_b -
// lF_a), every product is n_i1's share itself (the outputs add_direct_avx512 and
// add_row_avx512 expect: dE/dp_a, then dE/dv_a); the weights' gradients take
// the sign back.
template <SpringFunctionKind K>
struct Adjoint8 {
  Forces8<K, true> springs;
  const double *lx, *ly, *lz;                 // dE/dF at the chunk's first a node
  double *g1, *g2, *gL;                       // the chunk's weights' gradients
  __m512d stiffer_slope, stiffer_rest_slope;  // 1 + extra and 1 + extra (1 + threshold)

  Adjoint8(const SpringLayer& L, std::int32_t first, std::int32_t count, std::int32_t a,
           std::int32_t b, const ClothState& s, const NodeVectors& lF, SpringGradients& g)
      : springs(L, first, count, a, b, s, kMinSpringLength),
        lx(lF.x.data() + a),
        ly(lF.y.data() + a),
        lz(lF.z.data() + a),
        g1(g.stiffness.data() + first),
        g2(g.damping.data() + first),
        gL(g.rest_length.data() + first),
        stiffer_slope(_mm512_set1_pd(L.function.stiffening_factor)),
        stiffer_rest_slope(_mm512_set1_pd(1.0 + (L.function.stiffening_factor - 1.0) *
                                                    (1.0 + L.function.strain_threshold))) {}

  void operator()(std::int32_t k, __mmask8 m, __m512d (&out)[6]) const {
    const auto at = [m, k](const double* p) { return _mm512_maskz_loadu_pd(m, p + k); };
    const auto n = springs.neurons(k, m);
    const std::int32_t o = springs.offset;
    const __m512d b1 = at(springs.b1), b2 = at(springs.b2);
    const __m512d lfx = _mm512_sub_pd(at(lx + o), at(lx));  // -lf
    const __m512d lfy = _mm512_sub_pd(at(ly + o), at(ly));
    const __m512d lfz = _mm512_sub_pd(at(lz + o), at(lz));
    // -A, zero where the spring has no direction (no force to differentiate).
    const __m512d A = _mm512_maskz_fmadd_pd(n.has_direction, lfz, n.dz,
                                            _mm512_fmadd_pd(lfy, n.dy, _mm512_mul_pd(lfx, n.dx)));
    const __m512d lm = _mm512_mul_pd(A, n.inv_len);  // -dE/dm
    const __m512d b2_speed = _mm512_mul_pd(b2, n.speed);
    const __m512d magnitude = _mm512_add_pd(_mm512_mul_pd(b1, n.stretch), b2_speed);
    // dE/dL = dE/dm b1 dphi/dL = lm b1 (-dphi/dL).
    __m512d b1_lm = _mm512_mul_pd(b1, lm);
    __m512d b1_slope = b1;
    if constexpr (K == SpringFunctionKind::stiffening) {
      b1_slope = _mm512_mask_mul_pd(b1, n.stiffer, b1, stiffer_slope);
      b1_lm = _mm512_mask_mul_pd(b1_lm, n.stiffer, b1_lm, stiffer_rest_slope);
    }
    _mm512_mask_storeu_pd(g1 + k, m, _mm512_fnmadd_pd(lm, n.stretch, at(g1)));
    _mm512_mask_storeu_pd(g2 + k, m, _mm512_fnmadd_pd(lm, n.speed, at(g2)));
    _mm512_mask_storeu_pd(gL + k, m, _mm512_add_pd(at(gL), b1_lm));
    // -dE/dl / l = (-dE/dm / l)(b1 phi' - (m + b2 speed) / l).
    const __m512d lm_il = _mm512_mul_pd(lm, n.inv_len);
    const __m512d c_rel = _mm512_mul_pd(lm_il, b2);
    const __m512d c_d = _mm512_mul_pd(
        lm_il, _mm512_fnmadd_pd(n.inv_len, _mm512_add_pd(magnitude, b2_speed), b1_slope));
    const __m512d s_m = _mm512_maskz_mul_pd(n.has_direction, magnitude, n.inv_len);
    out[0] = _mm512_fmadd_pd(c_d, n.dx, _mm512_fmadd_pd(c_rel, n.dvx, _mm512_mul_pd(s_m, lfx)));
    out[1] = _mm512_fmadd_pd(c_d, n.dy, _mm512_fmadd_pd(c_rel, n.dvy, _mm512_mul_pd(s_m, lfy)));
    out[2] = _mm512_fmadd_pd(c_d, n.dz, _mm512_fmadd_pd(c_rel, n.dvz, _mm512_mul_pd(s_m, lfz)));
    out[3] = _mm512_mul_pd(c_rel, n.dx);
    out[4] = _mm512_mul_pd(c_rel, n.dy);
    out[5] = _mm512_mul_pd(c_rel, n.dz);
  }
};
#endif

template <SpringFunctionKind K, bool Hand>
void adjoint_all(const ClothNetwork& net, const ClothState& s, const NodeVectors& lF,
                 ClothState& adj, SpringGradients& g) {
  AdjointChunk chunk;
  for_each_chunk(net.springs, [&](std::int32_t first, std::int32_t count, std::int32_t a,
                                  std::int32_t b, bool direct) {
#if defined(NEUROCLOTH_HAND_VECTORISED)
    if constexpr (Hand) {
      const Adjoint8<K> adjoint(net.springs, first, count, a, b, s, lF, g);
      double* const at_a[6] = {adj.x.data() + a,  adj.y.data() + a,  adj.z.data() + a,
                               adj.vx.data() + a, adj.vy.data() + a, adj.vz.data() + a};
      const std::int32_t o = b - a;
      if (direct) return add_direct_avx512<6>(count, o, adjoint, at_a);
      // A row's neighbours: summed in registers, as the forces do.
      if (o == 1 && o < count) return add_row_avx512<1, 6>(count, adjoint, at_a);
      if (o == 2 && o < count) return add_row_avx512<2, 6>(count, adjoint, at_a);
      double* const shares[6] = {chunk.position.fx, chunk.position.fy, chunk.position.fz,
                                 chunk.velocity.fx, chunk.velocity.fy, chunk.velocity.fz};
      store_avx512<6>(count, adjoint, shares);
    }
#endif
    if constexpr (!Hand) {
      if (direct) {
        adjoint_chunk<K, true>(net.springs, first, count, a, b, s, lF, chunk, adj, g);
        return;
      }
      adjoint_chunk<K, false>(net.springs, first, count, a, b, s, lF, chunk, adj, g);
    }
    accumulate_chunk(count, a, b, chunk.position.fx, chunk.position.fy, chunk.position.fz,
                     {adj.x.data(), adj.y.data(), adj.z.data()});
    accumulate_chunk(count, a, b, chunk.velocity.fx, chunk.velocity.fy, chunk.velocity.fz,
                     {adj.vx.data(), adj.vy.data(), adj.vz.data()});
  });
}

}  // namespace

void spring_forces_adjoint(const ClothNetwork& net, const ClothState& s, const NodeVectors& lF,
                           ClothState& adj, SpringGradients& g, SpringKernel kernel) {
  [[maybe_unused]] const bool hand = resolved(kernel) == SpringKernel::avx512;
  const auto sweep = [&](auto kind) {
    constexpr SpringFunctionKind K = decltype(kind)::value;
    if constexpr (kHandVectorised) {
      if (hand) return adjoint_all<K, true>(net, s, lF, adj, g);
    }
    adjoint_all<K, false>(net, s, lF, adj, g);
  };
  if (net.springs.function.kind == SpringFunctionKind::linear)
    sweep(std::integral_constant<SpringFunctionKind, SpringFunctionKind::linear>{});
  else
    sweep(std::integral_constant<SpringFunctionKind, SpringFunctionKind::stiffening>{});
}

}  // namespace neurocloth
