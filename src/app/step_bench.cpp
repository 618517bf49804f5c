#include "step_bench.h"

#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <numeric>
#include <random>
#include <utility>
#include <vector>

#include "mesh_node_order.h"
#include "obj_mesh_builder.h"
#include "obj_mesh_writer.h"
#include "stability.h"

namespace neurocloth {
namespace fs = std::filesystem;

namespace {

Scene with_bench_step(Scene scene, IntegratorKind kind) {
  scene.solver.integrator = kind;
  scene.solver.adaptive = false;
  const ClothNetwork net = scene.build_network();
  double bound = stable_step_bound(net, 2.0);
  if (kind == IntegratorKind::explicit_euler) {
    const double damped = explicit_euler_step_bound(net);
    if (damped > 0) bound = std::min(bound, damped);
  }
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

StepBench::StepBench(const Scene& scene, IntegratorKind integrator)
    : sim_(with_bench_step(scene, integrator).make_simulation()) {}

long StepBench::run(long steps) {
  const long before = sim_.steps();
  for (long left = steps; left > 0 && sim_.status() == RunStatus::ok; left -= kFrameSteps)
    sim_.advance(static_cast<double>(std::min(left, kFrameSteps)) * dt());
  return sim_.steps() - before;
}

}  // namespace neurocloth
