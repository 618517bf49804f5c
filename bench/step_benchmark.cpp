// Google Benchmark: one step of each integrator on the one step benchmark's
// cloth (step_bench.h: the default scene's cloth resized to N x N, the cloth
// and step rule `neurocloth-cli bench` times), and the same cloth read from an
// OBJ file (the mesh path: its springs in stencil order, stencil_order.h),
// the network step through each spring kernel (BM_KernelStep), and with its
// damping taken either way (BM_DampingStep).
// Run with --benchmark_repetitions=9 --benchmark_report_aggregates_only=true
// and quote the medians: this machine is shared and noisy.
#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "app/cli/step_bench.h"
#include "core/integrators/stability.h"

namespace neurocloth {
namespace {

// Frames of the one rule until the benchmark has timed enough; per spring
// update and per step, from the steps actually taken.
void time_steps(benchmark::State& st, const Scene& scene, IntegratorKind kind,
                SpringPrecision precision = SpringPrecision::float64,
                SpringKernel kernel = SpringKernel::automatic) {
  StepBench bench(scene, kind, 1, precision, kernel);
  long steps = 0;
  for (auto _ : st)
    steps += bench.run(StepBench::kFrameSteps);
  if (bench.simulation().status() != RunStatus::ok) st.SkipWithError("diverged");
  const auto springs = static_cast<double>(bench.springs());
  st.SetLabel(std::string(to_string(kind)) + ", " + to_string(precision) + " springs, " +
              to_string(resolved(kernel)) + " kernel");
  st.counters["springs"] = springs;
  st.counters["ns_per_spring"] =
      benchmark::Counter(springs * static_cast<double>(steps) * 1e-9,
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  st.counters["us_per_step"] = benchmark::Counter(
      static_cast<double>(steps) * 1e-6, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void BM_Step(benchmark::State& st) {
  time_steps(st, bare_cloth(static_cast<int>(st.range(1))),
             static_cast<IntegratorKind>(st.range(0)));
}

// The same N x N cloth through the mesh path, network propagation: what a
// mesh costs per spring beside BM_Step/0/N (a mesh has other springs: edges,
// one diagonal a quad, bends across edges; no shear).
void BM_MeshStep(benchmark::State& st) {
  time_steps(st, bare_mesh_cloth(static_cast<int>(st.range(0))), IntegratorKind::network);
}
BENCHMARK(BM_MeshStep)->Arg(32)->Arg(64)->Arg(128)->Unit(benchmark::kMicrosecond);

// The same mesh with its file's vertices shuffled: what renumbering the nodes
// at load (mesh_node_order.h) wins back against BM_MeshStep/N.
void BM_ShuffledMeshStep(benchmark::State& st) {
  time_steps(st, bare_shuffled_mesh_cloth(static_cast<int>(st.range(0))), IntegratorKind::network);
}
BENCHMARK(BM_ShuffledMeshStep)->Arg(32)->Arg(64)->Arg(128)->Unit(benchmark::kMicrosecond);

// The reference (step_bench.h): what the network step is measured against.
void BM_ReferenceScalarStep(benchmark::State& st) {
  const StepBench bench(bare_cloth(static_cast<int>(st.range(0))), IntegratorKind::network);
  ReferenceStep reference(bench);
  for (auto _ : st) {
    reference.run(StepBench::kFrameSteps);
    benchmark::DoNotOptimize(reference.positions().data());
  }
  st.counters["ns_per_spring"] = benchmark::Counter(
      static_cast<double>(reference.springs()) * StepBench::kFrameSteps * st.iterations() * 1e-9,
      benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_ReferenceScalarStep)->Arg(32)->Arg(64)->Arg(128)->Unit(benchmark::kMicrosecond);

void Args(benchmark::internal::Benchmark* b) {
  for (IntegratorKind k : kAllIntegrators)
    for (int n : {32, 64, 128})
      b->Args({static_cast<long>(k), n});
}
BENCHMARK(BM_Step)->Apply(Args)->Unit(benchmark::kMicrosecond);

// The network step with the springs' damping in the force sum (range(0) 0,
// the paper's) or taken implicitly after the update (1, spring_damping.h), on
// the N x N cloth (range(1)). us_per_step is the cost of one step;
// steps_per_simulated_s is what the adaptive cap (0.5 of the stability bound,
// with or without the damping's part) allows, so their product is the cost of
// a simulated second at the cap.
void BM_DampingStep(benchmark::State& st) {
  Scene scene = bare_cloth(static_cast<int>(st.range(1)));
  scene.solver.damping =
      st.range(0) == 1 ? DampingMode::implicit_springwise : DampingMode::explicit_force;
  time_steps(st, scene, IntegratorKind::network);
  const ClothNetwork net = scene.build_network();
  const double bound =
      integrator_step_bound(net, *make_integrator(scene.solver, net), scene.solver.step_bound);
  st.counters["steps_per_simulated_s"] = 1.0 / (0.5 * bound);
  st.SetLabel(std::string("network, damping ") + to_string(scene.solver.damping));
}
BENCHMARK(BM_DampingStep)->ArgsProduct({{0, 1}, {32, 64, 128}})->Unit(benchmark::kMicrosecond);

// The network step through one spring kernel (spring_kernel.h): range(0) the
// kernel, range(1) the precision, range(2) N. The AVX-512 kernel is reported
// as skipped where it is not compiled in. Interleave the two kernels'
// repetitions (--benchmark_enable_random_interleaving=true) for their ratio.
void BM_KernelStep(benchmark::State& st) {
  const auto kernel = static_cast<SpringKernel>(st.range(0));
  const std::string missing = kernel_unavailable(kernel);
  if (!missing.empty()) {
    st.SkipWithError(missing.c_str());
    return;
  }
  time_steps(st, bare_cloth(static_cast<int>(st.range(2))), IntegratorKind::network,
             static_cast<SpringPrecision>(st.range(1)), kernel);
}

void KernelArgs(benchmark::internal::Benchmark* b) {
  for (SpringPrecision p : {SpringPrecision::float64, SpringPrecision::float32})
    for (int n : {32, 64, 128})
      for (SpringKernel k : {SpringKernel::portable, SpringKernel::avx512})
        b->Args({static_cast<long>(k), static_cast<long>(p), n});
}
BENCHMARK(BM_KernelStep)->Apply(KernelArgs)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace neurocloth

BENCHMARK_MAIN();
