#pragma once
// The errors a trade can be measured in, between two runs of one cloth: where
// its nodes are (the largest distance and the RMS), where its surface is (the
// mean and largest distance from one cloth's nodes to the other's triangles,
// both ways), how it drapes over a support (the drape coefficient), how far it
// stretches and its energy. Positions are relative to the cloth's size, energy
// to the work gravity does dropping it by that size (docs/tradeoff.md, "Errors
// people see"). A run's error in a metric is its worst over the compared times
// (the RMS: over all of them).
#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/scene/scene.h"
#include "tradeoff/drape_shape.h"
#include "tradeoff/sampled_run.h"
#include "tradeoff/surface_distance.h"

namespace neurocloth {

enum class Metric : int { node_max, node_rms, surface_mean, surface_max, drape, stretch, energy };
inline constexpr int kMetricCount = 7;
inline constexpr Metric kAllMetrics[kMetricCount] = {
    Metric::node_max, Metric::node_rms, Metric::surface_mean, Metric::surface_max,
    Metric::drape,    Metric::stretch,  Metric::energy};
// What picks and fronts use unless told: the metric whose spread under a
// millimetre's shift is smallest against what real modelling errors (10% in
// stiffness or mass, a step twice too large) do to it, measured in
// docs/tradeoff.md ("Which metric"). Every scene has it.
inline constexpr Metric kDefaultMetric = Metric::energy;

using MetricValues = std::array<double, kMetricCount>;
constexpr std::size_t slot(Metric m) {
  return static_cast<std::size_t>(m);
}
MetricValues unmeasured_metrics();  // every entry NaN

const char* to_string(Metric m);  // "node_max", ...
std::optional<Metric> parse_metric(const std::string& name);
std::string metric_names();  // "node_max, node_rms, ..." for messages
// What a metric's figure is a fraction of, for reports.
const char* metric_meaning(Metric m);

// What comparing two states of one scene's cloth needs, taken from the scene
// once: its triangles, structural springs and support, and the scales.
struct MetricContext {
  std::size_t nodes = 0;
  Triangles triangles;
  std::vector<char> free;  // node distances are over free nodes (pins do not move)
  double size = 1;         // m: the initial cloth's bounding-box diagonal
  double energy_scale = 1;
  std::vector<std::array<std::int32_t, 2>> edges;  // the structural springs
  std::vector<double> rest;                        // their rest lengths
  std::optional<DrapeSupport> support;
  std::shared_ptr<const DrapeMeter> drape;  // set when the scene has a support
};
MetricContext metric_context(const Scene& scene);

// What one state shows by itself: its drape and its stretch.
struct FrameShape {
  double drape = 0;                        // the drape coefficient; NaN without a support
  int folds = -1;                          // -1 without a support
  double strain_max = 0, strain_mean = 0;  // structural springs' |l - l0| / l0
};
FrameShape frame_shape(const double* x, const MetricContext& context);

// A run's samples, with the shape of each, ready to be compared many times.
struct Trajectory {
  std::vector<std::vector<double>> positions;  // per sample: x0 y0 z0 ...
  std::vector<double> energy;                  // per sample, J
  std::vector<FrameShape> shapes;
};
Trajectory trajectory(const SampledRun& run, const MetricContext& context);

// One pair of states.
MetricValues compare_frames(const double* a, const FrameShape& shape_a, double energy_a,
                            const double* b, const FrameShape& shape_b, double energy_b,
                            const MetricContext& context);

struct MetricComparison {
  MetricValues run;                     // over the whole run
  std::vector<MetricValues> by_sample;  // at each compared time
};
// Throws std::invalid_argument when the two have different sample counts or
// node counts.
MetricComparison compare_trajectories(const Trajectory& a, const Trajectory& b,
                                      const MetricContext& context);

}  // namespace neurocloth
