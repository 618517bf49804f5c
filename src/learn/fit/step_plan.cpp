#include "learn/fit/step_plan.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "core/io/physical_limits.h"
#include "core/scene/scene.h"

namespace neurocloth {

StepPlan window_of(const StepPlan& plan, std::size_t first, std::size_t count) {
  StepPlan w;
  const auto a = static_cast<std::ptrdiff_t>(first), b = static_cast<std::ptrdiff_t>(first + count);
  w.start.assign(plan.start.begin() + a, plan.start.begin() + b);
  w.size.assign(plan.size.begin() + a, plan.size.begin() + b);
  return w;
}

namespace {

// The scene's own run over the reference must be sound: the gradient of a run
// that diverges — a fixed step above the stable step rings and levels off
// (docs/stability.md) — says nothing about the scene, and its differences
// disagree with any adjoint.
void require_sound_run(Simulation& sim, double duration) {
  if (sim.advance(duration) != RunStatus::ok || sim.check_result() != RunStatus::ok)
    throw std::runtime_error("the scene's own run diverged before " + show_number(duration) +
                             " s: " + sim.divergence_reason());
  if (sim.budget_exhausted())
    throw std::runtime_error("the scene's own run ran out of step budget before " +
                             show_number(duration) + " s");
}

}  // namespace

StepPlan plan_steps(const Scene& scene, double duration, std::size_t max_steps) {
  StepPlan plan;
  if (!(duration > 0)) return plan;
  const double dt = scene.solver.dt;
  if (!scene.solver.adaptive) {
    // Simulation::advance's arithmetic: steps of dt, a shorter last one, and
    // the end time exact.
    double t = 0;
    while (t < duration) {
      if (plan.count() == max_steps)
        throw std::runtime_error("more than " + std::to_string(max_steps) + " steps of " +
                                 show_number(dt) + " s to reach t = " + show_number(duration) +
                                 " s");
      const double remaining = duration - t;
      const bool last = remaining <= dt * (1.0 + 1e-9);
      const bool whole = std::abs(remaining - dt) <= 1e-9 * dt;
      const double h = last && !whole ? remaining : dt;
      plan.start.push_back(t);
      plan.size.push_back(h);
      t = last ? duration : t + h;
    }
    Simulation sim = scene.make_simulation();
    require_sound_run(sim, duration);
    return plan;
  }
  Simulation sim = scene.make_simulation();
  sim.set_observer([&](const StepEvent& e) {
    if (!e.accepted) return;
    // The steps may be far below dt (a stiff cloth): the count, not the
    // duration, bounds the plan and every run of the fit. The simulation is
    // this function's own, dropped as the exception leaves.
    if (plan.count() == max_steps)
      throw std::runtime_error("the scene's own adaptive run takes more than " +
                               std::to_string(max_steps) +
                               " steps to reach t = " + show_number(duration) + " s (steps of " +
                               show_number(e.step) + " s at t = " + show_number(e.time) +
                               " s); a fit runs at most that many: a shorter reference");
    plan.start.push_back(e.time);
    plan.size.push_back(e.step);
  });
  require_sound_run(sim, duration);
  return plan;
}

}  // namespace neurocloth
