#include "core/network/spring_kernel.h"

#include <stdexcept>
#include <string>

#include "core/base/cpu_features.h"
#include "core/network/avx512_region.h"

namespace neurocloth {

bool avx512_kernel_available() {
#if defined(NEUROCLOTH_AVX512_REGION)
  return cpu_has_avx512();
#else
  return false;
#endif
}

std::string kernel_unavailable(SpringKernel kernel) {
  if (kernel != SpringKernel::avx512 || avx512_kernel_available()) return "";
#if defined(NEUROCLOTH_AVX512_REGION)
  if (cpu_reports_avx512())
    return std::string("the avx512 spring kernel is masked on this run (") +
           kDisableCpuFeaturesVariable + " names avx512); portable and auto run here";
  return "the avx512 spring kernel needs a CPU with AVX-512 F and VL, and this one lacks them; "
         "portable and auto run here";
#else
  return "the avx512 spring kernel exists only on x86-64; portable and auto run here";
#endif
}

SpringKernel resolved(SpringKernel kernel) {
  switch (kernel) {
    case SpringKernel::automatic:
      return avx512_kernel_available() ? SpringKernel::avx512 : SpringKernel::portable;
    case SpringKernel::portable:
      return kernel;
    case SpringKernel::avx512:
      if (!avx512_kernel_available()) throw std::invalid_argument(kernel_unavailable(kernel));
      return kernel;
  }
  throw std::invalid_argument("unknown spring kernel " + std::to_string(static_cast<int>(kernel)));
}

}  // namespace neurocloth
