#include "core/network/spring_kernel.h"

#include <stdexcept>
#include <string>

#include "core/network/spring_chunk_avx512.h"

namespace neurocloth {

bool avx512_kernel_compiled() {
  return spring_chunks::kHandVectorised;
}

std::string kernel_unavailable(SpringKernel kernel) {
  if (kernel != SpringKernel::avx512 || avx512_kernel_compiled()) return "";
  return "the avx512 spring kernel is not compiled into this build (it needs a compiler "
         "targeting AVX-512 F and VL, e.g. NEUROCLOTH_NATIVE on such a CPU); portable and auto "
         "run here";
}

SpringKernel resolved(SpringKernel kernel) {
  switch (kernel) {
    case SpringKernel::automatic:
      return avx512_kernel_compiled() ? SpringKernel::avx512 : SpringKernel::portable;
    case SpringKernel::portable:
      return kernel;
    case SpringKernel::avx512:
      if (!avx512_kernel_compiled()) throw std::invalid_argument(kernel_unavailable(kernel));
      return kernel;
  }
  throw std::invalid_argument("unknown spring kernel " + std::to_string(static_cast<int>(kernel)));
}

}  // namespace neurocloth
