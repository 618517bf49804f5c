#include "ui/scene_info.h"

#include <algorithm>
#include <cstdio>

namespace neurocloth {

namespace {

std::string describe_cloth(const Scene& scene, double mass) {
  char line[256];
  if (!scene.grid) {
    std::snprintf(line, sizeof line, "mesh, %zu nodes, %.3g kg",
                  scene.topology.rest_positions.size(), mass);
    return line;
  }
  const GridSpec& g = *scene.grid;
  const double width = g.spacing * (std::max(g.rows, g.cols) - 1);
  int n = std::snprintf(line, sizeof line, "%d x %d nodes, %.3g m wide, %.3g kg", g.rows, g.cols,
                        width, mass);
  if (const auto& from = scene.resized_from) {
    // Equal for a square cloth; one squared from a rectangle keeps its mass per area.
    const bool kept = from->rows == from->cols;
    std::snprintf(line + n, sizeof line - n,
                  kept ? "; resized from %d x %d, width and total mass kept"
                       : "; resized from %d x %d, longer side and mass per area kept",
                  from->rows, from->cols);
  }
  return line;
}

}  // namespace

SceneInfo::SceneInfo(const Scene& scene)
    : name_(scene.name),
      path_(scene.path),
      names_(parameter_names(scene)),
      ranges_(parameter_ranges(scene)),
      material_(scene.material),
      solver_(scene.solver),
      trade_(
          load_accuracy_trade(scene.path, scene.resized_from && scene.grid ? scene.grid->rows : 0)),
      drape_(scene_drape_meter(scene)) {
  // Masses as the network has them (a rule base's node_mass is per reference
  // area, so nodes at the border carry less): built once per scene, not per drag.
  const ClothNetwork net = scene.build_network();
  node_mass_.resize(net.node_count());
  for (std::size_t i = 0; i < node_mass_.size(); ++i)
    node_mass_[i] = net.mass(i);
  mass_share_ = net.mass_share;
  double mass = 0;
  for (double m : node_mass_)
    mass += m;
  cloth_summary_ = describe_cloth(scene, mass);
  if (scene.fuzzy_material && scene.fuzzy_material->rules)
    fuzzy_.emplace(scene.fuzzy_material->rules_path, scene.fuzzy_material->rules);
}

const ParameterRange* SceneInfo::range(const ParameterId& id) const {
  return find_range(ranges_, id);
}

double SceneInfo::node_mass(int node, const std::vector<std::pair<std::string, double>>& inputs) {
  if (node < 0 || static_cast<std::size_t>(node) >= node_mass_.size()) return 0;
  if (!fuzzy_) return node_mass_[node];
  return mass_share_[node] * fuzzy_->evaluate(inputs).material.node_mass;
}

}  // namespace neurocloth
