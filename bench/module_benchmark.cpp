// Google Benchmark: what scene modules cost on top of the bare network. The
// table drape's cloth resized to N x N is stepped by the one step benchmark's
// rule (step_bench.h: fixed network steps) three ways: bare (no modules), with
// a declared plane that no node ever reaches, and lying on the table (the box
// collider in contact with the cloth's middle every step). Quote medians of
//   --benchmark_repetitions=9 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include "app/cli/step_bench.h"

namespace neurocloth {
namespace {

enum Variant { bare = 0, unreached_plane = 1, on_table = 2 };

Scene variant_scene(Variant v, int n) {
  Scene scene = table_drape_cloth(n);
  const ModuleDeclaration table = scene.modules.at(0);  // the box
  scene.modules.clear();
  if (v == unreached_plane) {
    PlaneSpec far_below;
    far_below.point = Vec3(0, -100, 0);
    scene.modules.push_back({"plane", "{\"type\":\"plane\"}", far_below});
  }
  if (v == on_table) {
    scene.modules.push_back(table);
    // Lower the cloth onto the table top (0.75 m) so the middle is in contact.
    const double drop = scene.topology.rest_positions[0].y() - (0.75 + 0.004);
    for (Vec3& p : scene.topology.rest_positions)
      p.y() -= drop;
  }
  return scene;
}

void BM_Modules(benchmark::State& st) {
  const auto v = static_cast<Variant>(st.range(0));
  const int n = static_cast<int>(st.range(1));
  StepBench bench(variant_scene(v, n), IntegratorKind::network);
  long steps = 0;
  for (auto _ : st)
    steps += bench.run(StepBench::kFrameSteps);
  if (bench.simulation().status() != RunStatus::ok) st.SkipWithError("diverged");
  static const char* const names[] = {"bare", "unreached_plane", "on_table"};
  st.SetLabel(names[v]);
  st.counters["us_per_step"] = benchmark::Counter(
      static_cast<double>(steps) * 1e-6, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

BENCHMARK(BM_Modules)
    ->ArgsProduct({{bare, unreached_plane, on_table}, {32, 64, 128}})
    ->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace neurocloth

BENCHMARK_MAIN();
