#pragma once
// The scene's own spread: K references, each the scene with its cloth moved by
// less than anyone could place a real cloth to (by default 1 mm, in a seeded
// horizontal direction), run as the converged reference is. How far they land
// from each other is the floor below which no method's error means anything:
// a symmetric drape decides which way a fold falls on differences that small
// (docs/tradeoff.md, "The scene's own spread").
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "tradeoff/cloth_metrics.h"

namespace neurocloth {

inline constexpr int kMinEnsemble = 2, kMaxEnsemble = 64;
inline constexpr double kMinShift = 1e-9, kMaxShift = 0.05;  // m

struct EnsemblePlan {
  int members = 0;       // 0: no ensemble; else in [kMinEnsemble, kMaxEnsemble]
  double shift = 0.001;  // m, in [kMinShift, kMaxShift]
  std::uint64_t seed = 1;
};

// Why a plan cannot run ("" when it can), naming what is wrong.
std::string ensemble_refusal(const EnsemblePlan& plan);

// Member k's shift: `shift` metres in a horizontal direction (across gravity;
// the x-z plane without it). The K directions are evenly spaced around the
// circle and turned together by an angle drawn from the seed. The same on every
// machine: the angle comes from an integer hash and portable_sin/cos.
Vec3 member_shift(const Scene& scene, const EnsemblePlan& plan, int member);
// The scene with its cloth (its pins too) moved by `offset`; its colliders stay.
Scene shifted_scene(const Scene& scene, const Vec3& offset);

// The references' pairwise distances in every metric: for each metric the
// median and the 90th percentile over the K(K-1)/2 pairs, over the run and at
// each compared time. A method is within the floor when its distance to the
// ensemble is no more than p90.
struct EnsembleFloor {
  int members = 0;
  double shift = 0;
  std::uint64_t seed = 1;
  double member_dt = 0;  // RK4's step the members ran at
  MetricValues median = unmeasured_metrics(), p90 = unmeasured_metrics();
  std::vector<MetricValues> median_by_sample, p90_by_sample;
};

struct Ensemble {
  std::vector<Trajectory> members;
  EnsembleFloor floor;
};

// Runs the members with `settings` (RK4 at a converged step) through `times`,
// on up to `workers` threads. Throws std::runtime_error naming the member when
// one does not finish.
Ensemble run_ensemble(const Scene& scene, const std::vector<double>& times,
                      const SolverSettings& settings, const EnsemblePlan& plan,
                      const MetricContext& context, int workers,
                      const std::function<void(const std::string&)>& log = {});

// A run's distance to the ensemble in every metric: the median over the members.
MetricValues distance_to_ensemble(const Trajectory& run, const Ensemble& ensemble,
                                  const MetricContext& context);

// The p-quantile (p in [0, 1]) of `values` by linear interpolation between
// order statistics; NaN when any value is NaN or there are none.
double quantile(std::vector<double> values, double p);

}  // namespace neurocloth
