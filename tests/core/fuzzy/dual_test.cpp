// The sparse dual numbers against dense ones (a derivative for every seed, the
// representation dual.h had before): every operation the engine uses, on
// operands with random values and random sets of seeds, gives the same value
// and the same derivative for every seed.
#include "core/fuzzy/dual.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace neurocloth::fuzzy {
namespace {

constexpr std::uint32_t kSeeds = 12;

// The dense reference: d has one entry per seed, zero where the value does not depend on it.
struct Dense {
  double v = 0;
  std::vector<double> d = std::vector<double>(kSeeds, 0.0);
};

Dense combine_duals(double v, double a, const Dense& x, double b, const Dense& y) {
  Dense r;
  r.v = v;
  for (std::uint32_t i = 0; i < kSeeds; ++i)
    r.d[i] = a * x.d[i] + b * y.d[i];
  return r;
}

// A random operand, as both: `count` distinct seeds with random derivatives.
std::pair<Dual, Dense> random_operand(std::mt19937& random, std::uint32_t count, double lo = -2,
                                      double hi = 2) {
  std::uniform_real_distribution<double> u(lo, hi);
  Dense dense;
  dense.v = u(random);
  std::vector<std::uint32_t> seeds(kSeeds);
  for (std::uint32_t i = 0; i < kSeeds; ++i)
    seeds[i] = i;
  std::shuffle(seeds.begin(), seeds.end(), random);
  seeds.resize(count);
  std::sort(seeds.begin(), seeds.end());
  Dual sparse(dense.v);
  sparse.d.reset(count);
  for (std::uint32_t s : seeds) {
    dense.d[s] = u(random);
    sparse.d.push_back(s, dense.d[s]);
  }
  return {sparse, dense};
}

void expect_same(const Dual& sparse, const Dense& dense, const char* what) {
  EXPECT_EQ(sparse.v, dense.v) << what;
  for (std::uint32_t i = 0; i < kSeeds; ++i)
    EXPECT_EQ(sparse.derivative(i), dense.d[i]) << what << " seed " << i;
  std::uint32_t previous = 0;
  for (const auto& e : sparse.d) {
    EXPECT_TRUE(&e == sparse.d.begin() || e.seed > previous) << what << ": seeds not ascending";
    previous = e.seed;
  }
}

TEST(Dual, EveryOperationMatchesDenseDerivatives) {
  std::mt19937 random(5);
  // Operand sizes across the inline capacity, and constants (no seeds).
  for (std::uint32_t na : {0u, 1u, 3u, SparseGradient::kInline, kSeeds})
    for (std::uint32_t nb : {0u, 2u, SparseGradient::kInline + 1, kSeeds}) {
      const auto [a, da] = random_operand(random, na);
      const auto [b, db] = random_operand(random, nb);
      const auto [p, dp] = random_operand(random, nb, 0.5, 3);  // positive, for sqrt, pow
      expect_same(a + b, combine_duals(da.v + db.v, 1, da, 1, db), "a + b");
      expect_same(a - b, combine_duals(da.v - db.v, 1, da, -1, db), "a - b");
      expect_same(-a, combine_duals(-da.v, -1, da, 0, db), "-a");
      expect_same(a * b, combine_duals(da.v * db.v, db.v, da, da.v, db), "a * b");
      expect_same(a / p, combine_duals(da.v / dp.v, 1 / dp.v, da, -da.v / (dp.v * dp.v), dp),
                  "a / p");
      Dual sum = a;
      sum += b;
      expect_same(sum, combine_duals(da.v + db.v, 1, da, 1, db), "a += b");
      const double s = std::sqrt(dp.v);
      expect_same(sqrt(p), combine_duals(s, 0.5 / s, dp, 0, da), "sqrt(p)");
      const double e = std::exp(da.v);
      expect_same(exp(a), combine_duals(e, e, da, 0, db), "exp(a)");
      const double r = std::pow(dp.v, db.v);
      expect_same(pow(p, b),
                  combine_duals(r, db.v * std::pow(dp.v, db.v - 1), dp, r * std::log(dp.v), db),
                  "pow(p, b)");
      expect_same(abs(a), da.v < 0 ? combine_duals(-da.v, -1, da, 0, db) : da, "abs(a)");
    }
}

TEST(Dual, SumOfManyTermsMatchesAddingThemOneByOne) {
  std::mt19937 random(8);
  DualSum sum;
  Dual one_by_one(0.0);
  for (int i = 0; i < 40; ++i) {
    const double c = 0.1 * i - 1.5;
    const Dual term = random_operand(random, std::uint32_t(i % 5)).first;
    sum.add(c, term);
    one_by_one += Dual(c) * term;
  }
  const Dual total = sum.total();
  EXPECT_EQ(total.v, one_by_one.v);
  ASSERT_EQ(total.d.size(), one_by_one.d.size());
  for (std::uint32_t i = 0; i < kSeeds; ++i)
    EXPECT_EQ(total.derivative(i), one_by_one.derivative(i)) << "seed " << i;
}

TEST(Dual, CopiesAndMovesKeepTheDerivatives) {
  std::mt19937 random(3);
  for (std::uint32_t n : {2u, kSeeds}) {  // inline and on the heap
    const auto [a, da] = random_operand(random, n);
    Dual copy = a;
    expect_same(copy, da, "copy");
    Dual assigned(1.0);
    assigned = a;
    assigned = *&assigned;  // self-assignment keeps it
    expect_same(assigned, da, "assigned");
    Dual moved = std::move(copy);
    expect_same(moved, da, "moved");
    Dual target = random_operand(random, kSeeds).first;
    target = std::move(moved);
    expect_same(target, da, "move-assigned");
  }
}

}  // namespace
}  // namespace neurocloth::fuzzy
