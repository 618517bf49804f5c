#include "core/network/reciprocal_sqrt.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace neurocloth {
namespace {

TEST(ReciprocalSqrt, WithinTwoUlpOverTheWholeRange) {
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> exponent(-300, 300), mantissa(1, 10);
  double worst = 0;
  for (int i = 0; i < 200000; ++i) {
    const double x = std::pow(10.0, exponent(rng)) * mantissa(rng);
    const long double truth = 1.0L / std::sqrt(static_cast<long double>(x));
    worst = std::max(worst, static_cast<double>(std::abs((reciprocal_sqrt(x) - truth) / truth)));
  }
  EXPECT_LT(worst, 2 * 2.2204460492503131e-16);
}

TEST(ReciprocalSqrt, ExactSquares) {
  for (double x : {1.0, 4.0, 0.25, 1e-20, 1e20, 2.5e-3})
    EXPECT_NEAR(reciprocal_sqrt(x) * std::sqrt(x), 1.0, 4e-16);
}

}  // namespace
}  // namespace neurocloth
