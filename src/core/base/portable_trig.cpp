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

}  // namespace

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
