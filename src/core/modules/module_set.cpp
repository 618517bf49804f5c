#include "core/modules/module_set.h"

#include <algorithm>
#include <type_traits>

#include "core/modules/module_factories.h"

namespace neurocloth {

const char* module_type_names() {
  return "plane, box, sphere, capsule, cylinder, mesh, air_drag, wind, strain_limit, "
         "self_collision, pin_motion, bending";
}

ModuleSet build_modules(const std::vector<ModuleDeclaration>& declarations,
                        const ClothTopology& topology) {
  ModuleSet set;
  for (const ModuleDeclaration& d : declarations) {
    std::visit(
        [&](const auto& spec) {
          using T = std::decay_t<decltype(spec)>;
          std::shared_ptr<ForceModule> force;
          std::unique_ptr<ConstraintModule> constraint;
          if constexpr (std::is_same_v<T, AirDragSpec>)
            force = make_air_drag(spec);
          else if constexpr (std::is_same_v<T, BendingSpec>)
            force = make_bending(spec, topology);
          else if constexpr (std::is_same_v<T, WindSpec>)
            force = make_wind(spec, topology);
          else if constexpr (std::is_same_v<T, StrainLimitSpec>)
            constraint = make_strain_limit(spec, topology);
          else if constexpr (std::is_same_v<T, SelfCollisionSpec>)
            constraint = make_self_collision(spec, topology);
          else if constexpr (std::is_same_v<T, PinMotionSpec>)
            constraint = make_pin_motion(spec, topology);
          else if constexpr (std::is_same_v<T, MeshSpec>)
            constraint = make_collider(spec, topology);
          else
            constraint = make_collider(spec);
          if (force) {
            force->declaration = d.declaration;
            set.forces.push_back(std::move(force));
          } else {
            constraint->declaration = d.declaration;
            set.constraints.push_back(std::move(constraint));
          }
        },
        d.spec);
  }
  std::stable_sort(set.constraints.begin(), set.constraints.end(),
                   [](const auto& a, const auto& b) { return a->phase() < b->phase(); });
  return set;
}

}  // namespace neurocloth
