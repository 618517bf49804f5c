#include "core/network/material_limits.h"

#include "core/io/physical_limits.h"

namespace neurocloth {

std::optional<std::string> material_outside_limits(const Material& m) {
  const struct {
    const char* name;
    double value;
    const Limit& limit;
  } checks[] = {{"spring_constant", m.spring_constant, limits::kStiffness},
                {"shear_constant", m.shear(), limits::kStiffness},
                {"bend_constant", m.bend(), limits::kStiffness},
                {"node_mass", m.node_mass, limits::kNodeMass},
                {"viscosity", m.viscosity, limits::kViscosity},
                {"friction", m.friction, limits::kFriction}};
  for (const auto& c : checks)
    if (!c.limit.contains(c.value))
      return std::string(c.name) + " " + show_number(c.value) + ", which " +
             c.limit.refusal(c.value);
  return std::nullopt;
}

}  // namespace neurocloth
