#include "tradeoff/cloth_metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "tradeoff/run_error.h"

namespace neurocloth {

MetricValues unmeasured_metrics() {
  MetricValues v;
  v.fill(std::numeric_limits<double>::quiet_NaN());
  return v;
}

const char* to_string(Metric m) {
  switch (m) {
    case Metric::node_max:
      return "node_max";
    case Metric::node_rms:
      return "node_rms";
    case Metric::surface_mean:
      return "surface_mean";
    case Metric::surface_max:
      return "surface_max";
    case Metric::drape:
      return "drape";
    case Metric::stretch:
      return "stretch";
    case Metric::energy:
      return "energy";
  }
  return "?";
}

std::optional<Metric> parse_metric(const std::string& name) {
  for (Metric m : kAllMetrics)
    if (name == to_string(m)) return m;
  return std::nullopt;
}

std::string metric_names() {
  std::string s;
  for (Metric m : kAllMetrics)
    s += std::string(s.empty() ? "" : ", ") + to_string(m);
  return s;
}

const char* metric_meaning(Metric m) {
  switch (m) {
    case Metric::drape:
      return "drape coefficient (0..1)";
    case Metric::stretch:
      return "mean structural strain";
    case Metric::energy:
      return "the work of gravity over the size";
    default:
      return "the cloth's size";
  }
}

MetricContext metric_context(const Scene& scene) {
  MetricContext c;
  const ErrorScale scale = error_scale(scene);
  c.size = scale.size;
  c.energy_scale = scale.energy;
  c.free = scale.free;
  c.nodes = scale.free.size();
  c.triangles = scene.topology.triangles;
  const std::vector<Vec3>& rest = scene.topology.rest_positions;
  for (const SpringSpec& s : scene.topology.springs) {
    if (s.family != SpringFamily::structural) continue;
    const double l0 =
        (rest[static_cast<std::size_t>(s.a)] - rest[static_cast<std::size_t>(s.b)]).norm();
    if (!(l0 > 0)) continue;
    c.edges.push_back({s.a, s.b});
    c.rest.push_back(l0);
  }
  c.drape = scene_drape_meter(scene);
  if (c.drape) c.support = c.drape->support();
  return c;
}

FrameShape frame_shape(const double* x, const MetricContext& c) {
  FrameShape f;
  if (c.drape) {
    const DrapeShape d = c.drape->measure(x);
    f.drape = d.coefficient;
    f.folds = d.folds;
  } else {
    f.drape = std::numeric_limits<double>::quiet_NaN();
  }
  double sum = 0;
  for (std::size_t k = 0; k < c.edges.size(); ++k) {
    const auto a = static_cast<std::size_t>(c.edges[k][0]),
               b = static_cast<std::size_t>(c.edges[k][1]);
    const Vec3 d(x[3 * a] - x[3 * b], x[3 * a + 1] - x[3 * b + 1], x[3 * a + 2] - x[3 * b + 2]);
    const double strain = std::abs(d.norm() - c.rest[k]) / c.rest[k];
    f.strain_max = std::max(f.strain_max, strain);
    sum += strain;
  }
  f.strain_mean = c.edges.empty() ? 0 : sum / static_cast<double>(c.edges.size());
  return f;
}

Trajectory trajectory(const SampledRun& run, const MetricContext& context) {
  Trajectory t;
  t.positions = run.positions;
  t.energy = run.energy;
  for (const std::vector<double>& x : t.positions) {
    if (x.size() != 3 * context.nodes)
      throw std::invalid_argument("trajectory: the run has another node count than its scene");
    t.shapes.push_back(frame_shape(x.data(), context));
  }
  return t;
}

MetricValues compare_frames(const double* a, const FrameShape& shape_a, double energy_a,
                            const double* b, const FrameShape& shape_b, double energy_b,
                            const MetricContext& c) {
  MetricValues v;
  const NodeDistances d = node_distances(a, b, c.free);
  v[slot(Metric::node_max)] = d.max / c.size;
  v[slot(Metric::node_rms)] = d.rms() / c.size;
  const SurfaceDistance s = surface_distance(a, b, c.nodes, c.triangles);
  v[slot(Metric::surface_mean)] = s.mean / c.size;
  v[slot(Metric::surface_max)] = s.max / c.size;
  v[slot(Metric::drape)] = std::abs(shape_a.drape - shape_b.drape);
  v[slot(Metric::stretch)] = std::abs(shape_a.strain_mean - shape_b.strain_mean);
  v[slot(Metric::energy)] = std::abs(energy_a - energy_b) / c.energy_scale;
  return v;
}

MetricComparison compare_trajectories(const Trajectory& a, const Trajectory& b,
                                      const MetricContext& c) {
  if (a.positions.size() != b.positions.size() || a.shapes.size() != a.positions.size() ||
      b.shapes.size() != b.positions.size() || a.energy.size() != a.positions.size() ||
      b.energy.size() != b.positions.size())
    throw std::invalid_argument("compare_trajectories: the runs reached different sample times");
  MetricComparison out;
  out.run.fill(0);
  double rms2 = 0;
  for (std::size_t j = 0; j < a.positions.size(); ++j) {
    if (a.positions[j].size() != 3 * c.nodes || b.positions[j].size() != 3 * c.nodes)
      throw std::invalid_argument("compare_trajectories: the runs have different node counts");
    const MetricValues v = compare_frames(a.positions[j].data(), a.shapes[j], a.energy[j],
                                          b.positions[j].data(), b.shapes[j], b.energy[j], c);
    out.by_sample.push_back(v);
    for (int m = 0; m < kMetricCount; ++m)
      out.run[static_cast<std::size_t>(m)] =
          std::max(out.run[static_cast<std::size_t>(m)], v[static_cast<std::size_t>(m)]);
    const double r = v[slot(Metric::node_rms)];
    rms2 += r * r;
  }
  // Every sample has the same free nodes: the RMS over all is the RMS of the samples'.
  out.run[slot(Metric::node_rms)] =
      a.positions.empty() ? 0 : std::sqrt(rms2 / static_cast<double>(a.positions.size()));
  // std::max drops a NaN that comes second; a metric with nothing to measure stays NaN.
  for (int m = 0; m < kMetricCount; ++m)
    for (const MetricValues& v : out.by_sample)
      if (std::isnan(v[static_cast<std::size_t>(m)]))
        out.run[static_cast<std::size_t>(m)] = std::numeric_limits<double>::quiet_NaN();
  return out;
}

}  // namespace neurocloth
