#pragma once
// One spring's position-force neuron as the portable loops form it: the
// spring's length and direction from the difference of its ends, and the
// spring function of its elongation. Shared by the forces (cloth_network.cpp's
// propagate_chunk) and their adjoint (spring_adjoint.cpp), which must
// differentiate the arithmetic that ran. (The AVX-512 kernel's counterpart is
// Forces8::neurons, spring_chunk_avx512.h.) Internal to the core.
#include <algorithm>

#include "core/network/reciprocal_sqrt.h"
#include "core/network/spring_function.h"

namespace neurocloth {
namespace spring_chunks {

template <typename T>
struct PositionNeuron {
  T inv_len;             // 1/|d|; 1 where the spring has no direction
  T stretch;             // phi(|d| - L)
  bool has_direction;    // |d|^2 > min_len2: otherwise no force, never a division by zero
  bool stiffer = false;  // phi's steep part (stiffening): beyond the strain threshold
};

// d = p_b - p_a in T's arithmetic; threshold, extra: the spring function's
// strain threshold and stiffening factor - 1. Selects, no branches: the loops
// around it vectorise.
template <SpringFunctionKind K, typename T>
inline PositionNeuron<T> position_neuron(T dx, T dy, T dz, T rest, T threshold, T extra,
                                         T min_len2) {
  PositionNeuron<T> n;
  const T len2 = dx * dx + dy * dy + dz * dz;
  n.has_direction = len2 > min_len2;
  const T safe_len2 = n.has_direction ? len2 : T(1);
  n.inv_len = reciprocal_sqrt(safe_len2);
  const T len = safe_len2 * n.inv_len;
  n.stretch = len - rest;                               // spring function: linear ...
  if constexpr (K == SpringFunctionKind::stiffening) {  // ... or stiffer beyond the threshold
    const T over = n.stretch - threshold * rest;
    n.stiffer = over > T(0);
    n.stretch += extra * std::max(T(0), over);
  }
  return n;
}

}  // namespace spring_chunks
}  // namespace neurocloth
