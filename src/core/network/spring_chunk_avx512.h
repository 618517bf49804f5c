#pragma once
// The force neurons of one chunk (cloth_network.cpp's propagate_chunk) written
// for AVX-512 by hand, for one reason: 1/len. The portable loop seeds it from
// the exponent bits and needs four Newton steps (reciprocal_sqrt.h): 13 of the
// loop's 27 multiplies, and the multiply ports are what bounds it. The
// hardware estimate vrsqrt14pd is within 2^-14, so two Newton steps reach
// round-off: the 128 x 128 step is about a fifth cheaper.
//
// Deterministic for a build and a CPU: vrsqrt14pd is a table lookup, and the
// tail is the same instructions under a mask, so every spring sees the same
// operations whatever its place in a chunk or a thread's part. The bits
// differ from the portable loop's in the last place: runs through the two
// kernels are compared in spring_kernel_test.cpp, and each kernel's forces
// against the textbook formula in cloth_network_test.cpp (ClothNetworkKernel).
// Which kernel runs is chosen per evaluation (ForceContext::kernel,
// spring_kernel.h). Internal to the core.
//
// Included only inside an AVX-512 region (avx512_region.h), after the headers
// below: by spring_forces_avx512.cpp, and by spring_adjoint_avx512.cpp, whose
// adjoint starts from the same neurons (Forces8::neurons) and sends its
// outputs to the nodes the same ways (add_direct_avx512, add_row_avx512).
// Everything here is in an anonymous namespace on purpose: each region file
// gets its own copy with internal linkage, so no symbol compiled for AVX-512
// can stand in for a baseline one at link time.
//
// FloatForces8 is the same in float (SpringPrecision::float32). Both need
// AVX-512 F and VL (the float lanes are 256-bit registers under AVX-512
// masks): every AVX-512 CPU since Skylake-X has both.
#if !defined(NEUROCLOTH_AVX512_REGION)
#error "spring_chunk_avx512.h belongs inside an AVX-512 region on x86-64 (avx512_region.h)"
#endif
#include <immintrin.h>

#include <cstdint>
#include <type_traits>

#include "core/network/cloth_state.h"
#include "core/network/spring_layer.h"

namespace neurocloth {
namespace spring_chunks {
namespace {

inline __mmask8 first_lanes(std::int32_t n) {
  return n >= 8 ? __mmask8(0xFF) : __mmask8((1u << n) - 1u);
}

// Where a chunk's inputs are: the ends' positions and velocities from node a
// of its first spring (the b ends `offset` nodes on), its springs' weights.
struct ChunkInputs {
  const double* px;
  const double* py;
  const double* pz;
  const double* vx;
  const double* vy;
  const double* vz;
  const double* rest;
  const double* b1;
  const double* b2;
  std::int32_t offset;

  ChunkInputs(const SpringLayer& L, std::int32_t first, std::int32_t a, std::int32_t b,
              const ClothState& s)
      : px(s.x.data() + a),
        py(s.y.data() + a),
        pz(s.z.data() + a),
        vx(s.vx.data() + a),
        vy(s.vy.data() + a),
        vz(s.vz.data() + a),
        rest(L.rest_length.data() + first),
        b1(L.stiffness.data() + first),
        b2(L.damping.data() + first),
        offset(b - a) {}
};

// The force neurons' outputs of springs k..k+7 of a chunk whose b ends are
// `offset` nodes after its a ends (p* and v* point at node a of spring 0);
// lanes outside `m` are zero.
template <SpringFunctionKind K, bool Damped>
struct Forces8 : ChunkInputs {
  __m512d threshold, extra, min_len2;

  Forces8(const SpringLayer& L, std::int32_t first, std::int32_t /*count*/, std::int32_t a,
          std::int32_t b, const ClothState& s, double min_length)
      : ChunkInputs(L, first, a, b, s),
        threshold(_mm512_set1_pd(L.function.strain_threshold)),
        extra(_mm512_set1_pd(L.function.stiffening_factor - 1.0)),
        min_len2(_mm512_set1_pd(min_length * min_length)) {}

  // What the force neuron of each spring reads: the outputs of its
  // position-force and velocity-force neurons and the direction they act
  // along. The forces below and their adjoint (spring_adjoint.cpp) both start
  // here, so the adjoint differentiates the arithmetic that ran.
  struct Neurons {
    __m512d dx, dy, dz;     // p_b - p_a
    __m512d dvx, dvy, dvz;  // v_b - v_a (Damped)
    __m512d inv_len;        // 1/|d|; 1 where the spring has no direction
    __m512d stretch;        // phi(|d| - L): the position-force neuron
    __m512d speed;          // (v_b - v_a).d / |d|: the velocity-force neuron (Damped)
    __mmask8 has_direction;
    __mmask8 stiffer;  // phi's steep part (stiffening): beyond the strain threshold
  };

  Neurons neurons(std::int32_t k, __mmask8 m) const {
    const __m512d one = _mm512_set1_pd(1.0);
    const __m512d three_halves = _mm512_set1_pd(1.5);
    // Masked-off lanes load zeros (a zero-length spring: no direction, no force).
    const auto at = [m, k](const double* p) { return _mm512_maskz_loadu_pd(m, p + k); };
    Neurons n;
    n.dx = _mm512_sub_pd(at(px + offset), at(px));
    n.dy = _mm512_sub_pd(at(py + offset), at(py));
    n.dz = _mm512_sub_pd(at(pz + offset), at(pz));
    const __m512d len2 =
        _mm512_add_pd(_mm512_add_pd(_mm512_mul_pd(n.dx, n.dx), _mm512_mul_pd(n.dy, n.dy)),
                      _mm512_mul_pd(n.dz, n.dz));
    n.has_direction = _mm512_cmp_pd_mask(len2, min_len2, _CMP_GT_OQ);
    const __m512d safe_len2 = _mm512_mask_blend_pd(n.has_direction, one, len2);
    // Newton on 1/y^2 - x from the 2^-14 estimate: 2^-14 -> 3e-9 -> round-off.
    // (maskz forms here and below: GCC 12 warns about the unmasked forms'
    // undefined pass-through.)
    const __m512d half_x = _mm512_mul_pd(_mm512_set1_pd(0.5), safe_len2);
    __m512d y = _mm512_maskz_rsqrt14_pd(0xFF, safe_len2);
    y = _mm512_mul_pd(y, _mm512_sub_pd(three_halves, _mm512_mul_pd(half_x, _mm512_mul_pd(y, y))));
    n.inv_len =
        _mm512_mul_pd(y, _mm512_sub_pd(three_halves, _mm512_mul_pd(half_x, _mm512_mul_pd(y, y))));
    const __m512d len = _mm512_mul_pd(safe_len2, n.inv_len);
    const __m512d r = at(rest);
    n.stretch = _mm512_sub_pd(len, r);
    n.stiffer = 0;
    if constexpr (K == SpringFunctionKind::stiffening) {
      const __m512d over = _mm512_sub_pd(n.stretch, _mm512_mul_pd(threshold, r));
      n.stiffer = _mm512_cmp_pd_mask(over, _mm512_setzero_pd(), _CMP_GT_OQ);
      const __m512d beyond = _mm512_maskz_max_pd(0xFF, _mm512_setzero_pd(), over);
      n.stretch = _mm512_add_pd(n.stretch, _mm512_mul_pd(extra, beyond));
    }
    n.dvx = n.dvy = n.dvz = n.speed = _mm512_setzero_pd();
    if constexpr (Damped) {
      n.dvx = _mm512_sub_pd(at(vx + offset), at(vx));
      n.dvy = _mm512_sub_pd(at(vy + offset), at(vy));
      n.dvz = _mm512_sub_pd(at(vz + offset), at(vz));
      const __m512d rel =
          _mm512_add_pd(_mm512_add_pd(_mm512_mul_pd(n.dvx, n.dx), _mm512_mul_pd(n.dvy, n.dy)),
                        _mm512_mul_pd(n.dvz, n.dz));
      n.speed = _mm512_mul_pd(rel, n.inv_len);
    }
    return n;
  }

  // Force neuron: b1 * stretch + b2 * speed, along the unit direction; g is
  // the force on n_i1.
  void operator()(std::int32_t k, __mmask8 m, __m512d (&g)[3]) const {
    const auto at = [m, k](const double* p) { return _mm512_maskz_loadu_pd(m, p + k); };
    const Neurons n = neurons(k, m);
    __m512d magnitude = _mm512_mul_pd(at(b1), n.stretch);
    if constexpr (Damped) magnitude = _mm512_add_pd(magnitude, _mm512_mul_pd(at(b2), n.speed));
    const __m512d scale = _mm512_maskz_mul_pd(n.has_direction, magnitude, n.inv_len);
    g[0] = _mm512_mul_pd(scale, n.dx);
    g[1] = _mm512_mul_pd(scale, n.dy);
    g[2] = _mm512_mul_pd(scale, n.dz);
  }
};

// Eight doubles rounded to floats. (A named function, not a captureless
// lambda: the latter's function-pointer thunk is defined outside the region's
// target and would pass vectors the baseline way.)
inline __m256 narrow(__m512d v) {
  return _mm512_maskz_cvtpd_ps(0xFF, v);
}

// Forces8's arithmetic in float (SpringPrecision::float32): the differences
// of the ends' positions and velocities are taken in double and rounded,
// everything after is float, and the outputs are widened back to double for
// the node sums. Eight springs a step in 256-bit registers rather than 16 in
// 512-bit ones: the loads and the node sums are double either way, and 16
// lanes cost a join of two halves per input and a split per output, which
// measured slower than the double kernel (docs/network.md, "Float springs").
// vrsqrt14ps is within 2^-14, so one Newton step reaches float's round-off.
template <SpringFunctionKind K, bool Damped>
struct FloatForces8 : ChunkInputs {
  __m256 threshold, extra, min_len2;

  FloatForces8(const SpringLayer& L, std::int32_t first, std::int32_t /*count*/, std::int32_t a,
               std::int32_t b, const ClothState& s, double min_length)
      : ChunkInputs(L, first, a, b, s),
        threshold(_mm256_set1_ps(static_cast<float>(L.function.strain_threshold))),
        extra(_mm256_set1_ps(static_cast<float>(L.function.stiffening_factor - 1.0))),
        min_len2(_mm256_set1_ps(static_cast<float>(min_length * min_length))) {}

  void operator()(std::int32_t k, __mmask8 m, __m512d (&g)[3]) const {
    // Masked-off lanes load zeros (a zero-length spring: no direction, no force).
    const auto at = [m, k](const double* p) { return _mm512_maskz_loadu_pd(m, p + k); };
    const auto diff = [&](const double* p) { return narrow(_mm512_sub_pd(at(p + offset), at(p))); };
    const __m256 one = _mm256_set1_ps(1.0f);
    const __m256 dx = diff(px), dy = diff(py), dz = diff(pz);
    const __m256 len2 = _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(dx, dx), _mm256_mul_ps(dy, dy)),
                                      _mm256_mul_ps(dz, dz));
    const __mmask8 has_direction = _mm256_cmp_ps_mask(len2, min_len2, _CMP_GT_OQ);
    const __m256 safe_len2 = _mm256_mask_blend_ps(has_direction, one, len2);
    const __m256 y = _mm256_maskz_rsqrt14_ps(0xFF, safe_len2);
    const __m256 inv_len = _mm256_mul_ps(
        y, _mm256_sub_ps(
               _mm256_set1_ps(1.5f),
               _mm256_mul_ps(_mm256_mul_ps(_mm256_set1_ps(0.5f), safe_len2), _mm256_mul_ps(y, y))));
    const __m256 len = _mm256_mul_ps(safe_len2, inv_len);
    const __m256 r = narrow(at(rest));
    __m256 e = _mm256_sub_ps(len, r);
    if constexpr (K == SpringFunctionKind::stiffening) {
      const __m256 beyond = _mm256_maskz_max_ps(0xFF, _mm256_setzero_ps(),
                                                _mm256_sub_ps(e, _mm256_mul_ps(threshold, r)));
      e = _mm256_add_ps(e, _mm256_mul_ps(extra, beyond));
    }
    __m256 magnitude = _mm256_mul_ps(narrow(at(b1)), e);
    if constexpr (Damped) {
      const __m256 rel =
          _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(diff(vx), dx), _mm256_mul_ps(diff(vy), dy)),
                        _mm256_mul_ps(diff(vz), dz));
      magnitude =
          _mm256_add_ps(magnitude, _mm256_mul_ps(narrow(at(b2)), _mm256_mul_ps(rel, inv_len)));
    }
    const __m256 scale = _mm256_maskz_mul_ps(has_direction, magnitude, inv_len);
    g[0] = _mm512_maskz_cvtps_pd(0xFF, _mm256_mul_ps(scale, dx));
    g[1] = _mm512_maskz_cvtps_pd(0xFF, _mm256_mul_ps(scale, dy));
    g[2] = _mm512_maskz_cvtps_pd(0xFF, _mm256_mul_ps(scale, dz));
  }
};

// The force neurons of a chunk in `T`'s arithmetic.
// Damped: with the velocity-force neurons' term (false: the integrator damps
// the springs itself, SolverSettings::damping).
template <SpringFunctionKind K, typename T, bool Damped>
using Forces =
    std::conditional_t<std::is_same_v<T, float>, FloatForces8<K, Damped>, Forces8<K, Damped>>;

// How a chunk's outputs reach the nodes, for any kernel that gives N of them
// per spring, n_i1's share (n_i2 receives the negatives): `outputs(k, m, g)`
// sets g[0..N) for springs k..k+7 of the chunk, lanes outside m zero. The
// forces give three (spring_chunks.h's acceleration neurons), their adjoint six
// (dE/dp and dE/dv of n_i1, spring_adjoint.cpp). Always inlined: called
// out of line they read the kernel's pointers through a reference at every
// vector, and the 32 x 32 step measured 2.4% slower (step_benchmark).

// A direct chunk (its two node ranges disjoint): dst[c] + k receives +g[c],
// dst[c] + offset + k receives -g[c].
template <int N, typename Outputs>
[[gnu::always_inline]] inline void add_direct_avx512(std::int32_t count, std::int32_t offset,
                                                     const Outputs& outputs,
                                                     double* const (&dst)[N]) {
  for (std::int32_t k = 0; k < count; k += 8) {
    const __mmask8 m = first_lanes(count - k);
    __m512d g[N];
    outputs(k, m, g);
    const auto at = [m, k](const double* p) { return _mm512_maskz_loadu_pd(m, p + k); };
    for (int c = 0; c < N; ++c)
      _mm512_mask_storeu_pd(dst[c] + k, m, _mm512_add_pd(at(dst[c]), g[c]));
    for (int c = 0; c < N; ++c)
      _mm512_mask_storeu_pd(dst[c] + offset + k, m, _mm512_sub_pd(at(dst[c] + offset), g[c]));
  }
}

// The outputs stored at dst[c] + k, for accumulate_chunk.
template <int N, typename Outputs>
[[gnu::always_inline]] inline void store_avx512(std::int32_t count, const Outputs& outputs,
                                                double* const (&dst)[N]) {
  for (std::int32_t k = 0; k < count; k += 8) {
    const __mmask8 m = first_lanes(count - k);
    __m512d g[N];
    outputs(k, m, g);
    for (int c = 0; c < N; ++c)
      _mm512_mask_storeu_pd(dst[c] + k, m, g[c]);
  }
}

// The vector whose lane j is lane j - O of the sequence before, now: before's
// last O lanes, then now's first 8 - O. (Named, like narrow.)
template <int O>
inline __m512d shifted(__m512d now, __m512d before) {
  return _mm512_castsi512_pd(_mm512_maskz_alignr_epi64(0xFF, _mm512_castpd_si512(now),
                                                       _mm512_castpd_si512(before), 8 - O));
}

// A chunk of neighbours in a row (b = a + O, O < count): node a + j receives
// +g[j] - g[j - O]. The outputs never leave the registers: g[j - O] is the
// vector before shifted by O lanes. Each node's sum is the expression
// accumulate_chunk evaluates, so the bits are the same as that path's.
template <int O, int N, typename Outputs>
[[gnu::always_inline]] inline void add_row_avx512(std::int32_t count, const Outputs& outputs,
                                                  double* const (&dst)[N]) {
  static_assert(O > 0 && O < 8, "a shift within one vector");
  __m512d last[N];
  for (int c = 0; c < N; ++c)
    last[c] = _mm512_setzero_pd();
  for (std::int32_t k = 0; k < count + O; k += 8) {
    const __mmask8 springs = first_lanes(count - k > 0 ? count - k : 0);
    const __mmask8 nodes = first_lanes(count + O - k);
    __m512d g[N];
    for (int c = 0; c < N; ++c)
      g[c] = _mm512_setzero_pd();
    if (k < count) outputs(k, springs, g);
    for (int c = 0; c < N; ++c) {
      const __m512d before = shifted<O>(g[c], last[c]);
      const __m512d f = _mm512_maskz_loadu_pd(nodes, dst[c] + k);
      // Nodes with a spring starting at them: f + (g[j] - g[j-O]) (g[j-O] is
      // zero before the first); the last O nodes: f - g[j-O].
      const __m512d inner = _mm512_add_pd(f, _mm512_sub_pd(g[c], before));
      const __m512d outer = _mm512_sub_pd(f, before);
      _mm512_mask_storeu_pd(dst[c] + k, nodes, _mm512_mask_blend_pd(springs, outer, inner));
      last[c] = g[c];
    }
  }
}

}  // namespace
}  // namespace spring_chunks
}  // namespace neurocloth
