// The spring layer's forces through the AVX-512 kernel (spring_kernel_avx512.h):
// spring_sweep.h's walks with the hand-written chunks of spring_chunk_avx512.h,
// compiled for AVX-512 F and VL in a baseline build (avx512_region.h).
#include "core/network/spring_kernel_avx512.h"

#include <immintrin.h>

#include <array>
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

// The AVX-512 kernel as spring_sweep.h's policy: a row's neighbours (node
// offset 1 or 2, inside the part) are summed in registers (add_row_avx512),
// with the same bits as accumulate_chunk's sums.
template <SpringFunctionKind K, typename T, bool Damped>
struct Avx512Chunks {
  const SpringLayer& L;
  const ClothState& s;
  void direct(std::int32_t first, std::int32_t count, std::int32_t a, std::int32_t b, double* fx,
              double* fy, double* fz) const {
    const Forces<K, T, Damped> forces(L, first, count, a, b, s, kMinSpringLength);
    double* const dst[3] = {fx, fy, fz};
    add_direct_avx512<3>(count, b - a, forces,
                         dst);  // acceleration neurons: +1 at n_i1, -1 at n_i2
  }
  bool row(std::int32_t first, std::int32_t count, std::int32_t a, std::int32_t b, std::int32_t lo,
           std::int32_t hi, double* fx, double* fy, double* fz) const {
    const std::int32_t o = b - a;
    if (!((o == 1 || o == 2) && o < count && a >= lo && b + count <= hi)) return false;
    const Forces<K, T, Damped> forces(L, first, count, a, b, s, kMinSpringLength);
    double* const dst[3] = {fx, fy, fz};
    if (o == 1)
      add_row_avx512<1, 3>(count, forces, dst);
    else
      add_row_avx512<2, 3>(count, forces, dst);
    return true;
  }
  void store(std::int32_t first, std::int32_t count, std::int32_t a, std::int32_t b, double* fx,
             double* fy, double* fz) const {
    const Forces<K, T, Damped> forces(L, first, count, a, b, s, kMinSpringLength);
    double* const dst[3] = {fx, fy, fz};
    store_avx512<3>(count, forces, dst);
  }
};

}  // namespace

void spring_forces_avx512(const ClothNetwork& net, const ClothState& s, SpringPrecision precision,
                          bool damped, NodeVectors& F, std::int32_t lo, std::int32_t hi) {
  with_kernel<Avx512Chunks>(net.springs, s, precision, damped, [&](const auto& chunks) {
    propagate_part(net.springs, chunks, F, lo, hi);
  });
}

void spring_outputs_avx512(const ClothNetwork& net, const ClothState& s, SpringPrecision precision,
                           SpringActivations& act) {
  with_kernel<Avx512Chunks>(net.springs, s, precision, true,
                            [&](const auto& chunks) { outputs_all(net.springs, chunks, act); });
}

}  // namespace neurocloth
NEUROCLOTH_AVX512_END
#else
namespace neurocloth {
// Not x86-64: the kernel does not exist, and resolved() never chooses it.
void spring_forces_avx512(const ClothNetwork&, const ClothState&, SpringPrecision, bool,
                          NodeVectors&, std::int32_t, std::int32_t) {
  throw std::logic_error("the avx512 spring kernel exists only on x86-64");
}
void spring_outputs_avx512(const ClothNetwork&, const ClothState&, SpringPrecision,
                           SpringActivations&) {
  throw std::logic_error("the avx512 spring kernel exists only on x86-64");
}
}  // namespace neurocloth
#endif
