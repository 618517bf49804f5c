#pragma once
// The walks over the spring layer's chunks, written once for both kernels
// (spring_kernel.h): which chunks a thread's part of the nodes evaluates, which
// add straight into the nodes and which go through accumulate_chunk. A kernel
// is a policy with the three ways a chunk's outputs can reach the nodes:
//   direct(first, count, a, b, fx, fy, fz)  adds +g at fx + k, -g at fx + b - a + k
//   row(first, count, a, b, lo, hi, fx, fy, fz) -> bool
//                                           a row's neighbours summed in place,
//                                           or false where it has no such path
//   store(first, count, a, b, fx, fy, fz)   stores g at fx + k
// (the adjoint's policy the same with the adjoint's six outputs). The portable
// kernel's policy is in cloth_network.cpp and spring_adjoint.cpp; the AVX-512
// one's in spring_forces_avx512.cpp and spring_adjoint_avx512.cpp, which
// include this header inside their region (avx512_region.h): templates only,
// each instantiated on its own file's policy. Internal to the core.
#include <array>
#include <cstdint>
#include <type_traits>

#include "core/network/cloth_state.h"
#include "core/network/spring_chunks.h"
#include "core/network/spring_layer.h"
#include "core/network/spring_precision.h"

namespace neurocloth {
namespace spring_chunks {

// Calls fn(Kernel<K, T, Damped>{L, s}): the kernel's policy for springs of
// L's kind (K), in `precision`'s arithmetic (T), with or without the damping
// term (Damped), each a compile-time constant of its own instantiation.
template <template <SpringFunctionKind, typename, bool> class Kernel, typename Fn>
void with_kernel(const SpringLayer& L, const ClothState& s, SpringPrecision precision, bool damped,
                 Fn&& fn) {
  const auto by_damping = [&](auto k, auto t) {
    constexpr SpringFunctionKind K = decltype(k)::value;
    using T = decltype(t);
    if (damped)
      fn(Kernel<K, T, true>{L, s});
    else
      fn(Kernel<K, T, false>{L, s});
  };
  const auto by_precision = [&](auto k) {
    if (precision == SpringPrecision::float32)
      by_damping(k, float{});
    else
      by_damping(k, double{});
  };
  if (L.function.kind == SpringFunctionKind::linear)
    by_precision(std::integral_constant<SpringFunctionKind, SpringFunctionKind::linear>{});
  else
    by_precision(std::integral_constant<SpringFunctionKind, SpringFunctionKind::stiffening>{});
}

// The spring layer's contributions to the acceleration neurons of nodes
// [lo, hi): every chunk that writes one of them, in the one chunk order. A
// chunk wholly inside adds its outputs directly (or through accumulate_chunk);
// a chunk that crosses lo or hi is evaluated by every part it touches, and
// each adds only to its own nodes (step_threads.h).
template <typename Kernel>
void propagate_part(const SpringLayer& L, const Kernel& kernel, NodeVectors& F, std::int32_t lo,
                    std::int32_t hi) {
  Chunk chunk;
  const std::array<double*, 3> dst{F.x.data(), F.y.data(), F.z.data()};
  for_each_chunk(
      L, [&](std::int32_t first, std::int32_t count, std::int32_t a, std::int32_t b, bool direct) {
        const bool a_inside = a >= lo && a + count <= hi;
        const bool b_inside = b >= lo && b + count <= hi;
        if (direct && a_inside && b_inside) {
          kernel.direct(first, count, a, b, F.x.data() + a, F.y.data() + a, F.z.data() + a);
          return;
        }
        const bool touches = (a < hi && a + count > lo) || (b < hi && b + count > lo);
        if (!touches) return;
        if (kernel.row(first, count, a, b, lo, hi, F.x.data() + a, F.y.data() + a, F.z.data() + a))
          return;
        kernel.store(first, count, a, b, chunk.fx, chunk.fy, chunk.fz);
        accumulate_chunk(count, a, b, chunk.fx, chunk.fy, chunk.fz, dst, lo, hi);
      });
}

// Every force neuron's output, in the springs' order (act.f*[first + k]).
template <typename Kernel, typename Activations>
void outputs_all(const SpringLayer& L, const Kernel& kernel, Activations& act) {
  for_each_chunk(L,
                 [&](std::int32_t first, std::int32_t count, std::int32_t a, std::int32_t b, bool) {
                   kernel.store(first, count, a, b, act.fx.data() + first, act.fy.data() + first,
                                act.fz.data() + first);
                 });
}

// What one chunk of the adjoint sends back to its springs' first nodes (n_i1):
// dE/dp_a and dE/dv_a. The second nodes receive the negatives (accumulate_chunk).
struct AdjointChunk {
  Chunk position, velocity;
};

// The adjoint's walk (spring_adjoint.h): every chunk, in the forces' order; its
// policy adds dE/dp and dE/dv into adj and the weights' gradients itself.
//   direct(first, count, a, b, adj), row(first, count, a, b, adj) -> bool,
//   store(first, count, a, b, adj, AdjointChunk&)
template <typename Kernel>
void adjoint_all(const SpringLayer& L, const Kernel& kernel, ClothState& adj) {
  AdjointChunk chunk;
  for_each_chunk(
      L, [&](std::int32_t first, std::int32_t count, std::int32_t a, std::int32_t b, bool direct) {
        if (direct) {
          kernel.direct(first, count, a, b, adj);
          return;
        }
        if (kernel.row(first, count, a, b, adj)) return;
        kernel.store(first, count, a, b, adj, chunk);
        accumulate_chunk(count, a, b, chunk.position.fx, chunk.position.fy, chunk.position.fz,
                         {adj.x.data(), adj.y.data(), adj.z.data()});
        accumulate_chunk(count, a, b, chunk.velocity.fx, chunk.velocity.fy, chunk.velocity.fz,
                         {adj.vx.data(), adj.vy.data(), adj.vz.data()});
      });
}

}  // namespace spring_chunks
}  // namespace neurocloth
