// The float spring layer's error against double (SolverSettings::precision) on
// every shipped scene: each scene run T seconds (default 2) under its own
// solver in both precisions, and how far the float run's free nodes landed
// from the double run's, relative to the cloth's size (run_error.h), at 20
// sample times. Prints the Markdown table of docs/network.md, "Float springs".
//   precision_error [T]
#include <algorithm>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>
#include <vector>

#include "scene.h"
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
      "| scene | integrator | nodes | max \\|x_float - x_double\\| / size | RMS / size |\n");
  std::printf("|---|---|---|---|---|\n");
  for (const std::string& path : paths) {
    const Scene scene = load_scene(path);
    const std::string name = std::filesystem::path(path).stem().string();
    const char* integrator = to_string(scene.solver.integrator);
    const std::size_t nodes = scene.topology.rest_positions.size();
    SolverSettings in_double = scene.solver, in_float = scene.solver;
    in_double.precision = SpringPrecision::float64;
    in_float.precision = SpringPrecision::float32;
    const std::string conflict = precision_conflict(in_float.integrator, in_float.precision);
    if (!conflict.empty()) {
      std::printf("| %s | %s | %zu | no float path (%s) | |\n", name.c_str(), integrator, nodes,
                  integrator);
      continue;
    }
    const SampledRun d = run_sampled(scene, in_double, times);
    const SampledRun f = run_sampled(scene, in_float, times);
    if (!d.complete(times.size()) || !f.complete(times.size())) {
      std::printf("| %s | %s | %zu | incomplete (double %s, float %s) | |\n", name.c_str(),
                  integrator, nodes, d.complete(times.size()) ? "ok" : "did not finish",
                  f.complete(times.size()) ? "ok" : "did not finish");
      continue;
    }
    const RunError e = compare_runs(f, d, error_scale(scene));
    std::printf("| %s | %s | %zu | %.2e | %.2e |\n", name.c_str(), integrator, nodes,
                e.position_max, e.position_rms);
    std::fflush(stdout);
  }
  return 0;
}
