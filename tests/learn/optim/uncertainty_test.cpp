#include "learn/optim/uncertainty.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <cmath>
#include <random>

namespace neurocloth {
namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;

// E(x) = 1/2 |A x - b|^2: a linear least-squares problem whose covariance at
// the optimum is known exactly, s^2 (A^T A)^-1 with s^2 = |r|^2 / (N - P).
struct LeastSquares {
  MatrixXd A;
  VectorXd b;

  double operator()(const VectorXd& x, VectorXd* g) const {
    const VectorXd r = A * x - b;
    if (g) *g = A.transpose() * r;
    return 0.5 * r.squaredNorm();
  }
  VectorXd optimum() const { return A.colPivHouseholderQr().solve(b); }
};

// b = A truth + noise, truth = 1, 2, 3...; column j of A scaled by scale[j]
// (0: the unknown does not enter the residuals) before b is made.
LeastSquares random_problem(int N, int P, double noise, unsigned seed,
                            std::vector<double> scale = {}) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal;
  LeastSquares ls{MatrixXd(N, P), VectorXd(N)};
  for (int i = 0; i < N; ++i)
    for (int j = 0; j < P; ++j)
      ls.A(i, j) = normal(rng) * (scale.empty() ? 1.0 : scale[std::size_t(j)]);
  const VectorXd truth = VectorXd::LinSpaced(P, 1, P);
  for (int i = 0; i < N; ++i)
    ls.b[i] = ls.A.row(i).dot(truth) + noise * normal(rng);
  return ls;
}

std::vector<UncertainParameter> linear_names(int P) {
  std::vector<UncertainParameter> out;
  for (int j = 0; j < P; ++j)
    out.push_back({"p" + std::to_string(j), false});
  return out;
}

TEST(Uncertainty, MatchesTheKnownCovarianceOfALinearLeastSquaresProblem) {
  const LeastSquares ls = random_problem(60, 3, 0.1, 7);
  const VectorXd x = ls.optimum();
  const double E = ls(x, nullptr);
  const UncertaintyReport r = estimate_uncertainty(ls, x, E, 60, linear_names(3));
  ASSERT_TRUE(r.computed) << r.skipped;
  EXPECT_EQ(r.gradient_calls, 6);
  const double s2 = 2 * E / (60 - 3);
  EXPECT_DOUBLE_EQ(r.residual_variance, s2);
  const MatrixXd expected = s2 * (ls.A.transpose() * ls.A).inverse();
  EXPECT_LT((r.covariance - expected).norm(), 1e-8 * expected.norm());
  for (int j = 0; j < 3; ++j) {
    const ParameterUncertainty& p = r.parameters[std::size_t(j)];
    EXPECT_DOUBLE_EQ(p.value, x[j]);
    EXPECT_NEAR(p.sd, std::sqrt(expected(j, j)), 1e-8);
    EXPECT_NEAR(p.relative_sd, p.sd / std::abs(x[j]), 1e-12);
    EXPECT_EQ(p.verdict, Determination::determined) << p.name;
  }
  EXPECT_EQ(r.flat_directions, 0);
}

TEST(Uncertainty, ALogSpaceParameterReportsItsRelativeSpread) {
  // theta = log(value): the sd of theta is the relative sd of the value.
  const LeastSquares ls = random_problem(40, 2, 0.05, 3);
  const VectorXd x = ls.optimum();
  const UncertaintyReport r =
      estimate_uncertainty(ls, x, ls(x, nullptr), 40, {{"k", true}, {"m", false}});
  ASSERT_TRUE(r.computed);
  const double sd_theta = std::sqrt(r.covariance(0, 0));
  EXPECT_DOUBLE_EQ(r.parameters[0].value, std::exp(x[0]));
  EXPECT_DOUBLE_EQ(r.parameters[0].relative_sd, sd_theta);
  EXPECT_DOUBLE_EQ(r.parameters[0].sd, std::exp(x[0]) * sd_theta);
}

TEST(Uncertainty, AParameterTheLossIgnoresIsNotDetermined) {
  // The third unknown appears nowhere in the residuals.
  const LeastSquares ls = random_problem(30, 3, 0.1, 11, {1, 1, 0});
  VectorXd x = VectorXd::Zero(3);
  x.head(2) = ls.A.leftCols(2).colPivHouseholderQr().solve(ls.b);
  x[2] = 0.7;
  const UncertaintyReport r = estimate_uncertainty(ls, x, ls(x, nullptr), 30, linear_names(3));
  ASSERT_TRUE(r.computed);
  EXPECT_EQ(r.flat_directions, 1);
  EXPECT_EQ(r.parameters[0].verdict, Determination::determined);
  EXPECT_EQ(r.parameters[1].verdict, Determination::determined);
  EXPECT_EQ(r.parameters[2].verdict, Determination::not_determined);
  EXPECT_STREQ(to_string(r.parameters[2].verdict), "not determined");
}

TEST(Uncertainty, TwoParametersSeenOnlyTogetherAreBothNotDetermined) {
  // Only p0 + p1 matters (a mass and a stiffness that only their ratio shows).
  LeastSquares ls = random_problem(30, 2, 0.1, 5);
  ls.A.col(1) = ls.A.col(0);
  const VectorXd x{{1.5, 0.5}};
  const UncertaintyReport r = estimate_uncertainty(ls, x, ls(x, nullptr), 30, linear_names(2));
  ASSERT_TRUE(r.computed);
  EXPECT_EQ(r.flat_directions, 1);
  EXPECT_EQ(r.parameters[0].verdict, Determination::not_determined);
  EXPECT_EQ(r.parameters[1].verdict, Determination::not_determined);
}

TEST(Uncertainty, NoisyDataLeavesAParameterPoorlyDetermined) {
  // A weak column: its parameter's sd is far above 10% of its value.
  const LeastSquares ls = random_problem(20, 2, 1.0, 9, {1, 0.01});
  const VectorXd x = ls.optimum();
  const UncertaintyReport r = estimate_uncertainty(ls, x, ls(x, nullptr), 20, linear_names(2));
  ASSERT_TRUE(r.computed);
  EXPECT_GT(r.parameters[1].relative_sd, 0.1);
  EXPECT_EQ(r.parameters[1].verdict, Determination::poorly_determined);
}

TEST(Uncertainty, IsSkippedAboveTheCapAndWithTooLittleData) {
  int calls = 0;
  const Objective f = [&](const VectorXd& x, VectorXd* g) {
    ++calls;
    if (g) *g = x;
    return 0.5 * x.squaredNorm();
  };
  const UncertaintyReport big =
      estimate_uncertainty(f, VectorXd::Ones(40), 20, 1000, linear_names(40));
  EXPECT_FALSE(big.computed);
  EXPECT_NE(big.skipped.find("40 unknowns"), std::string::npos) << big.skipped;
  EXPECT_EQ(calls, 0);
  ASSERT_EQ(big.parameters.size(), 40u);
  EXPECT_DOUBLE_EQ(big.parameters[0].value, 1);
  EXPECT_TRUE(std::isnan(big.parameters[0].sd));

  const UncertaintyReport few = estimate_uncertainty(f, VectorXd::Ones(3), 1, 3, linear_names(3));
  EXPECT_FALSE(few.computed);
  EXPECT_NE(few.skipped.find("no more data"), std::string::npos) << few.skipped;
}

TEST(Uncertainty, ANonFiniteGradientBesideTheOptimumSkipsIt) {
  const Objective f = [](const VectorXd& x, VectorXd* g) {
    if (g) *g = x;
    if (x[0] > 1) g->setConstant(std::nan(""));
    return 0.5 * x.squaredNorm();
  };
  const UncertaintyReport r = estimate_uncertainty(f, VectorXd::Ones(2), 1, 100, linear_names(2));
  EXPECT_FALSE(r.computed);
  EXPECT_NE(r.skipped.find("p0"), std::string::npos) << r.skipped;
}

}  // namespace
}  // namespace neurocloth
