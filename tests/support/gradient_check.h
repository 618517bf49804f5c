#pragma once
// The learning tests' check that a fit's gradient is exact: central
// differences of FitProblem::loss against its adjoint, and a reference to
// take them against (any targets do for a gradient check).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "core/simulation/simulation.h"
#include "learn/fit/fit_problem.h"
#include "support/scene_builder.h"

namespace neurocloth::test {

// Frames at times that fall between steps, a scattered subset of nodes, and
// targets near the rest positions (any targets do for a gradient check).
inline ReferenceMotion scattered_reference(const Scene& scene, double seconds, int frames,
                                           unsigned seed = 7) {
  ReferenceMotion ref;
  ref.path = "synthetic";
  ref.source = ReferenceMotion::Source::markers;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> jitter(-0.02, 0.02);
  const int n = static_cast<int>(scene.topology.rest_positions.size());
  for (int f = 1; f <= frames; ++f) {
    ReferenceFrame fr;
    fr.time = seconds * (f - 0.37 * (f < frames)) / frames;
    for (int i = f % 3; i < n; i += 2) {
      fr.nodes.push_back(i);
      fr.positions.push_back(scene.topology.rest_positions[i] +
                             Vec3(jitter(rng), jitter(rng) - 0.05 * fr.time, jitter(rng)));
    }
    ref.frames.push_back(fr);
  }
  return ref;
}

// Checks components `which` of the gradient at theta0 (+ offset) against
// central differences of step eps.
inline void expect_exact_gradient(FitProblem& problem, const std::vector<Eigen::Index>& which,
                                  const Eigen::VectorXd& offset = Eigen::VectorXd(),
                                  double eps = 1e-6, double tolerance = 1e-6) {
  Eigen::VectorXd theta = problem.initial();
  if (offset.size() == theta.size()) theta += offset;
  Eigen::VectorXd g;
  const double E = problem.loss(theta, &g);
  ASSERT_TRUE(std::isfinite(E));
  ASSERT_GT(E, 0.0);
  double scale = 0;  // (a loop: Eigen's vectorised maxCoeff trips GCC 12's -Wmaybe-uninitialized)
  for (Eigen::Index i = 0; i < g.size(); ++i)
    scale = std::max(scale, std::abs(g[i]));
  ASSERT_GT(scale, 0.0);
  for (Eigen::Index i : which) {
    Eigen::VectorXd up = theta, down = theta;
    up[i] += eps;
    down[i] -= eps;
    const double fd = (problem.loss(up, nullptr) - problem.loss(down, nullptr)) / (2 * eps);
    // Relative to the component itself, with a floor of 1e-4 of the largest
    // component (a component near zero has no relative accuracy to speak of).
    const double denom = std::max(std::abs(fd), 1e-4 * scale);
    // Differences cannot resolve less than the loss's own rounding over 2 eps:
    // two ulps of E in the difference of two losses.
    const double resolution = 4 * std::numeric_limits<double>::epsilon() * std::abs(E) / (2 * eps);
    EXPECT_LE(std::abs(g[i] - fd), tolerance * denom + resolution)
        << "component " << i << ": adjoint " << g[i] << ", differences " << fd;
  }
}

inline std::vector<Eigen::Index> all_of(const FitProblem& p) {
  std::vector<Eigen::Index> v;
  for (Eigen::Index i = 0; i < static_cast<Eigen::Index>(p.size()); ++i)
    v.push_back(i);
  return v;
}

// The fit's run is the simulation users run: the loss at the scene's own
// weights of frames at T putting the first `nodes` nodes at the origin is
// exactly half the sum of their squared distances in the simulation.
inline void expect_fit_run_is_simulation(const Scene& scene, double T, int nodes) {
  ReferenceMotion ref;
  ReferenceFrame f;
  f.time = T;
  for (int i = 0; i < nodes; ++i) {
    f.nodes.push_back(i);
    f.positions.push_back(Vec3::Zero());
  }
  ref.frames.push_back(f);
  FitProblem p(scene, ref, FitSettings{});
  const double E = p.loss(p.initial(), nullptr);
  Simulation sim = scene.make_simulation();
  ASSERT_EQ(sim.advance(T), RunStatus::ok);
  double expected = 0;
  for (int i = 0; i < nodes; ++i)
    expected += 0.5 * sim.state().position(i).squaredNorm();
  EXPECT_EQ(E, expected);
}

// Control (issue 28): a cloth whose two pins follow a keyframed path, thrown
// with an initial velocity, run by `integrator` at `dt` (keys between steps).
inline SceneBuilder moving_pins(const std::string& integrator, double dt) {
  SceneBuilder b(5, 4, 0.05);
  b.pins(nlohmann::json::array({{0, 0}, {0, 3}})).material(80.0, 0.01, 0.08);
  b.solver(integrator, dt);
  b.module({{"type", "pin_motion"},
            {"keyframes",
             {{{"t", 0.0}, {"offset", {0, 0, 0}}},
              {{"t", 0.11}, {"offset", {0.02, 0.01, -0.01}}},
              {{"t", 0.17}, {"offset", {0.05, 0.03, 0.0}}},
              {{"t", 0.51}, {"offset", {0.04, -0.02, 0.03}}}}}});
  b.set("/cloth/initial_velocity", {0.1, 0.3, -0.2});
  return b;
}

}  // namespace neurocloth::test
