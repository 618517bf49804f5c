// How a reference's frames become the plan a fit's runs follow (fit_problem.h):
// the steps to the last frame, and for each frame the step it falls in and
// what it observes (nodes and their positions, or a point cloud), refused
// with the field at fault when the scene cannot be compared with it; and what
// that plan tells back (its steps, its observations, the reference's own state).
#include "learn/fit/observation_plan.h"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/io/input_error.h"
#include "core/io/physical_limits.h"
#include "learn/fit/fit_problem_impl.h"
#include "learn/fit/rollout.h"
#include "learn/fit/step_plan.h"

namespace neurocloth {

void FitProblem::Impl::plan(const ReferenceMotion& ref) {
  if (ref.frames.empty()) throw InputError(ref.path, "frames", "the reference has no frames");
  const std::size_t n = base.net.node_count();
  duration = ref.frames.back().time;
  if (!(duration > 0))
    throw InputError(ref.path, "time", "the reference ends at t = 0: nothing to fit to");
  // A fit runs the scene to the last frame many times: a reference whose time
  // runs to years would never finish (or allocate a plan of that many steps).
  if (!(duration / scene.solver.dt <= static_cast<double>(kMaxFitSteps)))
    throw InputError(ref.path, "time",
                     "the reference ends at t = " + show_number(duration) +
                         " s: " + show_number(duration / scene.solver.dt) +
                         " steps of the scene's dt; a fit runs at most 1e7");
  // A projective run keeps every iteration's Chebyshev weight for its adjoint
  // (16 bytes each), and each iteration is a solve: a plan of more iterations
  // than this is refused before it allocates them.
  if (base.integrator == IntegratorKind::projective &&
      duration / scene.solver.dt * scene.solver.iterations > kMaxFitIterations)
    throw InputError(scene.path, "solver.iterations",
                     "fit: " + show_number(duration / scene.solver.dt) + " steps of " +
                         std::to_string(scene.solver.iterations) +
                         " projective iterations to reach t = " + show_number(duration) +
                         " s; a fit runs at most 1e7 iterations: fewer iterations, larger "
                         "steps or a shorter reference");
  StepPlan steps;
  try {
    steps = plan_steps(scene, duration);
  } catch (const std::runtime_error& e) {
    throw InputError(scene.path, "solver", std::string("fit: ") + e.what());
  }
  ObservationPlan obs;
  std::shared_ptr<const ClothSurface> surface;
  if (ref.is_cloud()) {
    if (scene.topology.triangles.empty())
      throw InputError(ref.path, "points",
                       "a point cloud is compared with the cloth's triangles, and this scene's "
                       "cloth has none (a chain)");
    surface = std::make_shared<const ClothSurface>(scene.topology.triangles, n);
  }
  for (const ReferenceFrame& f : ref.frames) {
    if (!(f.time >= 0))
      throw InputError(ref.path, "time", "a frame before the scene's start (t < 0)");
    ObservationPlan::Frame fr;
    const auto it = std::upper_bound(steps.start.begin(), steps.start.end(), f.time);
    fr.step =
        it == steps.start.begin() ? 0 : static_cast<std::size_t>(it - steps.start.begin()) - 1;
    fr.step = std::min(fr.step, steps.count() - 1);
    fr.alpha = std::clamp((f.time - steps.start[fr.step]) / steps.size[fr.step], 0.0, 1.0);
    if (ref.is_cloud()) {
      if (f.positions.empty())
        throw InputError(ref.path, "points",
                         "the frame at t = " + show_number(f.time) + " s has no points");
      fr.cloud = static_cast<int>(obs.clouds.size());
      fr.count = f.positions.size();
      obs.clouds.push_back(
          std::make_shared<const ChamferTarget>(f.positions, surface, settings.chamfer));
      obs.frames.push_back(fr);
      frame_times.push_back(f.time);
      continue;
    }
    fr.first = obs.nodes.size();
    fr.count = f.nodes.size();
    for (std::size_t k = 0; k < f.nodes.size(); ++k) {
      const std::int32_t file_node = f.nodes[k];
      if (file_node < 0 || static_cast<std::size_t>(file_node) >= n)
        throw InputError(ref.path, "node",
                         "node " + std::to_string(file_node) + " is not in the scene (it has " +
                             std::to_string(n) + " nodes)");
      obs.nodes.push_back(scene.topology.numbering.node(file_node));
      obs.targets.push_back(f.positions[k]);
    }
    obs.frames.push_back(fr);
    frame_times.push_back(f.time);
  }
  this->steps = steps;
  observed = obs;
  rollout = std::make_unique<Rollout>(scene.initial_state(), std::move(steps), std::move(obs),
                                      settings.tape_budget_bytes);
}

std::size_t FitProblem::window_observations(std::size_t first, std::size_t count) const {
  std::size_t n = 0;
  for (const ObservationPlan::Frame& f : impl_->observed.frames)
    if (f.step >= first && f.step < first + count) n += f.count;
  return n;
}

std::size_t FitProblem::step_count() const {
  return impl_->steps.count();
}
double FitProblem::step_time(std::size_t k) const {
  return impl_->steps.start.at(k);
}
ClothState FitProblem::initial_state() const {
  return impl_->scene.initial_state();
}

bool FitProblem::reference_state(double t, ClothState& state) const {
  const Impl& m = *impl_;
  const std::vector<double>& ft = m.frame_times;
  const std::size_t n = m.base.net.node_count();
  if (ft.size() < 2 || !(t >= ft.front()) || !(t <= ft.back())) return false;
  // Frame f observes every node, in the order frame 0 lists them.
  const auto full = [&](std::size_t f) {
    const ObservationPlan::Frame& fr = m.observed.frames[f];
    if (fr.cloud >= 0 || fr.count != n) return false;  // a cloud names no node
    const ObservationPlan::Frame& first = m.observed.frames[0];
    return first.count == n && std::equal(m.observed.nodes.begin() + std::ptrdiff_t(fr.first),
                                          m.observed.nodes.begin() + std::ptrdiff_t(fr.first + n),
                                          m.observed.nodes.begin() + std::ptrdiff_t(first.first));
  };
  const auto at = [&](std::size_t f, std::size_t k) -> Vec3 {
    return m.observed.targets[m.observed.frames[f].first + k];
  };
  std::size_t f = static_cast<std::size_t>(std::upper_bound(ft.begin(), ft.end(), t) - ft.begin());
  f = std::min(std::max<std::size_t>(f, 1), ft.size() - 1);  // frames f-1 and f bracket t
  if (!full(f - 1) || !full(f)) return false;
  // Velocity at a frame: central difference where both neighbours are full
  // (second order), else one-sided.
  const auto velocity = [&](std::size_t g, std::size_t k) -> Vec3 {
    const std::size_t lo = g > 0 && full(g - 1) ? g - 1 : g;
    const std::size_t hi = g + 1 < ft.size() && full(g + 1) ? g + 1 : g;
    return (at(hi, k) - at(lo, k)) / (ft[hi] - ft[lo]);
  };
  const double w = (t - ft[f - 1]) / (ft[f] - ft[f - 1]);
  ClothState s(n);
  const ObservationPlan::Frame& first = m.observed.frames[f - 1];
  for (std::size_t k = 0; k < n; ++k) {
    const auto i = static_cast<std::size_t>(m.observed.nodes[first.first + k]);
    s.set_position(i, (1 - w) * at(f - 1, k) + w * at(f, k));
    s.set_velocity(i, (1 - w) * velocity(f - 1, k) + w * velocity(f, k));
  }
  state = std::move(s);
  return true;
}

bool FitProblem::fits_cloud() const {
  return !impl_->observed.clouds.empty();
}
double FitProblem::duration() const {
  return impl_->duration;
}

std::size_t ObservationPlan::data_count() const {
  std::size_t n = nodes.size();
  for (const auto& c : clouds)
    n += c->size();
  return n;
}

ObservationPlan window_of(const ObservationPlan& obs, std::size_t first, std::size_t count) {
  ObservationPlan w;
  w.clouds = obs.clouds;
  for (const ObservationPlan::Frame& f : obs.frames) {
    if (f.step < first || f.step >= first + count) continue;
    ObservationPlan::Frame g = f;
    g.step -= first;
    if (f.cloud >= 0) {  // the window keeps its clouds' numbers
      w.frames.push_back(g);
      continue;
    }
    g.first = w.nodes.size();
    w.nodes.insert(w.nodes.end(), obs.nodes.begin() + static_cast<std::ptrdiff_t>(f.first),
                   obs.nodes.begin() + static_cast<std::ptrdiff_t>(f.first + f.count));
    w.targets.insert(w.targets.end(), obs.targets.begin() + static_cast<std::ptrdiff_t>(f.first),
                     obs.targets.begin() + static_cast<std::ptrdiff_t>(f.first + f.count));
    w.frames.push_back(g);
  }
  return w;
}

}  // namespace neurocloth
