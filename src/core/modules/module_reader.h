#pragma once
// Reads a scene's "modules" array into checked declarations; every error names
// the file, the field (modules[i].key) and its line.
#include <vector>

#include "core/io/json_fields.h"
#include "core/modules/module_specs.h"
#include "core/network/cloth_topology.h"

namespace neurocloth {

// `pins` may grow: a pin_motion module pins the nodes it moves.
std::vector<ModuleDeclaration> read_modules(const JsonFields& in, const nlohmann::json& modules,
                                            const ClothTopology& topology, std::vector<int>& pins);

// One node reference: [row, col] on a grid cloth, or a node index.
int read_node_ref(const JsonFields& in, const nlohmann::json& v, const std::string& field,
                  const ClothTopology& topology);

}  // namespace neurocloth
