#include "learn/fit/rollout_tape.h"

#include <cstdint>

#if defined(__SSE2__)
#include <immintrin.h>
#endif

namespace neurocloth {
namespace {

// A copy of `from` in `to` that goes to memory without first reading each of
// `to`'s cache lines (non-temporal stores) where the CPU has them. A tape is
// written once and read far later, so plain stores would fetch every line
// only to overwrite it (twice the memory traffic) and push the step's own
// state out of the cache: on the 32 x 32 cloth's 500 steps the tape's writing
// took about a fifth of the gradient, and this halves it (learn_benchmark).
// finish_tape() orders them before anything that follows.
#if defined(__AVX512F__)
constexpr std::size_t kStreamed = 8;  // doubles per store
void stream(double* to, const double* from) {
  _mm512_stream_pd(to, _mm512_loadu_pd(from));
}
#elif defined(__AVX__)
constexpr std::size_t kStreamed = 4;
void stream(double* to, const double* from) {
  _mm256_stream_pd(to, _mm256_loadu_pd(from));
}
#elif defined(__SSE2__)
constexpr std::size_t kStreamed = 2;
void stream(double* to, const double* from) {
  _mm_stream_pd(to, _mm_loadu_pd(from));
}
#else
constexpr std::size_t kStreamed = 0;  // plain copies
void stream(double*, const double*) {}
#endif

}  // namespace

void write_to_tape(const ClothState& from, ClothState& to) {
  for (auto field : {&ClothState::x, &ClothState::y, &ClothState::z, &ClothState::vx,
                     &ClothState::vy, &ClothState::vz}) {
    const double* src = (from.*field).data();
    double* dst = (to.*field).data();
    const std::size_t n = (from.*field).size();
    std::size_t i = 0;
    if constexpr (kStreamed > 0) {
      // A streaming store needs an address aligned to its width.
      for (; i < n && reinterpret_cast<std::uintptr_t>(dst + i) % (kStreamed * sizeof(double)); ++i)
        dst[i] = src[i];
      for (; i + kStreamed <= n; i += kStreamed)
        stream(dst + i, src + i);
    }
    for (; i < n; ++i)
      dst[i] = src[i];
  }
}

void finish_tape() {
#if defined(__SSE2__)
  _mm_sfence();
#endif
}

}  // namespace neurocloth
