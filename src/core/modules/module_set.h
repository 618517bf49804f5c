#pragma once
// The modules a scene declared, built once for one cloth.
#include <memory>
#include <vector>

#include "../cloth_topology.h"
#include "module_specs.h"
#include "scene_module.h"

namespace neurocloth {

struct ModuleSet {
  std::vector<std::shared_ptr<ForceModule>> forces;  // go into the network's force evaluation
  std::vector<std::unique_ptr<ConstraintModule>> constraints;  // run after each step, by phase
  bool empty() const { return forces.empty() && constraints.empty(); }
};

// Builds each declaration's module (in declaration order within a phase).
ModuleSet build_modules(const std::vector<ModuleDeclaration>& declarations,
                        const ClothTopology& topology);

}  // namespace neurocloth
