#pragma once
// How the spring layer is walked in chunks: runs of springs whose end nodes are
// consecutive (spring_layer.h), cut so that a chunk's outputs stay in L1. Shared
// by the force evaluation (cloth_network.cpp) and its adjoint
// (spring_adjoint.cpp), which must visit the springs the same way. Internal to
// the core.
#include <algorithm>
#include <array>
#include <climits>
#include <cstdint>
#include <vector>

#include "core/network/spring_layer.h"

namespace neurocloth {
namespace spring_chunks {

// Force-neuron outputs live only as long as the acceleration neurons need them:
// a chunk this size stays in L1, so the outputs never travel to memory.
constexpr std::int32_t kChunk = 256;
struct Chunk {
  alignas(64) double fx[kChunk];
  alignas(64) double fy[kChunk];
  alignas(64) double fz[kChunk];
};

// Acceleration neurons: add each force neuron's output with weight +1 at n_i1
// and -1 at n_i2, in passes where no two writes of one loop hit the same node.
// Only nodes in [lo, hi) are written (one thread's part of the nodes,
// step_threads.h): a node receives the same sums in the same order whatever
// the clip, so a split step is bit-identical to a whole one.
inline void accumulate_chunk(std::int32_t count, std::int32_t a, std::int32_t b, const double* fx,
                             const double* fy, const double* fz, std::array<double*, 3> dst,
                             std::int32_t lo = 0, std::int32_t hi = INT32_MAX) {
  const double* const src[3] = {fx, fy, fz};
  const std::int32_t o = b - a;
  // Local indices [j0, j1) of the nodes base + j, clipped to [lo, hi) (node
  // indices and lo are >= 0, so nothing overflows).
  const auto first = [lo](std::int32_t j0, std::int32_t base) { return std::max(j0, lo - base); };
  const auto last = [hi](std::int32_t j1, std::int32_t base) { return std::min(j1, hi - base); };
  for (int c = 0; c < 3; ++c) {
    const double* f = src[c];
    double* to = dst[c] + a;
    if (o > 0 && o < count) {
      // Overlapping ends (a row's neighbours, o = 1 or 2): node a+j receives
      // +f[j] and -f[j-o], so one pass over the nodes does both ends.
      for (std::int32_t j = first(0, a), end = last(o, a); j < end; ++j)
        to[j] += f[j];
#pragma GCC ivdep
      for (std::int32_t j = first(o, a), end = last(count, a); j < end; ++j)
        to[j] += f[j] - f[j - o];
      for (std::int32_t j = first(count, a), end = last(count + o, a); j < end; ++j)
        to[j] -= f[j - o];
    } else {
#pragma GCC ivdep
      for (std::int32_t k = first(0, a), end = last(count, a); k < end; ++k)
        to[k] += f[k];
      double* to_b = dst[c] + b;
#pragma GCC ivdep
      for (std::int32_t k = first(0, b), end = last(count, b); k < end; ++k)
        to_b[k] -= f[k];
    }
  }
}

// Below this node offset a direct chunk would be too short to fill a vector.
constexpr std::int32_t kMinDirectOffset = 16;

// Chunks are evaluated band by band: every family's chunks that start among
// nodes [j kBand, (j+1) kBand) before any of the next band. Family by family,
// each sweep would stream the whole node state (72 bytes a node) through the
// cache once per family; a 128 x 128 cloth's state is larger than L2, so the
// band order keeps one band's state in L2 for all its families.
constexpr std::int32_t kBand = 1024;

// Every run cut into chunks, in evaluation order. A run whose ends are at
// least kMinDirectOffset nodes apart is cut into chunks no longer than that
// offset, so each chunk's two node ranges are disjoint (direct).
inline std::vector<SpringChunk> cut(const std::vector<SpringRun>& runs) {
  std::vector<SpringChunk> chunks;
  for (const SpringRun& r : runs) {
    const std::int32_t offset = r.node_b - r.node_a;
    const bool direct = offset >= kMinDirectOffset || -offset >= kMinDirectOffset;
    const std::int32_t size = direct ? std::min(kChunk, offset < 0 ? -offset : offset) : kChunk;
    for (std::int32_t k = 0; k < r.count; k += size)
      chunks.push_back(
          {r.first + k, std::min(size, r.count - k), r.node_a + k, r.node_b + k, direct});
  }
  // Stable: within a band the chunks keep the runs' order, so the order is a
  // function of the topology alone.
  std::stable_sort(chunks.begin(), chunks.end(), [](const SpringChunk& x, const SpringChunk& y) {
    return std::min(x.node_a, x.node_b) / kBand < std::min(y.node_a, y.node_b) / kBand;
  });
  return chunks;
}

// Calls fn(first, count, a, b, direct) for every chunk, in the layer's order.
// Always inlined: an AVX-512 region's fn (avx512_region.h) can then be inlined
// into the region's caller, which a baseline copy of this loop could not do.
template <typename Fn>
[[gnu::always_inline]] inline void for_each_chunk(const SpringLayer& L, Fn&& fn) {
  for (const SpringChunk& c : L.chunks)
    fn(c.first, c.count, c.node_a, c.node_b, c.direct);
}

}  // namespace spring_chunks
}  // namespace neurocloth
