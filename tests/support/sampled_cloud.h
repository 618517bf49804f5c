#pragma once
// A point cloud taken off a running simulation, as a depth camera or a scanner
// would give one: after every `interval` s up to `seconds`, `points` random
// points on the cloth's surface (a triangle chosen by its area, a uniform
// point in it: not the nodes), each coordinate with Gaussian noise of `noise`
// m, none from the triangles `hidden` says the camera does not see, and
// `outliers` points anywhere in a box around the cloth (a depth camera's
// flying pixels, the background). Made by
// the simulation users run (Simulation::advance), not by the rollout a fit
// differentiates.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <functional>
#include <random>
#include <vector>

#include "core/simulation/simulation.h"
#include "learn/motion/reference_motion.h"

namespace neurocloth::test {

struct CloudSampling {
  std::size_t points = 200;  // per frame, before the hidden ones are dropped
  double noise = 0;          // m, per coordinate
  // True for a triangle (index into the topology's) the camera does not see.
  std::function<bool(std::size_t)> hidden;
  std::size_t outliers = 0;  // per frame, uniform in the cloth's box grown by 0.2 m
  unsigned seed = 1;
};

inline ReferenceMotion sampled_cloud(Simulation& sim,
                                     const std::vector<std::array<std::int32_t, 3>>& triangles,
                                     double seconds, double interval, const CloudSampling& s) {
  ReferenceMotion ref;
  ref.path = "sampled cloud";
  ref.source = ReferenceMotion::Source::cloud;
  std::mt19937 rng(s.seed);
  std::normal_distribution<double> gauss(0.0, 1.0);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  while (sim.time() < seconds - 1e-9) {
    EXPECT_EQ(sim.advance(interval), RunStatus::ok);
    const ClothState& st = sim.state();
    std::vector<double> area(triangles.size());
    for (std::size_t t = 0; t < triangles.size(); ++t) {
      const Vec3 a = st.position(std::size_t(triangles[t][0]));
      const Vec3 b = st.position(std::size_t(triangles[t][1]));
      const Vec3 c = st.position(std::size_t(triangles[t][2]));
      area[t] = 0.5 * (b - a).cross(c - a).norm();
    }
    std::discrete_distribution<std::size_t> pick(area.begin(), area.end());
    ReferenceFrame f;
    f.time = sim.time();
    for (std::size_t k = 0; k < s.points; ++k) {
      const std::size_t t = pick(rng);
      // A uniform point of the triangle: fold the unit square's upper half.
      double u = unit(rng), v = unit(rng);
      if (u + v > 1) {
        u = 1 - u;
        v = 1 - v;
      }
      if (s.hidden && s.hidden(t)) continue;
      const Vec3 a = st.position(std::size_t(triangles[t][0]));
      const Vec3 b = st.position(std::size_t(triangles[t][1]));
      const Vec3 c = st.position(std::size_t(triangles[t][2]));
      Vec3 p = a + u * (b - a) + v * (c - a);
      if (s.noise > 0) p += s.noise * Vec3(gauss(rng), gauss(rng), gauss(rng));
      f.positions.push_back(p);
    }
    Vec3 lo = st.position(0), hi = lo;
    for (std::size_t i = 0; i < st.size(); ++i) {
      lo = lo.cwiseMin(st.position(i));
      hi = hi.cwiseMax(st.position(i));
    }
    for (std::size_t k = 0; k < s.outliers; ++k) {
      const Vec3 u(unit(rng), unit(rng), unit(rng));
      f.positions.push_back(lo - Vec3::Constant(0.2) +
                            u.cwiseProduct(hi - lo + Vec3::Constant(0.4)));
    }
    ref.frames.push_back(f);
  }
  return ref;
}

}  // namespace neurocloth::test
