#include "core/integrators/spring_damping.h"

#include <algorithm>
#include <cstdint>

#include "core/base/step_threads.h"
#include "core/network/spring_chunks.h"

namespace neurocloth {
namespace {

// Springs first + j (j in [lo, hi)) of a chunk: ends a + j and b + j.
// Independent: no two of them share a node (the caller knows), so the
// iterations may run as one vector.
template <bool Independent>
inline void damp_range(const double* damping, const double* w, const double* free, const double* px,
                       const double* py, const double* pz, double* vx, double* vy, double* vz,
                       std::int32_t first, std::int32_t a, std::int32_t b, std::int32_t lo,
                       std::int32_t hi, double h) {
  constexpr double kMin2 = kMinSpringLength * kMinSpringLength;
  const double* const d = damping + first;
  const double *const pxa = px + a, *const pya = py + a, *const pza = pz + a;
  const double *const pxb = px + b, *const pyb = py + b, *const pzb = pz + b;
  const double *const wa_ = w + a, *const wb_ = w + b, *const fa = free + a, *const fb = free + b;
  double *const vxa = vx + a, *const vya = vy + a, *const vza = vz + a;
  double *const vxb = vx + b, *const vyb = vy + b, *const vzb = vz + b;
  // By value: the loop then reads the pointers, not a closure, and vectorises.
  const auto one = [=](std::int32_t j) {
    const double dx = pxb[j] - pxa[j], dy = pyb[j] - pya[j], dz = pzb[j] - pza[j];
    const double len2 = dx * dx + dy * dy + dz * dz;
    const double wa = fa[j] * wa_[j], wb = fb[j] * wb_[j];
    // No direction: no damping, as in the network (a select, not a branch).
    const bool has_direction = len2 > kMin2;
    const double hd = has_direction ? h * d[j] : 0.0;
    const double safe_len2 = has_direction ? len2 : 1.0;
    // u = n . v_ab; the impulse s x_ab with s = -u h d / ((1 + h d (wa + wb)) len),
    // written with x_ab for n: s = -(x_ab . v_ab) hd / ((1 + hd W) len2).
    const double rel = (vxb[j] - vxa[j]) * dx + (vyb[j] - vya[j]) * dy + (vzb[j] - vza[j]) * dz;
    const double s = -rel * hd / ((1.0 + hd * (wa + wb)) * safe_len2);
    vxa[j] -= wa * s * dx;
    vya[j] -= wa * s * dy;
    vza[j] -= wa * s * dz;
    vxb[j] += wb * s * dx;
    vyb[j] += wb * s * dy;
    vzb[j] += wb * s * dz;
  };
  if constexpr (Independent) {
#pragma GCC ivdep
    for (std::int32_t j = lo; j < hi; ++j)
      one(j);
  } else {
    for (std::int32_t j = lo; j < hi; ++j)
      one(j);
  }
}

// A row's neighbours: the chunk's spring j joins nodes a + j and b + j, O
// apart, so spring j + O starts where spring j ends. Springs j with j / O even
// share no node, nor do those with j / O odd. Tile by tile (a whole number of
// 2 O springs), each half's impulses are computed in one contiguous vector
// pass, masked to the half (none reads what another writes), then added in a
// pass over the nodes, where a node receives at most one of them.
template <int O>
void damp_neighbours(const double* damping, const double* w, const double* free, const double* px,
                     const double* py, const double* pz, double* vx, double* vy, double* vz,
                     std::int32_t first, std::int32_t count, std::int32_t a, std::int32_t b,
                     double h) {
  constexpr double kMin2 = kMinSpringLength * kMinSpringLength;
  constexpr std::int32_t kTile = 2 * O * (32 / O);
  // The impulses s x_ab of a tile's springs at [O, O + n), zeros around.
  alignas(64) double ix[kTile + 2 * O] = {}, iy[kTile + 2 * O] = {}, iz[kTile + 2 * O] = {};
  const std::int32_t low = std::min(a, b);
  // A spring's low end gets sign w (s x_ab), its high end the opposite.
  const double sign = a < b ? -1.0 : 1.0;
  for (std::int32_t j0 = 0; j0 < count; j0 += kTile) {
    const std::int32_t n = std::min(kTile, count - j0);
    const double* const d = damping + first + j0;
    const double *const pxa = px + a + j0, *const pya = py + a + j0, *const pza = pz + a + j0;
    const double *const pxb = px + b + j0, *const pyb = py + b + j0, *const pzb = pz + b + j0;
    const double *const wa_ = w + a + j0, *const wb_ = w + b + j0;
    const double *const fa = free + a + j0, *const fb = free + b + j0;
    const double *const vxa = vx + a + j0, *const vya = vy + a + j0, *const vza = vz + a + j0;
    const double *const vxb = vx + b + j0, *const vyb = vy + b + j0, *const vzb = vz + b + j0;
    for (std::int32_t half = 0; half < 2; ++half) {
      for (std::int32_t k = 0; k < n; ++k) {
        const double dx = pxb[k] - pxa[k], dy = pyb[k] - pya[k], dz = pzb[k] - pza[k];
        const double len2 = dx * dx + dy * dy + dz * dz;
        const double W = fa[k] * wa_[k] + fb[k] * wb_[k];
        const bool on = len2 > kMin2 && (k / O) % 2 == half;
        const double hd = on ? h * d[k] : 0.0;
        const double safe_len2 = on ? len2 : 1.0;
        const double rel = (vxb[k] - vxa[k]) * dx + (vyb[k] - vya[k]) * dy + (vzb[k] - vza[k]) * dz;
        const double s = -rel * hd / ((1.0 + hd * W) * safe_len2);
        ix[O + k] = s * dx;
        iy[O + k] = s * dy;
        iz[O + k] = s * dz;
      }
      for (std::int32_t k = n; k < n + O; ++k)
        ix[O + k] = iy[O + k] = iz[O + k] = 0.0;
      // Node low + j0 + t: the low end of spring t, the high end of t - O.
      double *const ux = vx + low + j0, *const uy = vy + low + j0, *const uz = vz + low + j0;
      const double *const wl = w + low + j0, *const fl = free + low + j0;
#pragma GCC ivdep
      for (std::int32_t t = 0; t < n + O; ++t) {
        const double g = sign * fl[t] * wl[t];
        ux[t] += g * (ix[O + t] - ix[t]);
        uy[t] += g * (iy[O + t] - iy[t]);
        uz[t] += g * (iz[O + t] - iz[t]);
      }
    }
  }
}

// Springs [first, first + count) of one chunk, in the order above.
void damp_chunk(const ClothNetwork& net, const ClothState& p, double h, double* vx, double* vy,
                double* vz, std::int32_t first, std::int32_t count, std::int32_t a,
                std::int32_t b) {
  const double* const damping = net.springs.damping.data();
  const double* const w = net.masses.inverse_mass.data();
  const double* const free = net.masses.free.data();
  const double *const px = p.x.data(), *const py = p.y.data(), *const pz = p.z.data();
  const std::int32_t o = b > a ? b - a : a - b;
  switch (o) {
#define NEUROCLOTH_NEIGHBOURS(O) \
  case O:                        \
    return damp_neighbours<O>(damping, w, free, px, py, pz, vx, vy, vz, first, count, a, b, h);
    NEUROCLOTH_NEIGHBOURS(1)
    NEUROCLOTH_NEIGHBOURS(2)
    NEUROCLOTH_NEIGHBOURS(3)
    NEUROCLOTH_NEIGHBOURS(4)
    NEUROCLOTH_NEIGHBOURS(5)
    NEUROCLOTH_NEIGHBOURS(6)
    NEUROCLOTH_NEIGHBOURS(7)
#undef NEUROCLOTH_NEIGHBOURS
    default:
      break;
  }
  // Blocks of 8 in order: within one, no spring's end is another's.
  constexpr std::int32_t kBlock = 8;
  std::int32_t j = 0;
  for (; j + kBlock <= count; j += kBlock)
    damp_range<true>(damping, w, free, px, py, pz, vx, vy, vz, first, a, b, j, j + kBlock, h);
  damp_range<false>(damping, w, free, px, py, pz, vx, vy, vz, first, a, b, j, count, h);
}

}  // namespace

void damp_springs(const ClothNetwork& net, const ClothState& p, double h, double* vx, double* vy,
                  double* vz, StepThreads* team) {
  const SpringLayer& L = net.springs;
  const std::size_t n = net.node_count();
  if (n < kMinThreadedNodes) {  // one sweep in chunk order
    spring_chunks::for_each_chunk(
        L, [&](std::int32_t first, std::int32_t count, std::int32_t a, std::int32_t b, bool) {
          damp_chunk(net, p, h, vx, vy, vz, first, count, a, b);
        });
    return;
  }
  // Three groups, each in chunk order: the springs with both ends below the
  // split, those with both at or above it, then those across it. The first
  // two share no node, so two threads take them at once; the split is the
  // same whatever the team, so are the bits. In a chunk the groups are a
  // prefix, a suffix and the middle (its ends a + j, b + j grow with j).
  const auto split = static_cast<std::int32_t>(part_begin(n, 1, 2));
  const auto group = [&](int which) {
    spring_chunks::for_each_chunk(
        L, [&](std::int32_t first, std::int32_t count, std::int32_t a, std::int32_t b, bool) {
          const std::int32_t below = std::clamp(split - std::max(a, b), 0, count);
          const std::int32_t above = std::clamp(split - std::min(a, b), 0, count);
          const std::int32_t j0 = which == 0 ? 0 : which == 1 ? above : below;
          const std::int32_t j1 = which == 0 ? below : which == 1 ? count : above;
          if (j1 > j0) damp_chunk(net, p, h, vx, vy, vz, first + j0, j1 - j0, a + j0, b + j0);
        });
  };
  run_halves(team, group);
  group(2);
}

}  // namespace neurocloth
