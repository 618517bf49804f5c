#include <chrono>
#include <cstdio>

#include "app/cli/commands.h"
#include "app/cli/motion_outputs.h"
#include "app/cli/result_json.h"
#include "core/scene/scene.h"
#include "core/simulation/relaxation.h"

namespace neurocloth {

int run_relax(const RelaxOptions& o) {
  const Scene scene = load_scene(o.scene);
  check_output_path("--out", o.out, input_files(scene));
  const ClothNetwork net = scene.build_network();
  ClothState state = scene.initial_state();
  const auto start = std::chrono::steady_clock::now();
  const RelaxReport r = relax(net, state);
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  nlohmann::json doc;
  doc["status"] = r.converged ? "ok" : "not_converged";
  doc["scene"] = o.scene;
  doc["time"] = 0.0;
  doc["steps"] = r.iterations;
  doc["rejected_steps"] = 0;
  doc["cg_iterations"] = r.cg_iterations;
  doc["residual_force"] = r.residual_force;
  doc["last_step"] = r.last_step;
  doc["accepted_steps"] = r.accepted_steps;
  doc["free_nodes"] = r.free_nodes;
  doc["wall_seconds"] = wall;
  doc["nodes"] = net.node_count();
  doc["springs"] = net.spring_count();
  doc["energy"] = energy_json(net.energy(state));
  doc["positions"] = state_json(state, scene.topology.numbering, false);
  doc["velocities"] = state_json(state, scene.topology.numbering, true);
  write_json_atomically(o.out, doc);

  if (r.free_nodes == 0)
    std::printf("%s: nothing to relax: every node is pinned, so the cloth rests as it is\n",
                scene.name.c_str());
  else
    std::printf(
        "%s: relaxation %s after %d Newton iterations (%d CG, %d accepted), residual force %.3g "
        "N, last step %.3g m\n",
        scene.name.c_str(), r.converged ? "converged" : "did NOT converge", r.iterations,
        r.cg_iterations, r.accepted_steps, r.residual_force, r.last_step);
  std::printf("  potential energy %.9g J; wrote %s\n", net.energy(state).potential(),
              o.out.c_str());
  return r.converged ? kExitOk : kExitNotConverged;
}

}  // namespace neurocloth
