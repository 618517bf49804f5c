#pragma once
// 1/sqrt(x) for the spring loop without the divider. std::sqrt followed by a
// division costs two trips through the divide/sqrt unit (about 4 cycles per
// spring even with AVX-512); this costs a bit-level seed and four Newton steps
// of plain multiplies and adds, which vectorise on every port.
//
// Deterministic: only IEEE add, multiply and integer ops, so the same bits on
// every machine and at every vector width (FP contraction is off). Accurate to
// a few ulp (tested in reciprocal_sqrt_test.cpp), not correctly rounded.
// Only for normal, positive x; callers select around zero.
#include <cstdint>
#include <cstring>

namespace neurocloth {

inline double reciprocal_sqrt(double x) {
  std::uint64_t bits;
  std::memcpy(&bits, &x, sizeof bits);
  // Halving the exponent and negating it, in one integer subtraction: a seed
  // within 3.5% of 1/sqrt(x) (the constant is the double-precision analogue of
  // the well-known single-precision one).
  bits = 0x5FE6EB50C7B537A9ull - (bits >> 1);
  double y;
  std::memcpy(&y, &bits, sizeof y);
  const double half_x = 0.5 * x;
  // Newton on f(y) = 1/y^2 - x: relative error e -> 1.5 e^2 per step,
  // 3.5e-2 -> 1.8e-3 -> 5e-6 -> 4e-11 -> round-off.
  y = y * (1.5 - half_x * y * y);
  y = y * (1.5 - half_x * y * y);
  y = y * (1.5 - half_x * y * y);
  y = y * (1.5 - half_x * y * y);
  return y;
}

// The same in float (the float spring path's portable loop): the classic
// seed, and three steps reach float's round-off (5e-6 -> 4e-11).
inline float reciprocal_sqrt(float x) {
  std::uint32_t bits;
  std::memcpy(&bits, &x, sizeof bits);
  bits = 0x5F375A86u - (bits >> 1);
  float y;
  std::memcpy(&y, &bits, sizeof y);
  const float half_x = 0.5f * x;
  y = y * (1.5f - half_x * y * y);
  y = y * (1.5f - half_x * y * y);
  y = y * (1.5f - half_x * y * y);
  return y;
}

}  // namespace neurocloth
