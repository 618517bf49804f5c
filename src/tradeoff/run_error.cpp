#include "tradeoff/run_error.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace neurocloth {

NodeDistances node_distances(const double* a, const double* b, const std::vector<char>& free) {
  NodeDistances d;
  for (std::size_t i = 0; i < free.size(); ++i) {
    if (!free[i]) continue;
    const double dx = a[3 * i] - b[3 * i], dy = a[3 * i + 1] - b[3 * i + 1],
                 dz = a[3 * i + 2] - b[3 * i + 2];
    const double d2 = dx * dx + dy * dy + dz * dz;
    d.max = std::max(d.max, std::sqrt(d2));
    d.sum2 += d2;
    ++d.count;
  }
  return d;
}

double cloth_size(const ClothState& s) {
  if (s.size() == 0) return 0;
  Vec3 lo = s.position(0), hi = lo;
  for (std::size_t i = 1; i < s.size(); ++i) {
    lo = lo.cwiseMin(s.position(i));
    hi = hi.cwiseMax(s.position(i));
  }
  return (hi - lo).norm();
}

ErrorScale error_scale(const Scene& scene) {
  const ClothNetwork net = scene.build_network();
  const ClothState start = scene.initial_state();
  ErrorScale scale;
  scale.size = cloth_size(start);
  // A single node (or a cloth of coincident nodes) has no size: errors are then in metres.
  if (!(scale.size > 0)) scale.size = 1;
  double free_mass = 0;
  scale.free.resize(net.node_count());
  for (std::size_t i = 0; i < net.node_count(); ++i) {
    scale.free[i] = net.masses.free[i] != 0.0;
    if (scale.free[i]) free_mass += net.mass(i);
  }
  scale.energy = free_mass * net.gravity.norm() * scale.size;
  if (!(scale.energy > 0)) {
    const Energy e = net.energy(start);
    scale.energy = std::max(e.kinetic, e.spring);
    if (!(scale.energy > 0)) scale.energy = 1;
  }
  return scale;
}

RunError compare_runs(const SampledRun& run, const SampledRun& reference, const ErrorScale& scale) {
  if (run.times != reference.times || run.positions.size() != reference.positions.size())
    throw std::invalid_argument("compare_runs: the runs reached different sample times");
  RunError e;
  double sum2 = 0;
  long count = 0;
  for (std::size_t j = 0; j < run.positions.size(); ++j) {
    const std::vector<double>& p = run.positions[j];
    const std::vector<double>& q = reference.positions[j];
    if (p.size() != q.size() || p.size() != 3 * scale.free.size())
      throw std::invalid_argument("compare_runs: the runs have different node counts");
    const NodeDistances d = node_distances(p.data(), q.data(), scale.free);
    const double sample_max = d.max;
    sum2 += d.sum2;
    count += d.count;
    e.position_max_by_sample.push_back(sample_max / scale.size);
    e.position_max = std::max(e.position_max, sample_max);
    e.energy = std::max(e.energy, std::abs(run.energy[j] - reference.energy[j]));
  }
  e.position_max /= scale.size;
  e.position_rms = count ? std::sqrt(sum2 / count) / scale.size : 0.0;
  e.energy /= scale.energy;
  return e;
}

}  // namespace neurocloth
