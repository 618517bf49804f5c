// Assembling a read Scene (scene_reader.cpp reads the file) into what runs:
// the network, its first state, the modules attached, and a grid cloth resized
// for `--size` and the benchmarks. Nothing here reads a file.
#include "core/scene/scene.h"

#include <algorithm>
#include <numeric>
#include <stdexcept>

#include "core/modules/module_set.h"
#include "core/network/material_limits.h"
#include "core/scene/element_weights.h"
#include "core/scene/fuzzy_material.h"
#include "core/scene/grid_builder.h"

namespace neurocloth {

namespace {
double cloth_area(const ClothTopology& t) {
  const std::vector<double> area = lumped_node_areas(t);
  return std::accumulate(area.begin(), area.end(), 0.0);
}
}  // namespace

double cloth_mass(const Scene& scene) {
  const ClothNetwork net = scene.build_network();
  double mass = 0;
  for (std::size_t i = 0; i < net.node_count(); ++i)
    mass += net.mass(i);
  return mass;
}

Scene resized_grid(const Scene& scene, int n) {
  if (!scene.grid || n < 2)
    throw std::invalid_argument("resized_grid needs a grid scene and n >= 2");
  Scene s = scene;
  GridSpec g = *scene.grid;
  g.spacing *= static_cast<double>(std::max(g.cols, g.rows) - 1) / (n - 1);
  g.rows = g.cols = n;
  g.families = SpringFamilies{};
  s.grid = g;
  s.topology = build_grid(g);
  s.element_weights.reset();                     // they were the old grid's springs and nodes
  if (!scene.pins.empty()) s.pins = {0, n - 1};  // a free cloth (a drape) stays free
  // Node indices of the old grid mean nothing on the new one: moving pins move the new pins.
  for (ModuleDeclaration& m : s.modules)
    if (auto* motion = std::get_if<PinMotionSpec>(&m.spec)) motion->nodes = s.pins;
  const double mass = cloth_mass(scene);
  s.resized_from = Scene::Resizing{scene.grid->rows, scene.grid->cols, mass};
  // A rule base's node_mass is per area already; a numeric one is per node, so
  // it is spread over the new nodes. A line of nodes (a chain) has no area: it
  // keeps its total mass.
  if (scene.measured_material) {
    s.material_notes.clear();
    s.material = measured_constants(*scene.measured_material, s.topology, &s.material_notes);
    // A measured material bends by its hinges, never by bend springs.
    s.topology.springs.erase(
        std::remove_if(s.topology.springs.begin(), s.topology.springs.end(),
                       [](const SpringSpec& sp) { return sp.family == SpringFamily::bend; }),
        s.topology.springs.end());
  } else if (!scene.fuzzy_material) {
    const double area = cloth_area(scene.topology);
    const double kept = area > 0 ? mass * cloth_area(s.topology) / area : mass;
    s.material.node_mass = kept / (static_cast<double>(n) * n);
    if (const auto why = material_outside_limits(s.material))
      throw std::invalid_argument("resized to " + std::to_string(n) + " x " + std::to_string(n) +
                                  ", the cloth's material " + *why);
  }
  return s;
}

ClothNetwork Scene::build_network() const {
  // A rule base's or a measured material's node_mass is the mass of
  // kReferenceNodeArea of cloth: each node carries its lumped share, so the
  // material weighs the same at any resolution (explicit materials give kg
  // per node and are left as written).
  std::vector<double> share;
  if (fuzzy_material || measured_material) {
    const std::vector<double> area = lumped_node_areas(topology);
    if (std::all_of(area.begin(), area.end(), [](double a) { return a > 0; }))
      for (double a : area)
        share.push_back(a / kReferenceNodeArea);
  }
  ClothNetwork net = ClothNetwork::build(
      topology, material, spring_function, std::move(share),
      measured_material ? measured_spring_shares(topology) : std::vector<double>{});
  if (element_weights) element_weights->apply_to(net);
  net.gravity = gravity;
  for (int p : pins)
    net.set_pinned(p, true);
  return net;
}

Simulation Scene::make_simulation() const {
  ClothNetwork net = build_network();
  if (modules.empty()) return Simulation(std::move(net), initial_state(), solver);
  ModuleSet set = build_modules(modules, topology);
  net.force_modules = std::move(set.forces);
  return Simulation(std::move(net), initial_state(), solver, std::move(set.constraints));
}

ClothState Scene::initial_state() const {
  ClothState s(topology.rest_positions.size());
  for (std::size_t i = 0; i < topology.rest_positions.size(); ++i) {
    s.set_position(i, topology.rest_positions[i]);
    s.set_velocity(i, initial_velocity);
  }
  for (int pin : pins)
    s.set_velocity(static_cast<std::size_t>(pin), Vec3::Zero());
  return s;
}

ParameterNames parameter_names(const Scene& scene) {
  ParameterNames names;
  if (scene.fuzzy_material)
    for (const auto& input : scene.fuzzy_material->inputs)  // a std::map: sorted by name
      names.inputs.push_back(input.first);
  for (const ModuleDeclaration& m : scene.modules)
    names.modules.push_back(m.type);
  return names;
}

}  // namespace neurocloth
