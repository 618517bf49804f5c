// tune-rules on the shipped rule base: 50 examples from cloth.fcl with
// elasticity.medium's peak moved from 0.35 to 0.45, tuned back from the
// original (spring_constant and viscosity named). One loss-and-gradient
// evaluation, and a tuning of 20 iterations with the RMSE before and after
// as counters (docs/learning.md, "Tuning a rule base from examples"). And
// the engine's derivatives alone per example, by which seeds they carry.
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>

#include "core/fuzzy/formats/fcl_reader.h"
#include "core/fuzzy/inference.h"
#include "learn/rules/rule_tuning.h"

namespace neurocloth {
namespace {

fuzzy::FuzzySystem cloth() {
  return fuzzy::read_fcl(NEUROCLOTH_MATERIALS "/cloth.fcl");
}

RuleExamples examples() {
  fuzzy::FuzzySystem truth = cloth();
  truth.inputs[truth.input_index("elasticity")].terms[1].function.params[1] = 0.45;
  RuleExamples e;
  e.path = "bench";
  e.outputs = {truth.output_index("spring_constant"), truth.output_index("viscosity")};
  std::mt19937 random(11);
  auto uniform = [&](double lo, double hi) {
    return lo + (hi - lo) * double(random()) / 4294967296.0;
  };
  for (int n = 0; n < 50; ++n) {
    const std::vector<double> x = {uniform(0.02, 1.5), uniform(0, 1), uniform(0, 10)};
    const auto r = fuzzy::infer(truth, x);
    e.inputs.push_back(x);
    e.targets.push_back({r.outputs[e.outputs[0]], r.outputs[e.outputs[1]]});
    e.lines.push_back(n + 2);
  }
  return e;
}

void BM_TuningLossAndGradient(benchmark::State& state) {
  const RuleExamples e = examples();
  const RuleTuning problem(cloth(), e, {});
  const Eigen::VectorXd theta = problem.initial();
  Eigen::VectorXd g;
  for (auto _ : state)
    benchmark::DoNotOptimize(problem.loss(theta, &g));
  state.counters["parameters"] = double(theta.size());
}
BENCHMARK(BM_TuningLossAndGradient)->Unit(benchmark::kMillisecond);

// The engine alone over the same 50 examples (items/s: examples per second): infer(),
// then infer_gradient() with every seed (102: 3 inputs, 99 parameters), with the
// inputs and the parameters tune-rules tunes, and with the inputs only (what
// FuzzyMaterial::sensitivity asks for).
enum class Seeds { none, all, tuned, inputs };
void BM_InferGradientPerExample(benchmark::State& state) {
  const Seeds seeds = Seeds(state.range(0));
  const RuleExamples e = examples();
  const fuzzy::FuzzySystem s = cloth();
  const std::vector<fuzzy::Parameter> wrt = seeds == Seeds::all ? fuzzy::parameters(s)
                                            : seeds == Seeds::tuned
                                                ? RuleTuning(s, e, {}).shape_parameters()
                                                : std::vector<fuzzy::Parameter>{};
  for (auto _ : state)
    for (const auto& x : e.inputs) {
      if (seeds == Seeds::none)
        benchmark::DoNotOptimize(fuzzy::infer(s, x));
      else
        benchmark::DoNotOptimize(fuzzy::infer_gradient(s, x, wrt));
    }
  state.SetItemsProcessed(std::int64_t(state.iterations()) * std::int64_t(e.inputs.size()));
  state.counters["seeds"] = seeds == Seeds::none ? 0.0 : double(s.inputs.size() + wrt.size());
}
BENCHMARK(BM_InferGradientPerExample)
    ->ArgName("seeds")
    ->Arg(int(Seeds::none))
    ->Arg(int(Seeds::all))
    ->Arg(int(Seeds::tuned))
    ->Arg(int(Seeds::inputs))
    ->Unit(benchmark::kMicrosecond);

void BM_TuneRules20Iterations(benchmark::State& state) {
  const RuleExamples e = examples();
  RuleTuningOptions o;
  o.search.max_iterations = 20;
  const RuleTuning problem(cloth(), e, o);
  RuleTuningResult r;
  for (auto _ : state)
    r = tune_rules(problem, o);
  // RMSE over both outputs, as a fraction of their ranges.
  state.counters["rmse_before"] = std::sqrt(r.loss_before);
  state.counters["rmse_after"] = std::sqrt(r.loss_after);
  state.counters["evaluations"] = double(r.search.evaluations);
}
BENCHMARK(BM_TuneRules20Iterations)->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace
}  // namespace neurocloth

BENCHMARK_MAIN();
