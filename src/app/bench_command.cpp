// `neurocloth-cli bench`: the default scene's cloth resized to N x N (all three
// spring families, same physical size), stepped with fixed steps through the
// same Simulation the other commands use, divergence checks included. Reports
// the median over repeats: this machine is shared and noisy.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <vector>

#include <nlohmann/json.hpp>

#include "commands.h"
#include "input_error.h"
#include "scene.h"
#include "stability.h"

namespace neurocloth {
namespace {

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

Scene bench_scene(int size, IntegratorKind integrator) {
  Scene scene = resized_grid(load_scene(assets_directory() + "/scenes/hanging.json"), size);
  scene.solver.integrator = integrator;
  scene.solver.adaptive = false;
  return scene;
}

}  // namespace

int run_bench(const BenchOptions& o) {
  // The largest grid a scene may declare (4 million nodes); runs a person waits for.
  if (o.size < 2 || o.size > 2000)
    throw InputError("command line", "--size", "must be in [2, 2000] (at most 4 million nodes)");
  if (o.steps < 1 || o.steps > 1000000)
    throw InputError("command line", "--steps", "must be in [1, 1000000]");
  if (o.repeat < 1 || o.repeat > 1000)
    throw InputError("command line", "--repeat", "must be in [1, 1000]");
  const auto kind = parse_integrator(o.integrator);
  if (!kind)
    throw InputError(
        "command line", "--integrator",
        "unknown integrator '" + o.integrator + "' (expected one of: " + integrator_names() + ")");
  Scene scene = bench_scene(o.size, *kind);
  {  // a step the explicit integrators survive, so the timing is of a healthy run
    const ClothNetwork net = scene.build_network();
    const double limit = make_integrator(*kind, net)->stability_limit();
    scene.solver.dt = std::min(scene.solver.dt, 0.5 * stable_step_bound(net, std::min(limit, 2.0)));
  }
  Simulation sim = scene.make_simulation();
  sim.advance(10 * scene.solver.dt);  // warm-up: caches, page faults
  std::vector<double> rates;
  for (int r = 0; r < o.repeat; ++r) {
    const auto start = std::chrono::steady_clock::now();
    sim.advance(o.steps * scene.solver.dt);
    const double wall =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    rates.push_back(o.steps / wall);
  }
  if (sim.status() != RunStatus::ok) {
    std::fprintf(stderr, "bench: the benchmark cloth diverged (%s)\n",
                 sim.divergence_reason().c_str());
    return kExitDiverged;
  }
  const double sps = median(rates);
  const double springs = static_cast<double>(sim.network().spring_count());
  const double ns = 1e9 / (sps * springs);
  if (o.json) {
    nlohmann::json doc = {{"size", o.size},
                          {"nodes", sim.network().node_count()},
                          {"springs", sim.network().spring_count()},
                          {"integrator", o.integrator},
                          {"dt", scene.solver.dt},
                          {"steps", o.steps},
                          {"repeat", o.repeat},
                          {"steps_per_second", sps},
                          {"ns_per_spring_update", ns},
                          {"steps_per_second_all", rates},
                          {"statistic", "median"}};
    std::printf("%s\n", doc.dump(1).c_str());
  } else {
    std::printf("%dx%d cloth, %zu nodes, %zu springs, %s, dt %.3g s\n", o.size, o.size,
                sim.network().node_count(), sim.network().spring_count(), o.integrator.c_str(),
                scene.solver.dt);
    std::printf("  median of %d runs of %d steps: %.1f steps/s, %.3f ns per spring update\n",
                o.repeat, o.steps, sps, ns);
  }
  return kExitOk;
}

}  // namespace neurocloth
