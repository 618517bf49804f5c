#pragma once
// A material as a fabric lab measures it (docs/materials.md, "Measured
// units"): mass per area, tensile and shear stiffness per unit width (KES-FB1),
// bending rigidity per unit width (KES-FB2's B, or a cantilever's bending
// length), turned into the network's weights so that the cloth behaves the
// same at any spacing or mesh.
//
// In-plane: a square grid of structural springs k and two shear diagonals ks
// per cell stores, for a uniform strain E, (k/2)(Exx^2 + Eyy^2) +
// (ks/2)(Exx + Eyy)^2 + 2 ks Exy^2 per area, whatever the spacing: a sheet of
// shear stiffness G = ks and uniaxial (free-sided) tensile stiffness
// k (k + 2 ks) / (k + ks). A triangle mesh's edge e gets E (A1 + A2) / |e|^2
// (Van Gelder 1998: exact for equilateral triangles, an isotropic sheet of
// Poisson's ratio 1/3 whose shear is 3/8 of its tensile stiffness).
// Bending: a measured material has no bend springs (theirs is no plate's
// bending); its rigidity goes to the "bending" module's hinges (bending.h).
#include <nlohmann/json.hpp>

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/network/cloth_topology.h"
#include "core/network/material.h"

namespace neurocloth {

struct MeasuredMaterial {
  double areal_density = 0.2;              // kg/m^2
  double tensile_stiffness = 1e4;          // N/m: force per width per unit strain
  std::optional<double> shear_stiffness;   // N/m per radian; unset: 3/8 of tensile
  std::optional<double> bending_rigidity;  // N m; unset: no bending module from it
  double damping = 0.05;  // N s/m: the membrane's viscosity, like its stiffness per width
  double friction = 0.3;  // Coulomb coefficient

  double shear() const { return shear_stiffness ? *shear_stiffness : 0.375 * tensile_stiffness; }
};

class JsonFields;

// Reads the keys of a measured material (areal_density, tensile_stiffness,
// shear_stiffness, bending_rigidity or bending_length, damping, friction)
// from `v`, which `field` names; each inside its physical limit. Throws
// InputError naming the field.
MeasuredMaterial read_measured_material(const JsonFields& in, const nlohmann::json& v,
                                        const std::string& field);

// A shipped fabric (assets/materials/fabrics/NAME.json): its measured values
// and, for each, where the figure comes from (docs/materials.md's table).
struct MeasuredPreset {
  std::string name, path, description;
  MeasuredMaterial measured;
  std::map<std::string, std::string> sources;  // key of `measured` -> source
};
// The JSON object read_measured_material reads back as `m`.
nlohmann::json measured_material_json(const MeasuredMaterial& m);

// Throws InputError naming the file when there is no such fabric or it is malformed.
MeasuredPreset load_measured_preset(const std::string& name);
std::vector<std::string> measured_preset_names();  // sorted

// The network's constants for `m` on `topology`: spring and shear constants
// (N/m, for a grid; on a mesh spring_constant is the tensile stiffness that
// measured_spring_shares scales per edge), node_mass per kReferenceNodeArea,
// bend_constant 0. `notes` (when given) gets what the cloth cannot represent:
// a grid without shear springs, a mesh's shear fixed by its triangles.
Material measured_constants(const MeasuredMaterial& m, const ClothTopology& topology,
                            std::vector<std::string>* notes = nullptr);

// Per spring, the share of the constants it carries: 1 on a grid, E's
// (A1 + A2) / |e|^2 on a mesh's edges; 0 for bend springs.
std::vector<double> measured_spring_shares(const ClothTopology& topology);

// The sheet the network's springs make for `material` on a square grid with
// structural and shear springs: uniaxial tensile and shear stiffness, N/m (for
// `material command` to show the mapping both ways).
double grid_tensile_stiffness(const Material& material);

}  // namespace neurocloth
