#pragma once
// Which code evaluates the spring layer's force neurons (ForceInputs::kernel,
// SolverSettings::kernel). Two kernels compute the same forces: the portable
// loop (cloth_network.cpp's propagate_chunk, with reciprocal_sqrt.h), compiled
// into every build, and the hand-written AVX-512 one (spring_chunk_avx512.h),
// compiled in only where the compiler targets AVX-512 F and VL. Their last
// bits differ (1/len from vrsqrt14pd and two Newton steps against the bit
// seed and four), so a test or a benchmark names the kernel it means and both
// run on an AVX-512 machine (docs/network.md, "Spring kernels").
#include <optional>
#include <string>

namespace neurocloth {

// automatic: AVX-512 where it is compiled in, otherwise portable (what every
// run uses unless told otherwise). portable: always available. avx512: only
// where compiled in; asked for elsewhere it is refused, never replaced.
enum class SpringKernel { automatic, portable, avx512 };

// Whether this build of the core holds the AVX-512 kernel (decided by the
// flags the core was compiled with, not the caller's).
bool avx512_kernel_compiled();

// Why `kernel` cannot run in this build, or "" when it can.
std::string kernel_unavailable(SpringKernel kernel);

// The kernel that runs when `kernel` is asked for: automatic resolved, the
// others as they are. Throws std::invalid_argument when it cannot run here.
SpringKernel resolved(SpringKernel kernel);

// The names a command line takes: "auto", "portable", "avx512".
inline const char* to_string(SpringKernel k) {
  switch (k) {
    case SpringKernel::portable:
      return "portable";
    case SpringKernel::avx512:
      return "avx512";
    case SpringKernel::automatic:
      break;
  }
  return "auto";
}

inline std::optional<SpringKernel> parse_kernel(const std::string& name) {
  for (const SpringKernel k :
       {SpringKernel::automatic, SpringKernel::portable, SpringKernel::avx512})
    if (name == to_string(k)) return k;
  return std::nullopt;
}

inline constexpr const char* kKernelNames = "auto, portable, avx512";

}  // namespace neurocloth
