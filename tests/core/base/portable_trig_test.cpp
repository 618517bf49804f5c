// sin and cos with the same bits on every CPU (portable_trig.h): close to the
// C library's, and their bits stored, so that a run on another CPU (ctest's
// core_tests_on_a_baseline_cpu, emulated without FMA) checks them.
#include "core/base/portable_trig.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <utility>
#include <vector>

namespace neurocloth {
namespace {

// How many units in the last place a and b are apart.
double ulps(double a, double b) {
  const double scale = std::max(std::fabs(b), std::numeric_limits<double>::min());
  return std::fabs(a - b) / (std::nextafter(scale, 2 * scale + 1) - scale);
}

// The arguments the tests read: spread over [-1e6, 1e6] (a phase 2 pi f t for
// days of a run), many near zero, near multiples of pi/2, and the edges.
std::vector<double> arguments() {
  std::vector<double> xs = {0.0,
                            -0.0,
                            1e-300,
                            1e-8,
                            0.5,
                            0.785398,
                            1.5707963267948966,
                            3.141592653589793,
                            4.71238898038469,
                            6.283185307179586,
                            1e3,
                            1e6};
  std::mt19937_64 rng(20261207);
  std::uniform_real_distribution<double> near(-10.0, 10.0), far(-1e6, 1e6), unit(-1.0, 1.0);
  for (int i = 0; i < 20000; ++i)
    xs.push_back(near(rng));
  for (int i = 0; i < 20000; ++i)
    xs.push_back(far(rng));
  for (int k = -200; k <= 200; ++k)  // next to n pi/2, where the reduction cancels most
    xs.push_back(k * 1.5707963267948966 + 1e-9 * unit(rng));
  return xs;
}

// Within 2 ulp of the C library's value (itself within 1 ulp of the truth),
// or within 2 ulp of 1 where the value is tiny next to the argument's own
// rounding (near a zero of sin or cos, both are then rounding noise).
TEST(PortableTrig, CloseToTheCLibrary) {
  double worst = 0;
  for (const double x : arguments()) {
    for (const bool is_sin : {true, false}) {
      const double ours = is_sin ? portable_sin(x) : portable_cos(x);
      const double theirs = is_sin ? std::sin(x) : std::cos(x);
      const double d = std::fabs(theirs) < 1e-6 ? std::fabs(ours - theirs) / 2.220446049250313e-16
                                                : ulps(ours, theirs);
      worst = std::max(worst, d);
      ASSERT_LE(d, 2.0) << (is_sin ? "sin(" : "cos(") << x << ") = " << ours << ", not " << theirs;
    }
  }
  std::printf("worst: %.6g ulp\n", worst);
}

TEST(PortableTrig, NaNAndInfinityGiveNaN) {
  for (const double x :
       {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(),
        -std::numeric_limits<double>::infinity()}) {
    EXPECT_TRUE(std::isnan(portable_sin(x))) << x;
    EXPECT_TRUE(std::isnan(portable_cos(x))) << x;
  }
  EXPECT_EQ(portable_sin(0.0), 0.0);
  EXPECT_EQ(portable_cos(0.0), 1.0);
  // Far past where the reduction is exact: still a value in [-1, 1].
  for (const double x : {1e12, -3e15, 1e300}) {
    EXPECT_LE(std::fabs(portable_sin(x)), 1.0) << x;
    EXPECT_LE(std::fabs(portable_cos(x)), 1.0) << x;
  }
}

// The bits of every value above, hashed (FNV-1a over the doubles' bytes) and
// stored: the same on any CPU, which the C library's are not. Regenerate only
// for a change to the functions themselves.
TEST(PortableTrig, TheBitsAreTheStoredOnes) {
  std::uint64_t h = 1469598103934665603ull;
  for (const double x : arguments())
    for (const double v : {portable_sin(x), portable_cos(x)}) {
      unsigned char b[sizeof v];
      std::memcpy(b, &v, sizeof v);
      for (unsigned char c : b)
        h = (h ^ c) * 1099511628211ull;
    }
  EXPECT_EQ(h, 0x63d994d73b370d87ull) << std::hex << h;
}

// atan2 over every direction (a fold's angle: y and x of any size and sign)
// within 2 ulp of the C library's, exact on the axes and diagonals' signs.
std::vector<std::pair<double, double>> atan2_arguments() {
  std::vector<std::pair<double, double>> yx;
  // Made with exact or portable operations only (the bits test runs on other
  // CPUs too): the generator's integers, ldexp, and portable_sin and cos.
  std::mt19937_64 rng(44);
  for (int i = 0; i < 20000; ++i) {
    const double a = (static_cast<double>(rng() >> 11) / 9007199254740992.0 - 0.5) * 6.283;
    const double r = std::ldexp(1.0, static_cast<int>(rng() % 201) - 100);
    yx.emplace_back(r * portable_sin(a), r * portable_cos(a));
  }
  for (const double y : {0.0, 1.0, -1.0, 1e-300, 0.2679491924311227, 1e300})
    for (const double x : {0.0, 1.0, -1.0, 1e-300, 3.0, -1e300})
      yx.emplace_back(y, x);
  return yx;
}

TEST(PortableTrig, Atan2CloseToTheCLibrary) {
  double worst = 0;
  for (const auto& [y, x] : atan2_arguments()) {
    const double ours = portable_atan2(y, x), theirs = std::atan2(y, x);
    const double d = std::fabs(theirs) < 1e-300 ? std::fabs(ours - theirs) : ulps(ours, theirs);
    worst = std::max(worst, d);
    ASSERT_LE(d, 2.0) << "atan2(" << y << ", " << x << ") = " << ours << ", not " << theirs;
  }
  std::printf("worst: %.6g ulp\n", worst);
  EXPECT_EQ(portable_atan2(0.0, -1.0), 3.141592653589793);
  EXPECT_EQ(portable_atan2(1.0, 1.0), 0.7853981633974483);
  EXPECT_TRUE(std::isnan(portable_atan2(std::numeric_limits<double>::quiet_NaN(), 1.0)));
}

TEST(PortableTrig, Atan2BitsAreTheStoredOnes) {
  std::uint64_t h = 1469598103934665603ull;
  for (const auto& [y, x] : atan2_arguments()) {
    const double v = portable_atan2(y, x);
    unsigned char b[sizeof v];
    std::memcpy(b, &v, sizeof v);
    for (unsigned char c : b)
      h = (h ^ c) * 1099511628211ull;
  }
  EXPECT_EQ(h, 0x91641d43905f6a3bull) << std::hex << h;
}

}  // namespace
}  // namespace neurocloth
