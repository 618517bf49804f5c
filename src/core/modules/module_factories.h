#pragma once
// One factory per module type; each lives in the file named after its module.
#include <memory>

#include "core/modules/module_specs.h"
#include "core/network/cloth_topology.h"
#include "core/network/scene_module.h"

namespace neurocloth {

// colliders.cpp: contact with Coulomb friction against a solid shape.
std::unique_ptr<ConstraintModule> make_collider(const PlaneSpec& spec);
std::unique_ptr<ConstraintModule> make_collider(const BoxSpec& spec);
std::unique_ptr<ConstraintModule> make_collider(const SphereSpec& spec);
std::unique_ptr<ConstraintModule> make_collider(const CapsuleSpec& spec);
std::unique_ptr<ConstraintModule> make_collider(const CylinderSpec& spec);
// mesh_collider.cpp: the same contact against a triangle mesh, and the
// cloth's edges (its triangles') against the mesh's sharp edges.
std::unique_ptr<ConstraintModule> make_collider(const MeshSpec& spec,
                                                const ClothTopology& topology);

// air.cpp
std::shared_ptr<ForceModule> make_air_drag(const AirDragSpec& spec);
std::shared_ptr<ForceModule> make_wind(const WindSpec& spec, const ClothTopology& topology);

// bending.cpp: dihedral-angle hinges over the cloth's interior edges.
std::shared_ptr<ForceModule> make_bending(const BendingSpec& spec, const ClothTopology& topology);

// strain_limit.cpp
std::unique_ptr<ConstraintModule> make_strain_limit(const StrainLimitSpec& spec,
                                                    const ClothTopology& topology);
// self_collision.cpp
std::unique_ptr<ConstraintModule> make_self_collision(const SelfCollisionSpec& spec,
                                                      const ClothTopology& topology);
// pin_motion.cpp
std::unique_ptr<ConstraintModule> make_pin_motion(const PinMotionSpec& spec,
                                                  const ClothTopology& topology);

}  // namespace neurocloth
