#include "scene_info.h"

namespace neurocloth {

SceneInfo::SceneInfo(const Scene& scene)
    : name_(scene.name),
      path_(scene.path),
      names_(parameter_names(scene)),
      ranges_(parameter_ranges(scene)),
      material_(scene.material),
      solver_(scene.solver),
      trade_(load_accuracy_trade(scene.path)) {
  // Masses as the network has them (a rule base's node_mass is per reference
  // area, so nodes at the border carry less): built once per scene, not per drag.
  const ClothNetwork net = scene.build_network();
  node_mass_.resize(net.node_count());
  for (std::size_t i = 0; i < node_mass_.size(); ++i)
    node_mass_[i] = net.mass(i);
  mass_share_ = net.mass_share;
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
