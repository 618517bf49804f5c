#include "core/base/portable_trig.h"

#include <cmath>
#include <cstdint>

namespace neurocloth {
namespace {

// pi/2 as the sum of three doubles, the first two with their low bits zero so
// that n * kHalfPi1 and n * kHalfPi2 are exact for |n| < 2^20 (|x| < 1.6e6):
// x - n pi/2 then loses nothing to cancellation there.
constexpr double kHalfPi1 = 0x1.921fb544p+0;        // 33 significant bits
constexpr double kHalfPi2 = 0x1.0b4611a6p-34;       // the next 33
constexpr double kHalfPi3 = 0x1.3198a2e037073p-69;  // the rest, rounded
constexpr double kTwoOverPi = 0x1.45f306dc9c883p-1;

// sin r and cos r for |r| <= pi/4 by their Taylor series, Horner's rule; the
// first omitted term is below 1e-19 relative there. Coefficients: 1/k!.
double sin_kernel(double r) {
  const double z = r * r;
  double p = 1.0 / 355687428096000.0;  // 1/17!
  p = p * z - 1.0 / 1307674368000.0;   // 1/15!
  p = p * z + 1.0 / 6227020800.0;      // 1/13!
  p = p * z - 1.0 / 39916800.0;        // 1/11!
  p = p * z + 1.0 / 362880.0;          // 1/9!
  p = p * z - 1.0 / 5040.0;            // 1/7!
  p = p * z + 1.0 / 120.0;             // 1/5!
  p = p * z - 1.0 / 6.0;               // 1/3!
  return r + r * (z * p);
}

double cos_kernel(double r) {
  const double z = r * r;
  double p = -1.0 / 6402373705728000.0;  // 1/18!
  p = p * z + 1.0 / 20922789888000.0;    // 1/16!
  p = p * z - 1.0 / 87178291200.0;       // 1/14!
  p = p * z + 1.0 / 479001600.0;         // 1/12!
  p = p * z - 1.0 / 3628800.0;           // 1/10!
  p = p * z + 1.0 / 40320.0;             // 1/8!
  p = p * z - 1.0 / 720.0;               // 1/6!
  p = p * z + 1.0 / 24.0;                // 1/4!
  // 1 - z/2 + z^2 p, the large terms added last.
  return 1.0 - 0.5 * z + (z * z) * p;
}

// Past this the products n * kHalfPi1 are no longer exact; the argument is
// first taken modulo the double nearest 2 pi (exactly, by fmod): no longer
// accurate, still a deterministic angle.
constexpr double kExactReduction = 1e6;

// x = n pi/2 + r with |r| <= pi/4 (about), n's last two bits the quadrant.
double reduce(double x, std::int64_t& quadrant) {
  if (std::fabs(x) > kExactReduction) x = std::fmod(x, 6.283185307179586);
  const double n = std::nearbyint(x * kTwoOverPi);  // exact: rounds to an integer
  quadrant = static_cast<std::int64_t>(std::fmod(n, 4.0));
  if (quadrant < 0) quadrant += 4;
  return ((x - n * kHalfPi1) - n * kHalfPi2) - n * kHalfPi3;
}

// sin(q pi/2 + r): the quadrant's kernel and sign.
double at_quadrant(std::int64_t q, double r) {
  switch (q & 3) {
    case 0:
      return sin_kernel(r);
    case 1:
      return cos_kernel(r);
    case 2:
      return -sin_kernel(r);
    default:
      return -cos_kernel(r);
  }
}

// atan r for |r| <= tan(pi/12) = 0.268 by its Taylor series r - r^3/3 + ...:
// with r^2 <= 0.0718 the 15th term is below 1e-18 of the first.
double atan_kernel(double r) {
  // (-1)^k / (2k + 1) for k = 14 .. 1, each the double nearest it.
  static constexpr double kCoefficients[14] = {
      1.0 / 29,  -1.0 / 27, 1.0 / 25,  -1.0 / 23, 1.0 / 21, -1.0 / 19, 1.0 / 17,
      -1.0 / 15, 1.0 / 13,  -1.0 / 11, 1.0 / 9,   -1.0 / 7, 1.0 / 5,   -1.0 / 3};
  const double z = r * r;
  double p = 0;
  for (const double c : kCoefficients)
    p = p * z + c;
  return r + r * (z * p);
}

// pi, pi/2, pi/6 and 1/sqrt(3) as a double and the rest: the sums below add
// the rest last, so the constants cost no more than their final rounding.
constexpr double kPiHi = 3.141592653589793, kPiLo = 1.2246467991473532e-16;
constexpr double kHalfPiHi = 1.5707963267948966, kHalfPiLo = 6.123233995736766e-17;
constexpr double kSixthPiHi = 0.5235987755982989, kSixthPiLo = -5.360408832255455e-17;
constexpr double kInvSqrt3Hi = 0.5773502691896257, kInvSqrt3Lo = 3.3450280739356345e-17;
constexpr double kTanPiOver12 = 0.2679491924311227;

// atan a for 0 <= a <= 1: above tan(pi/12),
// atan a = pi/6 + atan((a - 1/sqrt3) / (1 + a/sqrt3)).
double atan_unit(double a) {
  if (a <= kTanPiOver12) return atan_kernel(a);
  const double t = ((a - kInvSqrt3Hi) - kInvSqrt3Lo) / (1.0 + a * kInvSqrt3Hi);
  return kSixthPiHi + (atan_kernel(t) + kSixthPiLo);
}

}  // namespace

double portable_atan2(double y, double x) {
  if (!std::isfinite(x) || !std::isfinite(y)) return std::atan2(y, x);  // not a step's case
  const double ax = std::fabs(x), ay = std::fabs(y);
  if (ax == 0 && ay == 0) return 0;
  // The angle from the nearer axis, in [0, pi/4], then unfolded by octant.
  double angle = ay <= ax ? atan_unit(ay / ax) : kHalfPiHi - (atan_unit(ax / ay) - kHalfPiLo);
  if (x < 0) angle = (kPiHi - angle) + kPiLo;
  return y < 0 ? -angle : angle;
}

double portable_sin(double x) {
  if (!std::isfinite(x)) return x - x;  // NaN, without the C library
  std::int64_t q = 0;
  const double r = reduce(x, q);
  return at_quadrant(q, r);
}

double portable_cos(double x) {  // cos x = sin(x + pi/2): one quadrant on
  if (!std::isfinite(x)) return x - x;
  std::int64_t q = 0;
  const double r = reduce(x, q);
  return at_quadrant(q + 1, r);
}

}  // namespace neurocloth
