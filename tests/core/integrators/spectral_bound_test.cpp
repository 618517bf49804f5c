// The spectral step bound: the top eigenvalue by Lanczos against a dense solve,
// the bound by hand on one spring, and what it lifts on the table drape.
#include "core/integrators/spectral_bound.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>

#include "core/integrators/stability.h"
#include "core/scene/scene.h"
#include "support/test_support.h"

namespace neurocloth {
namespace {

// M^-1/2 L M^-1/2 over the free nodes, dense: the truth for a small cloth.
// (Eigen's dense solver under AVX-512 trips GCC 12's false maybe-uninitialized
// warning: tests/CMakeLists.txt builds this file apart without it.)
double dense_top_eigenvalue(const ClothNetwork& net, const std::vector<double>& weight) {
  const int n = static_cast<int>(net.node_count());
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n, n);
  for (std::size_t s = 0; s < net.spring_count(); ++s) {
    const int i = net.springs.node_a[s], j = net.springs.node_b[s];
    const double w = std::abs(weight[s]);
    a(i, i) += w;
    a(j, j) += w;
    a(i, j) -= w;
    a(j, i) -= w;
  }
  std::vector<double> scale(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i)
    scale[i] = net.masses.free[i] != 0.0 ? std::sqrt(net.masses.inverse_mass[i]) : 0.0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      a(i, j) *= scale[i] * scale[j];
  // Eigen returns them in increasing order.
  const Eigen::VectorXd eigenvalues =
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(a, Eigen::EigenvaluesOnly).eigenvalues();
  return eigenvalues[n - 1];
}

TEST(SpectralBound, TheTopEigenvalueLiesJustAboveTheDenseSolvesOnAPinnedCloth) {
  // hanging: 20 x 20 nodes, two pinned, all three spring families.
  const ClothNetwork net = test::asset_scene("hanging").build_network();
  SpectralScratch scratch;
  for (bool damping : {false, true}) {
    std::vector<double> weight(net.spring_count());
    for (std::size_t s = 0; s < weight.size(); ++s)
      weight[s] = damping ? net.springs.damping[s] : net.springs.stiffness[s];
    const double truth = dense_top_eigenvalue(net, weight);
    const double estimate = laplacian_top_eigenvalue(net, weight, scratch);
    // Lanczos converged (398 free nodes, 114 steps): before rounding, the
    // estimate is the top eigenvalue over (1 - 0.02) to 1e-14 (measured
    // 3.6e-15); rounded up to 24 bits it lies within 2^-23 above that.
    const double ratio = estimate * 0.98 / truth;
    EXPECT_GE(ratio, 1.0 - 1e-14) << damping;
    EXPECT_LE(ratio, (1.0 + 1e-14) * (1.0 + 0x1p-23)) << damping;
    EXPECT_EQ(estimate, spectral_round_up(estimate)) << damping;
  }
}

TEST(SpectralBound, OneSpringByHand) {
  // spring_mass: one free node on one spring to a pin. M^-1 D is c / m itself
  // (Gershgorin's disc doubles it), which one Lanczos step finds exactly; the
  // springs' part keeps Gershgorin's disc, 2 k / m.
  Scene scene = test::asset_scene("spring_mass");
  scene.material.viscosity = 0.3;
  const ClothNetwork net = scene.build_network();
  const double k = 40, m = 0.1, c = 0.3, L = 2.0;
  const double lambda_k = 2 * k / m, lambda_d = spectral_round_up(c / m / 0.98);
  SpectralScratch scratch;
  EXPECT_NEAR(spectral_step_bound(net, L, scratch),
              L * L / (lambda_d + std::sqrt(lambda_d * lambda_d + L * L * lambda_k)), 1e-15);
  EXPECT_TRUE(std::isinf(spectral_step_bound(net, INFINITY, scratch)));
}

TEST(SpectralBound, TheEstimateIsRoundedUpTo24Bits) {
  EXPECT_EQ(spectral_round_up(1.0), 1.0);
  EXPECT_EQ(spectral_round_up(3.0 * 0x1p-40), 3.0 * 0x1p-40);  // already 24 bits
  EXPECT_EQ(spectral_round_up(1.0 + 0x1p-40), 1.0 + 0x1p-23);  // up, never down
  EXPECT_EQ(spectral_round_up(0x1p-1 + 0x1p-50), 0x1p-1 + 0x1p-24);
  EXPECT_EQ(spectral_round_up(0.0), 0.0);
  EXPECT_TRUE(std::isinf(spectral_round_up(INFINITY)));
  EXPECT_TRUE(std::isnan(spectral_round_up(NAN)));
}

TEST(SpectralBound, NothingFreeOrNoSpringsLeavesTheStepUnbounded) {
  SpectralScratch scratch;
  EXPECT_TRUE(std::isinf(
      spectral_step_bound(test::asset_scene("free_fall").build_network(), 2.0, scratch)));
  EXPECT_EQ(spectral_lanczos_steps(0), 0);
  EXPECT_EQ(spectral_lanczos_steps(5), 5);  // never more steps than nodes
  EXPECT_EQ(spectral_lanczos_steps(16384), 118);
}

// The table drape at 64 x 64: its light edge and corner nodes hold
// Gershgorin's bound far under the spectrum's. Measured 1.772 with the damping
// (which sets the step); the springs alone keep Gershgorin's bound.
TEST(SpectralBound, LiftsTheDrapesStep) {
  const ClothNetwork net = resized_grid(test::asset_scene("table_drape"), 64).build_network();
  SpectralScratch scratch;
  std::vector<double> k, d;
  const double with =
      spectral_step_bound(net, 2.0, scratch, true) / stable_step_bound(net, 2.0, k, d, true);
  const double without =
      spectral_step_bound(net, 2.0, scratch, false) / stable_step_bound(net, 2.0, k, d, false);
  EXPECT_NEAR(with, 1.772, 0.001);
  EXPECT_EQ(without, 1.0);
}

// A scene asks for a bound by name; a wrong name is refused naming the field.
TEST(SpectralBound, AScenesStepBoundIsReadAndAWrongOneRefused) {
  const std::string base = R"({"cloth": {"grid": {"rows": 4, "cols": 4, "spacing": 0.1}},
      "material": {"spring_constant": 100, "node_mass": 0.01, "viscosity": 0, "friction": 0},
      "solver": {"integrator": "network", "step_bound": )";
  EXPECT_EQ(parse_scene(base + "\"gershgorin\"}}", "s.json").solver.step_bound,
            StepBound::gershgorin);
  EXPECT_EQ(parse_scene(base + "\"spectral\"}}", "s.json").solver.step_bound, StepBound::spectral);
  try {
    parse_scene(base + "\"tight\"}}", "s.json");
    FAIL() << "accepted";
  } catch (const std::exception& e) {
    EXPECT_TRUE(test::contains(e.what(), "solver.step_bound")) << e.what();
    EXPECT_TRUE(test::contains(e.what(), "spectral, gershgorin")) << e.what();
  }
}

}  // namespace
}  // namespace neurocloth
