#pragma once
// The one step benchmark: the cloth and the step rule that `neurocloth-cli
// bench` and build/step_benchmark time, and the cloth build/module_benchmark
// starts from. The cloth is the default scene's (the table drape) resized to
// N x N, so every speed table (README "Speed", docs/history.md) speaks of the same cloth.
#include <string>
#include <vector>

#include "core/scene/scene.h"

namespace neurocloth {

// The table drape resized to n x n: the same 1.2 m square and material, all
// three spring families, its box still declared, fixed steps. n >= 2.
Scene table_drape_cloth(int n);

// The same cloth with no modules: what the network step alone costs.
Scene bare_cloth(int n);

// The bare cloth read through the mesh path: written as a Wavefront OBJ file
// (node k is vertex k + 1, the grid's two triangles a quad) into a temporary
// folder that is removed again, and built by build_obj_mesh: structural springs
// on the triangles' edges, bend springs across them (no shear family).
Scene bare_mesh_cloth(int n);
// The same with the OBJ file's vertices shuffled (a fixed seed): a mesh whose
// file scatters neighbours, renumbered at load (mesh_node_order.h).
Scene bare_shuffled_mesh_cloth(int n);

// Steps a scene's cloth by the benchmarks' one rule: fixed steps of half the
// semi-implicit Euler bound (L = 2) whatever the integrator, so every
// integrator is timed at the same step (forward Euler, which no such bound
// keeps stable, within half its damped bound too), in frames of 16 steps (a
// viewer frame: the end-of-advance checks weigh what they weigh in use).
class StepBench {
 public:
  // `threads` share each sweep (SolverSettings::threads; the results do not
  // depend on it); `precision` is the spring layer's arithmetic and `kernel`
  // the code that evaluates it (refused, std::invalid_argument, where the CPU
  // cannot run it).
  StepBench(const Scene& scene, IntegratorKind integrator, int threads = 1,
            SpringPrecision precision = SpringPrecision::float64,
            SpringKernel kernel = SpringKernel::automatic);
  // Takes about `steps` steps and returns how many it took.
  long run(long steps);
  static constexpr long kFrameSteps = 16;

  const Simulation& simulation() const { return sim_; }
  double dt() const { return sim_.settings().dt; }
  std::size_t springs() const { return sim_.network().spring_count(); }

 private:
  Simulation sim_;
};

// The reference the step is measured against: a straightforward scalar loop
// over springs (array of structs, sqrt and a division, scatter-adds) plus the
// same semi-implicit Euler node update, on the network's cloth at the
// benchmark's step. Same arithmetic, no layout work, one thread.
class ReferenceStep {
 public:
  explicit ReferenceStep(const StepBench& bench);
  void run(long steps);
  std::size_t springs() const { return springs_.size(); }
  const std::vector<Vec3>& positions() const { return p_; }

 private:
  struct Spring {
    int a, b;
    double rest, k, d;
  };
  std::vector<Spring> springs_;
  std::vector<Vec3> p_, v_, f_;
  std::vector<double> inverse_mass_, free_;
  Vec3 gravity_;
  double dt_;
};

}  // namespace neurocloth
