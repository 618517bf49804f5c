#pragma once
// A reference motion recorded from a running simulation, as the tests of
// learning need one: the nodes (every `stride`-th, network order = file order
// for the grids the tests use) after every `interval` s up to `seconds`, each
// coordinate with Gaussian noise of `noise` m when asked. Made by the
// simulation users run (Simulation::advance), not by the rollout a fit
// differentiates.
#include <gtest/gtest.h>

#include <cstdint>
#include <random>

#include "core/simulation/simulation.h"
#include "learn/motion/reference_motion.h"

namespace neurocloth::test {

inline ReferenceMotion recorded_reference(Simulation& sim, double seconds, double interval,
                                          std::size_t stride = 1, double noise = 0,
                                          unsigned seed = 1) {
  ReferenceMotion ref;
  ref.path = "recorded";
  std::mt19937 rng(seed);
  std::normal_distribution<double> gauss(0.0, 1.0);
  while (sim.time() < seconds - 1e-9) {
    EXPECT_EQ(sim.advance(interval), RunStatus::ok);
    ReferenceFrame f;
    f.time = sim.time();
    for (std::size_t i = 0; i < sim.state().size(); i += stride) {
      Vec3 p = sim.state().position(i);
      if (noise > 0) p += noise * Vec3(gauss(rng), gauss(rng), gauss(rng));
      f.nodes.push_back(static_cast<std::int32_t>(i));
      f.positions.push_back(p);
    }
    ref.frames.push_back(f);
  }
  return ref;
}

}  // namespace neurocloth::test
