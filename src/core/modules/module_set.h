#pragma once
// The modules a scene declared, built once for one cloth.
#include <memory>
#include <vector>

#include "core/modules/module_specs.h"
#include "core/network/cloth_topology.h"
#include "core/network/scene_module.h"

namespace neurocloth {

// Both kinds are model: immutable once built, so copies of a simulation share them.
struct ModuleSet {
  std::vector<std::shared_ptr<const ForceModule>> forces;  // in the network's force evaluation
  std::vector<std::shared_ptr<const ConstraintModule>> constraints;  // after each step, by phase
  bool empty() const { return forces.empty() && constraints.empty(); }
};

// Builds each declaration's module (in declaration order within a phase).
ModuleSet build_modules(const std::vector<ModuleDeclaration>& declarations,
                        const ClothTopology& topology);

}  // namespace neurocloth
