#pragma once
// How far a run landed from a reference, in numbers that mean the same on any
// scene: positions relative to the cloth's size, energy relative to the work
// gravity does dropping the whole cloth by its size (docs/tradeoff.md).
#include <cmath>
#include <vector>

#include "tradeoff/sampled_run.h"

namespace neurocloth {

struct RunError {
  double position_max = 0;  // max over sample times and free nodes of |x - x_ref| / size
  double position_rms = 0;  // root mean square of the same over sample times and free nodes
  double energy = 0;        // max over sample times of |E - E_ref| / energy scale
  std::vector<double> position_max_by_sample;  // the max at each sample time
};

// What the errors are measured against, taken from the scene at its start.
struct ErrorScale {
  double size = 1;         // m: the cloth's bounding-box diagonal
  double energy = 1;       // J
  std::vector<char> free;  // per node: 1 when the node is free (pinned nodes are not compared)
};

// Node by node between two states (x0 y0 z0 ... of free.size() nodes), over
// the free ones: the largest distance and the sum of squares (m, m^2).
struct NodeDistances {
  double max = 0, sum2 = 0;
  long count = 0;
  double rms() const { return count ? std::sqrt(sum2 / static_cast<double>(count)) : 0.0; }
};
NodeDistances node_distances(const double* a, const double* b, const std::vector<char>& free);

// Bounding-box diagonal of the nodes.
double cloth_size(const ClothState& state);
// size from the initial state; energy = (mass of the free nodes) * |g| * size, or,
// without gravity, the larger of the initial kinetic and spring energy (1 J if both are 0).
ErrorScale error_scale(const Scene& scene);

// Both runs must have reached the same sample times (throws std::invalid_argument
// otherwise): a diverged run has no error to measure.
RunError compare_runs(const SampledRun& run, const SampledRun& reference, const ErrorScale& scale);

}  // namespace neurocloth
