#pragma once
// The physical parameters a material gives the network (paper: "spring
// constant, mass, viscosity and friction force"). The fuzzy system derives them
// from linguistic descriptions (fuzzy_material.h); a scene may also state them
// directly.
namespace neurocloth {

// A material given per area (in words, or measured) weighs node_mass for this
// much cloth, m^2 (a node of a 5 cm grid); a scene gives each node its lumped
// share of the cloth's area in these units (Scene::build_network), so the
// cloth weighs the same at any resolution.
inline constexpr double kReferenceNodeArea = 0.0025;

struct Material {
  double spring_constant = 200.0;  // N/m, structural springs
  double shear_constant = -1.0;    // N/m; < 0 means "same as spring_constant"
  double bend_constant = -1.0;     // N/m; < 0 means "same as spring_constant"
  double node_mass = 0.01;         // kg per node
  double viscosity = 0.05;         // N s/m, damping along each spring
  double friction = 0.1;           // Coulomb coefficient (used by colliders)

  double shear() const { return shear_constant < 0 ? spring_constant : shear_constant; }
  double bend() const { return bend_constant < 0 ? spring_constant : bend_constant; }
};

}  // namespace neurocloth
