// The spring layer's adjoint through the AVX-512 kernel (spring_kernel_avx512.h):
// spring_sweep.h's walk with Adjoint8's chunks, compiled for AVX-512 F and VL
// in a baseline build (avx512_region.h). The formulas are spring_adjoint.cpp's.
#include "core/network/spring_kernel_avx512.h"

#include <immintrin.h>

#include <cstdint>
#include <stdexcept>
#include <type_traits>

#include "core/network/avx512_region.h"
#include "core/network/cloth_state.h"
#include "core/network/spring_chunks.h"
#include "core/network/spring_layer.h"

#if defined(NEUROCLOTH_AVX512_REGION)
NEUROCLOTH_AVX512_BEGIN
#include "core/network/spring_chunk_avx512.h"
#include "core/network/spring_sweep.h"

namespace neurocloth {
namespace {
using namespace spring_chunks;

// The same for springs k..k+7 in AVX-512 (SpringKernel::avx512): the neurons
// as the forces' kernel forms them (Forces8::neurons), then spring_adjoint.cpp's adjoint_chunk,
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

// Adjoint8 as spring_sweep.h's policy: direct chunks and a row's neighbours
// add into adj in registers, the rest are stored for accumulate_chunk.
template <SpringFunctionKind K>
struct Avx512Adjoint {
  const SpringLayer& L;
  const ClothState& s;
  const NodeVectors& lF;
  SpringGradients& g;
  static void at_a(ClothState& adj, std::int32_t a, double* (&to)[6]) {
    double* const p[6] = {adj.x.data() + a,  adj.y.data() + a,  adj.z.data() + a,
                          adj.vx.data() + a, adj.vy.data() + a, adj.vz.data() + a};
    for (int c = 0; c < 6; ++c)
      to[c] = p[c];
  }
  void direct(std::int32_t first, std::int32_t count, std::int32_t a, std::int32_t b,
              ClothState& adj) const {
    const Adjoint8<K> adjoint(L, first, count, a, b, s, lF, g);
    double* to[6];
    at_a(adj, a, to);
    add_direct_avx512<6>(count, b - a, adjoint, to);
  }
  bool row(std::int32_t first, std::int32_t count, std::int32_t a, std::int32_t b,
           ClothState& adj) const {
    const std::int32_t o = b - a;
    if (!((o == 1 || o == 2) && o < count)) return false;
    const Adjoint8<K> adjoint(L, first, count, a, b, s, lF, g);
    double* to[6];
    at_a(adj, a, to);
    if (o == 1)
      add_row_avx512<1, 6>(count, adjoint, to);
    else
      add_row_avx512<2, 6>(count, adjoint, to);
    return true;
  }
  void store(std::int32_t first, std::int32_t count, std::int32_t a, std::int32_t b, ClothState&,
             AdjointChunk& out) const {
    const Adjoint8<K> adjoint(L, first, count, a, b, s, lF, g);
    double* const shares[6] = {out.position.fx, out.position.fy, out.position.fz,
                               out.velocity.fx, out.velocity.fy, out.velocity.fz};
    store_avx512<6>(count, adjoint, shares);
  }
};

}  // namespace

void spring_forces_adjoint_avx512(const ClothNetwork& net, const ClothState& s,
                                  const NodeVectors& lF, ClothState& adj, SpringGradients& g) {
  if (net.springs.function.kind == SpringFunctionKind::linear)
    adjoint_all(net.springs, Avx512Adjoint<SpringFunctionKind::linear>{net.springs, s, lF, g}, adj);
  else
    adjoint_all(net.springs, Avx512Adjoint<SpringFunctionKind::stiffening>{net.springs, s, lF, g},
                adj);
}

}  // namespace neurocloth
NEUROCLOTH_AVX512_END
#else
namespace neurocloth {
// Not x86-64: the kernel does not exist, and resolved() never chooses it.
void spring_forces_adjoint_avx512(const ClothNetwork&, const ClothState&, const NodeVectors&,
                                  ClothState&, SpringGradients&) {
  throw std::logic_error("the avx512 spring kernel exists only on x86-64");
}
}  // namespace neurocloth
#endif
