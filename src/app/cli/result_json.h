#pragma once
// RESULT.json: what `simulate` and `relax` write. Written to a temporary file
// beside the target and renamed, so a failure never leaves a partial file.
#include <nlohmann/json.hpp>

#include <string>

#include "core/io/json_writer.h"
#include "core/simulation/simulation.h"

namespace neurocloth {

// status, time, steps, energy, positions, velocities... of a simulation whose
// nodes are the file's vertices as `numbering` says (the scene's topology's).
nlohmann::json simulation_result(const Simulation& sim, const NodeNumbering& numbering,
                                 const std::string& scene_path, double wall_seconds);
// Positions or velocities as arrays of [x, y, z], in the file's vertex order:
// entry k is the file's vertex k + 1 whatever order the nodes are in.
nlohmann::json state_json(const ClothState& s, const NodeNumbering& numbering, bool velocities);
nlohmann::json energy_json(const Energy& e);

}  // namespace neurocloth
