// Google Benchmark: one step of each integrator on the default scene's cloth
// resized to N x N (the same cloth `neurocloth-cli bench` times). Run with
// --benchmark_repetitions=9 --benchmark_report_aggregates_only=true and quote
// the medians: this machine is shared and noisy.
#include <benchmark/benchmark.h>

#include <algorithm>

#include "scene.h"
#include "stability.h"

namespace neurocloth {
namespace {

Scene resized(int n) {
  Scene scene = load_scene(assets_directory() + "/scenes/hanging.json");
  GridSpec g = *scene.grid;
  g.spacing *= static_cast<double>(g.cols - 1) / (n - 1);
  g.rows = g.cols = n;
  scene.grid = g;
  scene.topology = build_grid(g);
  scene.pins = {0, n - 1};
  return scene;
}

void BM_Step(benchmark::State& st) {
  const auto kind = static_cast<IntegratorKind>(st.range(0));
  const int n = static_cast<int>(st.range(1));
  Scene scene = resized(n);
  scene.solver.integrator = kind;
  const ClothNetwork net = scene.build_network();
  scene.solver.dt = std::min(scene.solver.dt, 0.5 * stable_step_bound(net, 2.0));
  Simulation sim = scene.make_simulation();
  // 16 steps an iteration, like a viewer frame: the end-of-advance checks weigh
  // what they weigh in use.
  constexpr int kSteps = 16;
  for (auto _ : st)
    sim.advance(kSteps * scene.solver.dt);
  if (sim.status() != RunStatus::ok) st.SkipWithError("diverged");
  st.SetLabel(to_string(kind));
  st.counters["springs"] = static_cast<double>(net.spring_count());
  st.counters["ns_per_spring"] =
      benchmark::Counter(static_cast<double>(net.spring_count()) * kSteps * st.iterations() * 1e-9,
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  st.counters["us_per_step"] = benchmark::Counter(
      kSteps * st.iterations() * 1e-6, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void Args(benchmark::internal::Benchmark* b) {
  for (IntegratorKind k : kAllIntegrators)
    for (int n : {32, 64, 128})
      b->Args({static_cast<long>(k), n});
}
BENCHMARK(BM_Step)->Apply(Args)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace neurocloth

BENCHMARK_MAIN();
