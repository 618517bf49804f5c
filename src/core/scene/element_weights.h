#pragma once
// Per-element weights beside a scene: one stiffness, damping and rest length
// per spring and one mass per node, as a fit learns them (docs/learning.md). A
// scene names the file under "element_weights"; once the network is built
// from the material, these replace its weights. Springs are keyed by their two
// file vertex indices and family, nodes listed in file order, so the file does
// not depend on how the loader orders nodes in memory (NodeNumbering).
#include <nlohmann/json.hpp>

#include <string>
#include <vector>

#include "core/network/cloth_network.h"
#include "core/network/cloth_topology.h"

namespace neurocloth {

struct ElementWeights {
  std::string path;  // the side file, for messages
  // In the network's order (the topology's springs and nodes).
  std::vector<double> stiffness, damping, rest_length;  // one per spring
  std::vector<double> node_mass;                        // one per node, kg

  // Writes them into `net` (built from the same topology): stiffness, damping,
  // rest length and 1/m replace what the material gave.
  void apply_to(ClothNetwork& net) const;
};

// Reads and checks the side file `path` against `topology`: every spring of
// the cloth listed exactly once, no other, every node's mass; values finite,
// masses and rest lengths > 0, each inside the scene's physical limits.
// Throws InputError naming the file, field and line.
ElementWeights read_element_weights(const std::string& path, const ClothTopology& topology);

// The side file's document for `net`'s current weights (built from `topology`).
nlohmann::json element_weights_json(const ClothNetwork& net, const ClothTopology& topology);

}  // namespace neurocloth
