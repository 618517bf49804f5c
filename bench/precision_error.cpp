// The float spring layer's error against double (SolverSettings::precision) on
// every shipped scene: each scene run T seconds (default 2) under its own
// solver in both precisions, and how far the float run's free nodes landed
// from the double run's, relative to the cloth's size (run_error.h), at 20
// sample times. Beside it, the same measure between double runs at dt and
// dt/2 (the refresh interval, when adaptive): how far the step's own discretisation moves the same
// run, so the float error can be read against it (a cloth that folds or collides amplifies any
// small difference alike). Prints the table of docs/network.md, "Float springs".
//   precision_error [T]
#include <algorithm>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>
#include <vector>

#include "core/scene/scene.h"
#include "tradeoff/run_error.h"
#include "tradeoff/sampled_run.h"

using namespace neurocloth;

int main(int argc, char** argv) {
  double seconds = 2.0;
  if (argc > 1) {
    try {
      seconds = std::stod(argv[1]);
    } catch (const std::exception&) {
      seconds = -1;
    }
    if (!(seconds > 0 && seconds <= 100)) {
      std::fprintf(stderr, "precision_error: T must be a number of seconds in (0, 100]\n");
      return 1;
    }
  }
  std::vector<std::string> paths;
  for (const auto& entry : std::filesystem::directory_iterator(NEUROCLOTH_SCENES))
    if (entry.path().extension() == ".json") paths.push_back(entry.path().string());
  std::sort(paths.begin(), paths.end());
  const std::vector<double> times = sample_times(seconds, 20);
  std::printf(
      "| scene | solver | nodes | float vs double: max / size | RMS / size | "
      "double, dt/2 vs dt: max / size |\n");
  std::printf("|---|---|---|---|---|---|\n");
  for (const std::string& path : paths) {
    const Scene scene = load_scene(path);
    const std::string name = std::filesystem::path(path).stem().string();
    const std::string solver = std::string(to_string(scene.solver.integrator)) +
                               (scene.solver.adaptive ? ", adaptive" : "");
    const char* integrator = solver.c_str();
    const std::size_t nodes = scene.topology.rest_positions.size();
    SolverSettings in_double = scene.solver, in_float = scene.solver;
    in_double.precision = SpringPrecision::float64;
    in_float.precision = SpringPrecision::float32;
    const std::string conflict = precision_conflict(in_float.integrator, in_float.precision);
    if (!conflict.empty()) {
      std::printf("| %s | %s | %zu | no float path (%s) | | |\n", name.c_str(), integrator, nodes,
                  integrator);
      continue;
    }
    const SampledRun d = run_sampled(scene, in_double, times);
    const SampledRun f = run_sampled(scene, in_float, times);
    if (!d.complete(times.size()) || !f.complete(times.size())) {
      std::printf("| %s | %s | %zu | incomplete (double %s, float %s) | | |\n", name.c_str(),
                  integrator, nodes, d.complete(times.size()) ? "ok" : "did not finish",
                  f.complete(times.size()) ? "ok" : "did not finish");
      continue;
    }
    const ErrorScale scale = error_scale(scene);
    const RunError e = compare_runs(f, d, scale);
    SolverSettings halved = in_double;
    halved.dt = 0.5 * in_double.dt;
    const SampledRun h = run_sampled(scene, halved, times);
    char step_error[32] = "did not finish";
    if (h.complete(times.size()))
      std::snprintf(step_error, sizeof step_error, "%.2e", compare_runs(h, d, scale).position_max);
    std::printf("| %s | %s | %zu | %.2e | %.2e | %s |\n", name.c_str(), integrator, nodes,
                e.position_max, e.position_rms, step_error);
    std::fflush(stdout);
  }
  return 0;
}
