#include "physical_limits.h"

#include <cstdio>

namespace neurocloth {

std::string Limit::refusal(double got) const {
  char buf[96];
  std::snprintf(buf, sizeof buf, "must be in [%g, %g]%s%s (got %g): ", low, high, *unit ? " " : "",
                unit, got);
  return buf + std::string(meaning);
}

std::string show_number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

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
