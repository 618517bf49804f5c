#pragma once
// The paper's spring layer (section 3). Per spring i:
//   position-force neuron  net = p_{n_i1} - p_{n_i2}   (weights 1, -1) -> spring function
//   velocity-force neuron  net = v_{n_i1} - v_{n_i2}   (weights 1, -1) -> damping function
//   force neuron           f_i = b1 * spring(.) + b2 * damping(.)
// b1 is the stiffness weight and b2 the damping weight; both are learnable.
//
// Layout: everything a force evaluation reads is a flat array indexed by spring,
// ordered so that consecutive springs usually have consecutive end nodes
// ("runs"). A run lets the evaluation read node arrays contiguously and write the
// force-neuron outputs contiguously: no gather, no scatter conflicts.
#include <cstdint>
#include <vector>

#include "core/network/cloth_topology.h"
#include "core/network/spring_function.h"

namespace neurocloth {

// Springs first..first+count-1 connect node_a+k to node_b+k, k = 0..count-1.
struct SpringRun {
  std::int32_t first;
  std::int32_t count;
  std::int32_t node_a;
  std::int32_t node_b;
};

// A run's piece evaluated in one go (spring_chunks.h): the same fields as a run,
// plus whether its two node ranges are disjoint, so its outputs can go straight
// into the acceleration neurons.
struct SpringChunk {
  std::int32_t first;
  std::int32_t count;
  std::int32_t node_a;
  std::int32_t node_b;
  bool direct;
};

struct SpringLayer {
  // Topology (fixed for a run).
  std::vector<std::int32_t> node_a;  // n_i1
  std::vector<std::int32_t> node_b;  // n_i2
  std::vector<SpringFamily> family;
  std::vector<SpringRun> runs;
  std::vector<SpringChunk> chunks;  // every run cut up, in the order they are evaluated
  // Learnable parameters (weights), one per spring.
  std::vector<double> rest_length;
  std::vector<double> stiffness;  // b1, N/m
  std::vector<double> damping;    // b2, N s/m (viscosity along the spring)

  SpringFunction function;

  std::size_t size() const { return node_a.size(); }
  // Rebuilds `runs` and `chunks` from node_a/node_b; call after changing the topology.
  void rebuild_runs();
};

}  // namespace neurocloth
