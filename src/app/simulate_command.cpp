#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>

#include "commands.h"
#include "input_error.h"
#include "result_json.h"
#include "scene.h"

namespace neurocloth {

int run_simulate(const SimulateOptions& o) {
  if (!(o.seconds >= 0) || !std::isfinite(o.seconds))
    throw InputError("command line", "--seconds", "must be a finite number >= 0");
  Scene scene = load_scene(o.scene);
  if (o.integrator) {
    const auto kind = parse_integrator(*o.integrator);
    if (!kind)
      throw InputError("command line", "--integrator",
                       "unknown integrator '" + *o.integrator +
                           "' (expected one of: " + integrator_names() + ")");
    scene.solver.integrator = *kind;
  }
  if (o.dt) {
    if (!(*o.dt > 0) || !std::isfinite(*o.dt))
      throw InputError("command line", "--dt", "must be a finite number > 0");
    scene.solver.dt = *o.dt;
  }
  if (o.adaptive) scene.solver.adaptive = true;
  if (o.fixed_step) scene.solver.adaptive = false;

  Simulation sim = scene.make_simulation();
  const auto start = std::chrono::steady_clock::now();
  sim.advance(o.seconds);
  sim.check_now();  // the result is checked in full, whatever the cadence
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  write_json_atomically(o.out, simulation_result(sim, o.scene, wall));

  const Energy e = sim.energy();
  std::printf("%s: %s at t = %.4g s after %ld steps (%ld rejected), %s%s, %.3g s wall\n",
              scene.name.c_str(), to_string(sim.status()), sim.time(), sim.steps(),
              sim.rejected_steps(), to_string(scene.solver.integrator),
              scene.solver.adaptive ? " adaptive" : "", wall);
  std::printf("  %zu nodes, %zu springs; energy: kinetic %.6g J, potential %.6g J, total %.6g J\n",
              sim.network().node_count(), sim.network().spring_count(), e.kinetic, e.potential(),
              e.total());
  for (const ModuleReport& m : sim.module_reports())
    std::printf("  module %-14s %8.3g s in %ld calls (%.3g us each)\n", m.type.c_str(), m.seconds,
                m.calls, m.calls ? 1e6 * m.seconds / m.calls : 0.0);
  if (sim.status() != RunStatus::ok)
    std::printf("  diverged: %s; kept the last good state (t = %.4g s)\n",
                sim.divergence_reason().c_str(), sim.time());
  std::printf("  wrote %s\n", o.out.c_str());
  return sim.status() == RunStatus::ok ? kExitOk : kExitDiverged;
}

}  // namespace neurocloth
