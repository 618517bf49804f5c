// `neurocloth-cli bench`: the one step benchmark (step_bench.h: the default
// scene's cloth resized to N x N, stepped by the rule build/step_benchmark
// uses), timed by the wall clock through the same Simulation the other
// commands use, divergence checks included. Reports the median over repeats:
// this machine is shared and noisy.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <vector>

#include <nlohmann/json.hpp>

#include "commands.h"
#include "input_error.h"
#include "step_bench.h"

namespace neurocloth {
namespace {

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
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
  StepBench bench(bare_cloth(o.size), *kind);
  bench.run(10);  // warm-up: caches, page faults
  std::vector<double> rates;
  for (int r = 0; r < o.repeat; ++r) {
    const auto start = std::chrono::steady_clock::now();
    const long taken = bench.run(o.steps);
    const double wall =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    rates.push_back(static_cast<double>(taken) / wall);
  }
  const Simulation& sim = bench.simulation();
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
                          {"dt", bench.dt()},
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
                bench.dt());
    std::printf("  median of %d runs of %d steps: %.1f steps/s, %.3f ns per spring update\n",
                o.repeat, o.steps, sps, ns);
  }
  return kExitOk;
}

}  // namespace neurocloth
