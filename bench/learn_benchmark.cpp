// What learning costs (docs/learning.md, README "Speed"): one gradient of the
// fit's loss (a forward run that keeps its tape, then the adjoint run back)
// against one forward run alone, on the hanging scene's cloth resized to 32 x 32
// over 500 steps of 1 ms, fitting the spring constant and the viscosity to a
// recording of every node at 60 frames per second. The target: the
// gradient within 3x the forward run.
#include <benchmark/benchmark.h>

#include <string>

#include "fit_problem.h"
#include "scene.h"

namespace neurocloth {
namespace {

struct Case {
  Scene scene;
  ReferenceMotion reference;
};

Case make_case(int n, int steps) {
  Case c;
  c.scene = resized_grid(load_scene(std::string(NEUROCLOTH_SCENES) + "/hanging.json"), n);
  Simulation sim = c.scene.make_simulation();
  const double seconds = steps * c.scene.solver.dt;
  for (double t = 1.0 / 60; t <= seconds + 1e-12; t += 1.0 / 60) {
    sim.advance(t - sim.time());
    ReferenceFrame f;
    f.time = sim.time();
    for (std::size_t i = 0; i < sim.state().size(); ++i) {
      f.nodes.push_back(static_cast<std::int32_t>(i));
      f.positions.push_back(sim.state().position(i) + Vec3(0, 1e-3, 0));
    }
    c.reference.frames.push_back(f);
  }
  return c;
}

void BM_FitForward(benchmark::State& state) {
  const Case c = make_case(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  FitProblem p(c.scene, c.reference, FitSettings{});
  const Eigen::VectorXd theta = p.initial();
  for (auto _ : state)
    benchmark::DoNotOptimize(p.loss(theta, nullptr));
  state.counters["tape_MB"] = double(p.peak_tape_bytes()) / (1 << 20);
}

void BM_FitGradient(benchmark::State& state) {
  const Case c = make_case(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  FitSettings s;
  if (state.range(2) > 0) s.tape_budget_bytes = std::size_t(state.range(2)) << 20;
  FitProblem p(c.scene, c.reference, s);
  const Eigen::VectorXd theta = p.initial();
  Eigen::VectorXd g;
  for (auto _ : state)
    benchmark::DoNotOptimize(p.loss(theta, &g));
  state.counters["tape_MB"] = double(p.peak_tape_bytes()) / (1 << 20);
}

BENCHMARK(BM_FitForward)->Args({32, 500})->Unit(benchmark::kMillisecond);
// The whole tape in memory, then a budget that forces checkpointed segments.
BENCHMARK(BM_FitGradient)->Args({32, 500, 0})->Args({32, 500, 4})->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace neurocloth

BENCHMARK_MAIN();
