#pragma once
// RESULT.json: what `simulate` and `relax` write. Written to a temporary file
// beside the target and renamed, so a failure never leaves a partial file.
#include <nlohmann/json.hpp>

#include <string>

#include "json_writer.h"
#include "simulation.h"

namespace neurocloth {

// status, time, steps, energy, positions, velocities... of a simulation.
nlohmann::json simulation_result(const Simulation& sim, const std::string& scene_path,
                                 double wall_seconds);
// Positions and velocities as arrays of [x, y, z].
nlohmann::json state_json(const ClothState& s, bool velocities);
nlohmann::json energy_json(const Energy& e);

}  // namespace neurocloth
