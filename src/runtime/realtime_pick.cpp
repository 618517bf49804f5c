#include "realtime_pick.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>

namespace neurocloth {

namespace {

Scene with_solver(const Scene& scene, const SolverSettings& s) {
  Scene copy = scene;
  copy.solver = s;
  return copy;
}

SolverSettings projective(const SolverSettings& own, int iterations) {
  SolverSettings s = own;
  s.integrator = IntegratorKind::projective;
  s.adaptive = false;
  s.dt = kRealtimeStep;
  s.iterations = iterations;
  return s;
}

std::string format(const char* pattern, double value) {
  char line[128];
  std::snprintf(line, sizeof line, pattern, value);
  return line;
}

}  // namespace

RealtimePick pick_for_real_time(const Scene& scene, const CostProbe& cost) {
  RealtimePick pick;
  pick.own = pick.picked = scene.solver;
  pick.own_cost = pick.picked_cost = cost(scene);
  if (pick.own_cost <= kRealtimeBudget) return pick;

  // The projective step's cost grows linearly with its iterations (one local
  // step and one prefactored solve each) on top of what a step costs anyway.
  const double one = cost(with_solver(scene, projective(scene.solver, 1)));
  const double four = cost(with_solver(scene, projective(scene.solver, 4)));
  const double per_iteration = std::max(0.0, (four - one) / 3);
  int iterations = 1;
  for (int it = kDefaultProjectiveIterations; it > 1; --it)
    if (one + (it - 1) * per_iteration <= kRealtimeBudget) {
      iterations = it;
      break;
    }
  pick.switched = true;
  pick.picked = projective(scene.solver, iterations);
  pick.picked_cost = one + (iterations - 1) * per_iteration;
  std::string note = "Running projective, " + std::to_string(iterations) +
                     (iterations == 1 ? " iteration" : " iterations") +
                     ", dt 1/60 s, to keep real time: the scene's " +
                     to_string(scene.solver.integrator) +
                     format(" step runs %.2gx real time at this size", 1 / pick.own_cost);
  if (pick.picked_cost > 1)
    note += format("; even this runs only %.2gx", 1 / pick.picked_cost);
  else if (pick.picked_cost > kRealtimeBudget)
    note += format("; this runs %.2gx, with little to spare", 1 / pick.picked_cost);
  note += ". Fewer iterations are more damped (docs/tradeoff.md).";
  pick.note = note;
  return pick;
}

double measure_cost(const Scene& scene, double wall_seconds, double max_sim_seconds) {
  using Clock = std::chrono::steady_clock;
  Simulation sim = scene.make_simulation();
  // Fixed steps advance a whole step at a time (a part step would be a one-off
  // of another length); an adaptive run in short pieces, so that the probe
  // stops near its wall time even when a piece is slow.
  const double frame =
      scene.solver.adaptive ? std::min(scene.solver.dt, 1.0 / 240) : scene.solver.dt;
  sim.advance(frame);  // untimed: the first factorisation, the first contact
  const double t0 = sim.time();
  const Clock::time_point start = Clock::now();
  double wall = 0;
  while (sim.status() == RunStatus::ok && sim.time() - t0 < max_sim_seconds) {
    sim.advance(frame);
    wall = std::chrono::duration<double>(Clock::now() - start).count();
    if (wall >= wall_seconds) break;
  }
  const double simulated = sim.time() - t0;
  if (!(simulated > 0)) return std::numeric_limits<double>::infinity();
  return wall / simulated;
}

}  // namespace neurocloth
