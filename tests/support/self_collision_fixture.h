#pragma once
// What the self-collision tests share: the thickness they run at, a module
// for a topology, and a state at rest.
#include <memory>

#include "core/modules/module_factories.h"
#include "core/scene/scene.h"

namespace neurocloth::self_collision_test {

inline constexpr double kThickness = 0.01;

inline std::unique_ptr<ConstraintModule> module_for(const ClothTopology& topology,
                                                    double thickness = kThickness) {
  SelfCollisionSpec spec;
  spec.thickness = thickness;
  return make_self_collision(spec, topology);
}

inline ClothState rest_of(const ClothTopology& t) {
  ClothState s(t.rest_positions.size());
  for (std::size_t i = 0; i < t.rest_positions.size(); ++i)
    s.set_position(i, t.rest_positions[i]);
  return s;
}

}  // namespace neurocloth::self_collision_test
