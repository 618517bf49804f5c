// The large-step integrators on the hanging cloth refined to N x N (its width
// and total mass kept by resized_grid): wall seconds per simulated second at
// dt 1/64 s, with CG (implicit_euler, its default preconditioner) or
// local-global (projective) iterations per step as counters. The figures of docs/network.md "Large
// steps".
//   build/large_step_benchmark --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <string>

#include "core/scene/scene.h"

namespace neurocloth {
namespace {

constexpr double kSeconds = 0.5;

// Whole runs of `seconds` from the scene's start (the factor is made inside,
// timed as a user waits): s per simulated s, and CG (or local-global)
// iterations a step.
void time_runs(benchmark::State& state, const Scene& scene, double seconds) {
  long steps = 0, iterations = 0;
  for (auto _ : state) {
    Simulation sim = scene.make_simulation();
    if (sim.advance(seconds) != RunStatus::ok) state.SkipWithError("the run did not finish ok");
    steps += sim.steps();
    iterations += sim.cg_iterations();
  }
  state.counters["s_per_simulated_s"] =
      benchmark::Counter(seconds * static_cast<double>(state.iterations()),
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["iterations_per_step"] =
      static_cast<double>(iterations) / static_cast<double>(steps);
}

void BM_LargeStep(benchmark::State& state, IntegratorKind kind,
                  double linear_tolerance = kDefaultLinearTolerance) {
  Scene scene = resized_grid(load_scene(std::string(NEUROCLOTH_SCENES) + "/hanging.json"),
                             static_cast<int>(state.range(0)));
  scene.solver.integrator = kind;
  scene.solver.adaptive = false;
  scene.solver.dt = 1.0 / 64;
  scene.solver.linear_tolerance = linear_tolerance;
  time_runs(state, scene, kSeconds);
}

void Sizes(benchmark::internal::Benchmark* b) {
  b->Arg(32)->Arg(64)->Arg(128)->Unit(benchmark::kMillisecond)->Iterations(1)->UseRealTime();
}

BENCHMARK_CAPTURE(BM_LargeStep, projective, IntegratorKind::projective)->Apply(Sizes);
BENCHMARK_CAPTURE(BM_LargeStep, implicit_euler, IntegratorKind::implicit_euler)->Apply(Sizes);
// A looser linear solve (solver.linear_tolerance 1e-6), against the default 1e-10.
BENCHMARK_CAPTURE(BM_LargeStep, implicit_euler_looser, IntegratorKind::implicit_euler, 1e-6)
    ->Apply(Sizes);

// The table drape (issue 27's scene) at 128 x 128, 2 s at a fixed step of
// 1/60 or 1/30 s, at each of the tradeoff's implicit tolerances, with the
// implicit step's preconditioner named, on range(1) threads (the same bits):
// s per simulated s, CG iterations a step.
void BM_TableDrape(benchmark::State& state, IntegratorKind kind, double dt, double linear_tolerance,
                   ImplicitPreconditioner preconditioner = ImplicitPreconditioner::automatic) {
  constexpr double kDrapeSeconds = 2;
  Scene scene = resized_grid(load_scene(std::string(NEUROCLOTH_SCENES) + "/table_drape.json"),
                             static_cast<int>(state.range(0)));
  scene.solver.integrator = kind;
  scene.solver.adaptive = false;
  scene.solver.dt = dt;
  scene.solver.linear_tolerance = linear_tolerance;
  scene.solver.implicit_preconditioner = preconditioner;
  scene.solver.threads = static_cast<int>(state.range(1));
  time_runs(state, scene, kDrapeSeconds);
}

void Drape(benchmark::internal::Benchmark* b) {
  b->Args({128, 1})->Unit(benchmark::kMillisecond)->Iterations(1)->UseRealTime();
}
// One thread and two.
void DrapeThreads(benchmark::internal::Benchmark* b) {
  Drape(b);
  b->Args({128, 2});
}

constexpr auto kImplicit = IntegratorKind::implicit_euler;
constexpr auto kMultigrid = ImplicitPreconditioner::multigrid;
// The default (at 128 x 128 the Laplacian preconditioner) at dt 1/60 and 1/30 s
// and the tolerances 1e-10, 1e-6, 1e-3; the multigrid it replaced beside it.
BENCHMARK_CAPTURE(BM_TableDrape, implicit_60_1e10, kImplicit, 1.0 / 60, 1e-10)->Apply(Drape);
BENCHMARK_CAPTURE(BM_TableDrape, implicit_60_1e6, kImplicit, 1.0 / 60, 1e-6)->Apply(Drape);
BENCHMARK_CAPTURE(BM_TableDrape, implicit_60_1e3, kImplicit, 1.0 / 60, 1e-3)->Apply(DrapeThreads);
BENCHMARK_CAPTURE(BM_TableDrape, implicit_30_1e10, kImplicit, 1.0 / 30, 1e-10)->Apply(Drape);
BENCHMARK_CAPTURE(BM_TableDrape, implicit_30_1e6, kImplicit, 1.0 / 30, 1e-6)->Apply(Drape);
BENCHMARK_CAPTURE(BM_TableDrape, implicit_30_1e3, kImplicit, 1.0 / 30, 1e-3)->Apply(DrapeThreads);
BENCHMARK_CAPTURE(BM_TableDrape, multigrid_60_1e10, kImplicit, 1.0 / 60, 1e-10, kMultigrid)
    ->Apply(Drape);
BENCHMARK_CAPTURE(BM_TableDrape, multigrid_60_1e6, kImplicit, 1.0 / 60, 1e-6, kMultigrid)
    ->Apply(Drape);
BENCHMARK_CAPTURE(BM_TableDrape, multigrid_60_1e3, kImplicit, 1.0 / 60, 1e-3, kMultigrid)
    ->Apply(Drape);
BENCHMARK_CAPTURE(BM_TableDrape, multigrid_30_1e3, kImplicit, 1.0 / 30, 1e-3, kMultigrid)
    ->Apply(Drape);
// Projective at the window's step and its default 10 iterations, for scale.
BENCHMARK_CAPTURE(BM_TableDrape, projective_60, IntegratorKind::projective, 1.0 / 60, 1e-10)
    ->Apply(DrapeThreads);

}  // namespace
}  // namespace neurocloth

BENCHMARK_MAIN();
