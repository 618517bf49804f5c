#include "app/cli/step_bench.h"

#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <numeric>
#include <random>
#include <utility>
#include <vector>

#include "core/integrators/stability.h"
#include "core/scene/mesh_node_order.h"
#include "core/scene/obj_mesh_builder.h"
#include "core/scene/obj_mesh_writer.h"

namespace neurocloth {
namespace fs = std::filesystem;

namespace {

Scene with_bench_step(Scene scene, IntegratorKind kind) {
  scene.solver.integrator = kind;
  scene.solver.adaptive = false;
  const ClothNetwork net = scene.build_network();
  const double bound =
      integrator_step_bound(net, *make_integrator(scene.solver, net), scene.solver.step_bound);
  scene.solver.dt = std::min(scene.solver.dt, 0.5 * bound);
  return scene;
}

// `scene` with its cloth replaced by `written` put through an OBJ file (vertex
// k + 1 is node k of `written`, whose numbering names the grid node each vertex
// is) in a temporary folder removed again; the pins follow their grid nodes.
Scene read_back_as_mesh(Scene scene, const ClothTopology& written) {
  const fs::path dir =
      fs::temp_directory_path() / ("neurocloth-mesh-" + std::to_string(::getpid()) + "-" +
                                   std::to_string(written.rest_positions.size()));
  fs::create_directories(dir);
  ObjMeshSpec spec;
  spec.path = (dir / "cloth.obj").string();
  try {
    write_obj_mesh(written, spec.path);
    scene.topology = build_obj_mesh(spec);
  } catch (...) {
    fs::remove_all(dir);
    throw;
  }
  fs::remove_all(dir);
  for (int& pin : scene.pins)
    pin = scene.topology.numbering.node(written.numbering.node(pin));
  scene.grid.reset();
  return scene;
}

}  // namespace

Scene table_drape_cloth(int n) {
  Scene scene = resized_grid(load_scene(assets_directory() + "/scenes/table_drape.json"), n);
  scene.solver.adaptive = false;
  return scene;
}

Scene bare_cloth(int n) {
  Scene scene = table_drape_cloth(n);
  scene.modules.clear();
  return scene;
}

Scene bare_mesh_cloth(int n) {
  Scene scene = bare_cloth(n);
  const ClothTopology grid = scene.topology;
  return read_back_as_mesh(std::move(scene), grid);
}

Scene bare_shuffled_mesh_cloth(int n) {
  Scene scene = bare_cloth(n);
  std::vector<std::int32_t> order(scene.topology.rest_positions.size());
  std::iota(order.begin(), order.end(), 0);
  std::shuffle(order.begin(), order.end(), std::mt19937(2024));
  const ClothTopology shuffled = renumbered(scene.topology, order);
  return read_back_as_mesh(std::move(scene), shuffled);
}

namespace {
Scene with_solver_choices(Scene scene, int threads, SpringPrecision precision,
                          SpringKernel kernel) {
  scene.solver.threads = threads;
  scene.solver.precision = precision;
  scene.solver.kernel = kernel;
  return scene;
}
}  // namespace

StepBench::StepBench(const Scene& scene, IntegratorKind integrator, int threads,
                     SpringPrecision precision, SpringKernel kernel)
    : sim_(with_solver_choices(with_bench_step(scene, integrator), threads, precision, kernel)
               .make_simulation()) {}

long StepBench::run(long steps) {
  const long before = sim_.steps();
  for (long left = steps; left > 0 && sim_.status() == RunStatus::ok; left -= kFrameSteps)
    sim_.advance(static_cast<double>(std::min(left, kFrameSteps)) * dt());
  return sim_.steps() - before;
}

ReferenceStep::ReferenceStep(const StepBench& bench) {
  const ClothNetwork& net = bench.simulation().network();
  for (std::size_t s = 0; s < net.spring_count(); ++s)
    springs_.push_back({net.springs.node_a[s], net.springs.node_b[s], net.springs.rest_length[s],
                        net.springs.stiffness[s], net.springs.damping[s]});
  const std::size_t n = net.node_count();
  p_.resize(n);
  v_.assign(n, Vec3::Zero());
  f_.resize(n);
  for (std::size_t i = 0; i < n; ++i)
    p_[i] = bench.simulation().state().position(i);
  inverse_mass_ = net.masses.inverse_mass;
  free_ = net.masses.free;
  gravity_ = net.gravity;
  dt_ = bench.dt();
}

void ReferenceStep::run(long steps) {
  for (long step = 0; step < steps; ++step) {
    for (auto& fi : f_)
      fi = Vec3::Zero();
    for (const Spring& s : springs_) {
      const Vec3 d = p_[s.b] - p_[s.a];
      const double len = d.norm();
      if (len <= 1e-12) continue;
      const Vec3 u = d / len;
      const Vec3 force = (s.k * (len - s.rest) + s.d * (v_[s.b] - v_[s.a]).dot(u)) * u;
      f_[s.a] += force;
      f_[s.b] -= force;
    }
    for (std::size_t i = 0; i < p_.size(); ++i) {
      v_[i] += dt_ * free_[i] * (inverse_mass_[i] * f_[i] + gravity_);
      p_[i] += dt_ * v_[i];
    }
  }
}

}  // namespace neurocloth
