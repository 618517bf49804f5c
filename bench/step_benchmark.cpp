// Google Benchmark: one step of each integrator on the default scene's cloth
// resized to N x N (the same cloth `neurocloth-cli bench` times). Run with
// --benchmark_repetitions=9 --benchmark_report_aggregates_only=true and quote
// the medians: this machine is shared and noisy.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <vector>

#include "scene.h"
#include "stability.h"

namespace neurocloth {
namespace {

Scene resized(int n) {
  return resized_grid(load_scene(assets_directory() + "/scenes/hanging.json"), n);
}

void BM_Step(benchmark::State& st) {
  const auto kind = static_cast<IntegratorKind>(st.range(0));
  const int n = static_cast<int>(st.range(1));
  Scene scene = resized(n);
  scene.solver.integrator = kind;
  const ClothNetwork net = scene.build_network();
  // Forward Euler gains energy on every undamped mode; a much smaller step keeps
  // it alive long enough to be timed (the cost of a step does not depend on dt).
  const double fraction = kind == IntegratorKind::explicit_euler ? 0.005 : 0.5;
  scene.solver.dt = std::min(scene.solver.dt, fraction * stable_step_bound(net, 2.0));
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

// The reference the brief measures against: a straightforward scalar loop over
// springs (array of structs, sqrt and a division, scatter-adds) plus the same
// semi-implicit Euler node update. Same cloth, same arithmetic, no layout work.
void BM_ReferenceScalarStep(benchmark::State& st) {
  const int n = static_cast<int>(st.range(0));
  const Scene scene = resized(n);
  const ClothNetwork net = scene.build_network();
  const double dt = std::min(scene.solver.dt, 0.5 * stable_step_bound(net, 2.0));
  struct Spring {
    int a, b;
    double rest, k, d;
  };
  std::vector<Spring> springs;
  for (std::size_t s = 0; s < net.spring_count(); ++s)
    springs.push_back({net.springs.node_a[s], net.springs.node_b[s], net.springs.rest_length[s],
                       net.springs.stiffness[s], net.springs.damping[s]});
  std::vector<Vec3> p(net.node_count()), v(net.node_count(), Vec3::Zero()), f(net.node_count());
  for (std::size_t i = 0; i < p.size(); ++i)
    p[i] = scene.topology.rest_positions[i];
  for (auto _ : st) {
    for (int step = 0; step < 16; ++step) {
      for (auto& fi : f)
        fi = Vec3::Zero();
      for (const Spring& s : springs) {
        const Vec3 d = p[s.b] - p[s.a];
        const double len = d.norm();
        if (len <= 1e-12) continue;
        const Vec3 u = d / len;
        const Vec3 force = (s.k * (len - s.rest) + s.d * (v[s.b] - v[s.a]).dot(u)) * u;
        f[s.a] += force;
        f[s.b] -= force;
      }
      for (std::size_t i = 0; i < p.size(); ++i) {
        const double free = net.masses.free[i];
        v[i] += dt * free * (net.masses.inverse_mass[i] * f[i] + net.gravity);
        p[i] += dt * v[i];
      }
    }
    benchmark::DoNotOptimize(p.data());
  }
  st.counters["ns_per_spring"] =
      benchmark::Counter(static_cast<double>(springs.size()) * 16 * st.iterations() * 1e-9,
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_ReferenceScalarStep)->Arg(32)->Arg(64)->Arg(128)->Unit(benchmark::kMicrosecond);

void Args(benchmark::internal::Benchmark* b) {
  for (IntegratorKind k : kAllIntegrators)
    for (int n : {32, 64, 128})
      b->Args({static_cast<long>(k), n});
}
BENCHMARK(BM_Step)->Apply(Args)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace neurocloth

BENCHMARK_MAIN();
