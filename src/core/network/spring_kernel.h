#pragma once
// Which code evaluates the spring layer's force neurons (ForceContext::kernel,
// SolverSettings::kernel). Two kernels compute the same forces: the portable
// loop (cloth_network.cpp's propagate_chunk, with reciprocal_sqrt.h), and the
// hand-written AVX-512 one (spring_chunk_avx512.h). Both are compiled into
// every x86-64 build, the AVX-512 one for its own target (avx512_region.h);
// which may run is decided at run time by the CPU (cpu_features.h). Their last
// bits differ (1/len from vrsqrt14pd and two Newton steps against the bit
// seed and four), so a test or a benchmark names the kernel it means and both
// run on an AVX-512 machine (docs/network.md, "Spring kernels").
#include <optional>
#include <string>

namespace neurocloth {

// automatic: AVX-512 where the CPU has it, otherwise portable (what every run
// uses unless told otherwise). portable: always available. avx512: only on a
// CPU with AVX-512 F and VL; asked for elsewhere it is refused, never replaced.
enum class SpringKernel { automatic, portable, avx512 };

// Whether this process can run the AVX-512 kernel: an x86-64 build on a CPU
// with AVX-512 F and VL, not masked by NEUROCLOTH_DISABLE_CPU_FEATURES.
bool avx512_kernel_available();

// Why `kernel` cannot run in this process, or "" when it can.
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
