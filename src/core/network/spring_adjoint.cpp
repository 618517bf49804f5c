#include "core/network/spring_adjoint.h"

#include <type_traits>

#include "core/network/position_neuron.h"
#include "core/network/spring_chunks.h"
#include "core/network/spring_kernel.h"
#include "core/network/spring_kernel_avx512.h"
#include "core/network/spring_sweep.h"

namespace neurocloth {
namespace {

using namespace spring_chunks;

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
// evaluation): add into adj at both ends at once (`out` unused); else store
// n_i1's share in `out` for accumulate_chunk (adj unused).
template <SpringFunctionKind K, bool Direct>
void adjoint_chunk(const SpringLayer& L, std::int32_t first, std::int32_t count, std::int32_t a,
                   std::int32_t b, const ClothState& s, const NodeVectors& lF, AdjointChunk* out,
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
      out->position.fx[k] = -gx;
      out->position.fy[k] = -gy;
      out->position.fz[k] = -gz;
      out->velocity.fx[k] = -c_rel * dx;
      out->velocity.fy[k] = -c_rel * dy;
      out->velocity.fz[k] = -c_rel * dz;
    }
    g1[k] += lm * phi;
    g2[k] += lm * rel * inv_len;
    gL[k] += lm * b1[k] * rest_slope;
  }
}

// The portable adjoint as spring_sweep.h's policy: no row path.
template <SpringFunctionKind K>
struct PortableAdjoint {
  const SpringLayer& L;
  const ClothState& s;
  const NodeVectors& lF;
  SpringGradients& g;
  void direct(std::int32_t first, std::int32_t count, std::int32_t a, std::int32_t b,
              ClothState& adj) const {
    adjoint_chunk<K, true>(L, first, count, a, b, s, lF, nullptr, adj, g);
  }
  bool row(std::int32_t, std::int32_t, std::int32_t, std::int32_t, ClothState&) const {
    return false;
  }
  void store(std::int32_t first, std::int32_t count, std::int32_t a, std::int32_t b,
             ClothState& adj, AdjointChunk& out) const {
    adjoint_chunk<K, false>(L, first, count, a, b, s, lF, &out, adj, g);
  }
};

}  // namespace

void spring_forces_adjoint(const ClothNetwork& net, const ClothState& s, const NodeVectors& lF,
                           ClothState& adj, SpringGradients& g, SpringKernel kernel) {
  if (resolved(kernel) == SpringKernel::avx512)  // throws before any work
    return spring_forces_adjoint_avx512(net, s, lF, adj, g);
  if (net.springs.function.kind == SpringFunctionKind::linear)
    adjoint_all(net.springs, PortableAdjoint<SpringFunctionKind::linear>{net.springs, s, lF, g},
                adj);
  else
    adjoint_all(net.springs, PortableAdjoint<SpringFunctionKind::stiffening>{net.springs, s, lF, g},
                adj);
}

}  // namespace neurocloth
