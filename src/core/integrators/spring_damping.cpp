#include "core/integrators/spring_damping.h"

#include <algorithm>
#include <cstdint>

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

}  // namespace

void damp_springs(const ClothNetwork& net, const ClothState& p, double h, double* vx, double* vy,
                  double* vz) {
  const SpringLayer& L = net.springs;
  const double* const damping = L.damping.data();
  const double* const w = net.masses.inverse_mass.data();
  const double* const free = net.masses.free.data();
  const double *const px = p.x.data(), *const py = p.y.data(), *const pz = p.z.data();
  constexpr std::int32_t kBlock = 8;
  spring_chunks::for_each_chunk(
      L, [&](std::int32_t first, std::int32_t count, std::int32_t a, std::int32_t b, bool) {
        const std::int32_t o = b > a ? b - a : a - b;
        if (o < kBlock) {
          // A row's neighbours: spring j + o starts where j ends. Springs j
          // with j / o even share no node, nor do those with j / o odd: each
          // half in turn, so no update waits for the one before it.
          for (std::int32_t half = 0; half < 2; ++half)
            for (std::int32_t base = half * o; base < count; base += 2 * o)
              damp_range<false>(damping, w, free, px, py, pz, vx, vy, vz, first, a, b, base,
                                std::min(base + o, count), h);
          return;
        }
        // Blocks of 8 in order: within one, no spring's end is another's.
        std::int32_t j = 0;
        for (; j + kBlock <= count; j += kBlock)
          damp_range<true>(damping, w, free, px, py, pz, vx, vy, vz, first, a, b, j, j + kBlock, h);
        damp_range<false>(damping, w, free, px, py, pz, vx, vy, vz, first, a, b, j, count, h);
      });
}

}  // namespace neurocloth
