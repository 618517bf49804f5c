#pragma once
// The steps a fit's runs take (rollout.h): fixed, as Simulation::advance
// takes them, or the adaptive propagation's accepted steps held fixed while
// the weights change, and the window of them an online fit runs.
#include <cstddef>
#include <vector>

namespace neurocloth {

// The steps a run takes, start time and size each: a fixed step, or the
// accepted steps of the adaptive propagation held fixed while weights change.
// A fit runs the scene to the reference's last frame many times: at most this
// many steps (fixed, or the adaptive run's accepted steps).
inline constexpr std::size_t kMaxFitSteps = 10000000;
// And at most this many projective local-global iterations (steps x iterations).
inline constexpr double kMaxFitIterations = 1e7;

struct StepPlan {
  std::vector<double> start, size;
  std::size_t count() const { return size.size(); }
  double end() const { return size.empty() ? 0.0 : start.back() + size.back(); }
};

// The part of `plan` in steps [first, first + count), renumbered from 0: a
// window for truncated back-propagation (online fits).
StepPlan window_of(const StepPlan& plan, std::size_t first, std::size_t count);

// The plan a scene's solver takes to `duration`: fixed steps as
// Simulation::advance takes them, or (adaptive) the steps it accepted, run
// once with the scene's own weights. Throws std::runtime_error when that run
// diverges or runs out of step budget, or the plan would pass `max_steps`.
struct Scene;
StepPlan plan_steps(const Scene& scene, double duration, std::size_t max_steps = kMaxFitSteps);

}  // namespace neurocloth
