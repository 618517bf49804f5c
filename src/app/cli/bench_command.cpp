// `neurocloth-cli bench`: the one step benchmark (step_bench.h: the default
// scene's cloth resized to N x N, stepped by the rule build/step_benchmark
// uses), timed by the wall clock through the same Simulation the other
// commands use, divergence checks included, beside the plain reference loop.
// Reports medians over repeats: this machine is shared and noisy.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/cli/commands.h"
#include "app/cli/step_bench.h"
#include "core/base/cpu_features.h"
#include "core/io/input_error.h"

namespace neurocloth {
namespace {

// CPU seconds the calling thread has used: what a step costs it, whatever
// else the shared machine runs meanwhile.
double thread_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// --kernel NAME as the kernel that will run, or an InputError naming the option.
SpringKernel bench_kernel_option(const std::string& name) {
  const auto kernel = parse_kernel(name);
  if (!kernel)
    throw InputError(
        "command line", "--kernel",
        "unknown spring kernel '" + name + "' (expected one of: " + kKernelNames + ")");
  const std::string missing = kernel_unavailable(*kernel);
  if (!missing.empty()) throw InputError("command line", "--kernel", missing);
  return resolved(*kernel);
}

// Steps per second of one timed run of `bench`, by the wall clock.
double timed_rate(StepBench& bench, long steps) {
  const auto start = std::chrono::steady_clock::now();
  const long taken = bench.run(steps);
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return static_cast<double>(taken) / wall;
}

// Whether a step timed beside the asked one diverged; says so.
bool beside_diverged(const std::optional<StepBench>& bench, const char* what) {
  if (!bench || bench->simulation().status() == RunStatus::ok) return false;
  std::fprintf(stderr, "bench: the benchmark cloth diverged %s (%s)\n", what,
               bench->simulation().divergence_reason().c_str());
  return true;
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
  if (o.threads < 1 || o.threads > kMaxStepThreads)
    throw InputError("command line", "--threads",
                     "must be in [1, " + std::to_string(kMaxStepThreads) + "]");
  const SpringPrecision precision = precision_option(o.precision);
  const std::string conflict = precision_conflict(*kind, precision);
  if (!conflict.empty()) throw InputError("command line", "--precision", conflict);
  const bool in_float = precision == SpringPrecision::float32;
  const SpringKernel kernel = bench_kernel_option(o.kernel);
  StepBench bench(bare_cloth(o.size), *kind, o.threads, precision, kernel);
  // The reference loop (step_bench.h), timed in the same runs: the ratio of
  // the two medians says what the step's layout buys under this run's load.
  // With float, the double step is timed in the same runs too, for the same
  // reason; and with a kernel named, the other kernel where the CPU runs it.
  ReferenceStep reference(bench);
  std::optional<StepBench> in_double, in_other_kernel;
  if (in_float)
    in_double.emplace(bare_cloth(o.size), *kind, o.threads, SpringPrecision::float64, kernel);
  const SpringKernel other_kernel =
      kernel == SpringKernel::avx512 ? SpringKernel::portable : SpringKernel::avx512;
  if (o.kernel != to_string(SpringKernel::automatic) && kernel_unavailable(other_kernel).empty())
    in_other_kernel.emplace(bare_cloth(o.size), *kind, o.threads, precision, other_kernel);
  bench.run(10);  // warm-up: caches, page faults
  reference.run(10);
  for (auto* beside : {&in_double, &in_other_kernel})
    if (*beside) (*beside)->run(10);
  std::vector<double> rates, cpu_rates, reference_rates, double_rates, other_kernel_rates;
  for (int r = 0; r < o.repeat; ++r) {
    if (in_double) double_rates.push_back(timed_rate(*in_double, o.steps));
    if (in_other_kernel) other_kernel_rates.push_back(timed_rate(*in_other_kernel, o.steps));
    auto start = std::chrono::steady_clock::now();
    const double cpu_start = thread_cpu_seconds();
    const long taken = bench.run(o.steps);
    const double cpu = thread_cpu_seconds() - cpu_start;
    double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    rates.push_back(static_cast<double>(taken) / wall);
    cpu_rates.push_back(static_cast<double>(taken) / cpu);
    start = std::chrono::steady_clock::now();
    reference.run(o.steps);
    wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    reference_rates.push_back(static_cast<double>(o.steps) / wall);
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
  const double reference_ns = 1e9 / (median(reference_rates) * springs);
  const double cpu_ns = 1e9 / (median(cpu_rates) * springs);
  const double double_ns = in_double ? 1e9 / (median(double_rates) * springs) : ns;
  const double other_kernel_ns =
      in_other_kernel ? 1e9 / (median(other_kernel_rates) * springs) : ns;
  if (beside_diverged(in_double, "in double") ||
      beside_diverged(in_other_kernel, "under the other kernel"))
    return kExitDiverged;
  if (o.json) {
    nlohmann::json doc = {{"size", o.size},
                          {"nodes", sim.network().node_count()},
                          {"springs", sim.network().spring_count()},
                          {"integrator", o.integrator},
                          {"threads", o.threads},
                          {"precision", to_string(precision)},
                          {"kernel", to_string(kernel)},
                          {"cpu_has_avx512", cpu_has_avx512()},
                          {"dt", bench.dt()},
                          {"steps", o.steps},
                          {"repeat", o.repeat},
                          {"steps_per_second", sps},
                          {"ns_per_spring_update", ns},
                          {"steps_per_second_all", rates},
                          {"calling_thread_cpu_ns_per_spring_update", cpu_ns},
                          {"reference_ns_per_spring_update", reference_ns},
                          {"reference_ratio", reference_ns / ns},
                          {"statistic", "median"}};
    if (in_double) {
      doc["double_ns_per_spring_update"] = double_ns;
      doc["double_over_float"] = double_ns / ns;
    }
    if (in_other_kernel) {
      doc["other_kernel"] = to_string(other_kernel);
      doc["other_kernel_ns_per_spring_update"] = other_kernel_ns;
      doc["other_kernel_over_this"] = other_kernel_ns / ns;
    }
    std::printf("%s\n", doc.dump(1).c_str());
  } else {
    std::printf(
        "%dx%d cloth, %zu nodes, %zu springs, %s, %s springs, %s kernel (CPU %s AVX-512), dt "
        "%.3g s, %d thread%s\n",
        o.size, o.size, sim.network().node_count(), sim.network().spring_count(),
        o.integrator.c_str(), to_string(precision), to_string(kernel),
        cpu_has_avx512() ? "with" : "without", bench.dt(), o.threads, o.threads == 1 ? "" : "s");
    std::printf("  median of %d runs of %d steps: %.1f steps/s, %.3f ns per spring update\n",
                o.repeat, o.steps, sps, ns);
    std::printf("  CPU time of the calling thread: %.3f ns per spring update\n", cpu_ns);
    std::printf(
        "  reference scalar loop, same runs: %.3f ns per spring update (%.2fx the step's)\n",
        reference_ns, reference_ns / ns);
    if (in_double)
      std::printf(
          "  double springs, same runs: %.3f ns per spring update (%.2fx the float step's)\n",
          double_ns, double_ns / ns);
    if (in_other_kernel)
      std::printf("  %s kernel, same runs: %.3f ns per spring update (%.2fx this kernel's)\n",
                  to_string(other_kernel), other_kernel_ns, other_kernel_ns / ns);
  }
  return kExitOk;
}

}  // namespace neurocloth
