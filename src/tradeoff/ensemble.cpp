#include "tradeoff/ensemble.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "core/base/portable_trig.h"
#include "tradeoff/ordered_jobs.h"

namespace neurocloth {

std::string ensemble_refusal(const EnsemblePlan& plan) {
  char s[160];
  if (plan.members < kMinEnsemble || plan.members > kMaxEnsemble) {
    std::snprintf(s, sizeof s, "must be a whole number in [%d, %d], got %d", kMinEnsemble,
                  kMaxEnsemble, plan.members);
    return s;
  }
  if (!(plan.shift >= kMinShift && plan.shift <= kMaxShift)) {
    std::snprintf(s, sizeof s, "the shift must be in [%g, %g] m, got %g", kMinShift, kMaxShift,
                  plan.shift);
    return s;
  }
  return "";
}

Vec3 member_shift(const Scene& scene, const EnsemblePlan& plan, int member) {
  // Evenly spaced around the circle, all turned by one angle drawn from the
  // seed (splitmix64): no two members alike, however few.
  std::uint64_t z = plan.seed + 0x9E3779B97F4A7C15ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  z ^= z >> 31;
  const double turn = static_cast<double>(z >> 11) * 0x1.0p-53;
  const double angle = 2 * kPi * (member + turn) / std::max(plan.members, 1);
  const Vec3 up = scene.gravity.norm() > 0 ? Vec3(-scene.gravity.normalized()) : Vec3::UnitY();
  Vec3 u, w;
  horizontal_axes(up, u, w);
  return plan.shift * (portable_cos(angle) * u + portable_sin(angle) * w);
}

Scene shifted_scene(const Scene& scene, const Vec3& offset) {
  Scene s = scene;
  for (Vec3& p : s.topology.rest_positions)
    p += offset;
  if (s.grid) s.grid->origin += offset;
  return s;
}

double quantile(std::vector<double> values, double p) {
  if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
  for (double v : values)
    if (std::isnan(v)) return v;
  std::sort(values.begin(), values.end());
  const double at = p * static_cast<double>(values.size() - 1);
  const auto lo = static_cast<std::size_t>(std::floor(at));
  const std::size_t hi = std::min(lo + 1, values.size() - 1);
  return values[lo] + (at - static_cast<double>(lo)) * (values[hi] - values[lo]);
}

namespace {

// Per metric, the median and p90 of the same entry over `values`.
void spread(const std::vector<MetricValues>& values, MetricValues& median, MetricValues& p90) {
  for (Metric m : kAllMetrics) {
    std::vector<double> v;
    for (const MetricValues& x : values)
      v.push_back(x[slot(m)]);
    median[slot(m)] = quantile(v, 0.5);
    p90[slot(m)] = quantile(v, 0.9);
  }
}

}  // namespace

Ensemble run_ensemble(const Scene& scene, const std::vector<double>& times,
                      const SolverSettings& settings, const EnsemblePlan& plan,
                      const MetricContext& context, int workers,
                      const std::function<void(const std::string&)>& log) {
  if (const std::string why = ensemble_refusal(plan); !why.empty())
    throw std::invalid_argument("ensemble: " + why);
  Ensemble e;
  e.floor.members = plan.members;
  e.floor.shift = plan.shift;
  e.floor.seed = plan.seed;
  e.floor.member_dt = settings.dt;
  const auto k = static_cast<std::size_t>(plan.members);
  e.members.resize(k);
  std::vector<std::string> said(k);
  SolverSettings own = settings;
  if (workers > 1) own.threads = 1;  // two cores go to two members or to one step
  run_jobs_in_order(
      k, workers,
      [&](std::size_t i) {
        const Vec3 offset = member_shift(scene, plan, static_cast<int>(i));
        const Scene member = shifted_scene(scene, offset);
        const SampledRun run = run_sampled(member, own, times);
        if (!run.complete(times.size()))
          throw std::runtime_error(
              "ensemble member " + std::to_string(i + 1) + " (the cloth shifted by " +
              std::to_string(plan.shift) +
              " m) did not finish: " + (run.reason.empty() ? "it stopped" : run.reason));
        e.members[i] = trajectory(run, context);
        char s[200];
        std::snprintf(s, sizeof s,
                      "ensemble member %zu/%zu: shifted (%.3g, %.3g, %.3g) m, rk4 dt=%.4g s, "
                      "%.3g s %s",
                      i + 1, k, offset.x(), offset.y(), offset.z(), own.dt, run.cost_seconds,
                      to_string(run_clock(own)));
        said[i] = s;
      },
      [&](std::size_t i) {
        if (log) log(said[i]);
      });
  std::vector<MetricValues> pairs;
  std::vector<std::vector<MetricValues>> by_sample(times.size());
  for (std::size_t a = 0; a < k; ++a)
    for (std::size_t b = a + 1; b < k; ++b) {
      const MetricComparison c = compare_trajectories(e.members[a], e.members[b], context);
      pairs.push_back(c.run);
      for (std::size_t j = 0; j < times.size(); ++j)
        by_sample[j].push_back(c.by_sample[j]);
    }
  spread(pairs, e.floor.median, e.floor.p90);
  for (const std::vector<MetricValues>& at : by_sample) {
    MetricValues median, p90;
    spread(at, median, p90);
    e.floor.median_by_sample.push_back(median);
    e.floor.p90_by_sample.push_back(p90);
  }
  return e;
}

MetricValues distance_to_ensemble(const Trajectory& run, const Ensemble& ensemble,
                                  const MetricContext& context) {
  std::vector<MetricValues> to_each;
  for (const Trajectory& member : ensemble.members)
    to_each.push_back(compare_trajectories(run, member, context).run);
  MetricValues median, p90;
  spread(to_each, median, p90);
  return median;
}

}  // namespace neurocloth
