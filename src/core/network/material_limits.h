#pragma once
// A material's numbers against the physical limits (io/physical_limits.h): the
// check every material from a rule base or a live change passes before it
// reaches a network.
#include <optional>
#include <string>

#include "core/network/material.h"

namespace neurocloth {

// "node_mass 5e-324 kg: must be in ..." for the first parameter of `m` outside
// its limit, or nothing. For materials that come from a rule base.
std::optional<std::string> material_outside_limits(const Material& m);

}  // namespace neurocloth
