#pragma once
// RESULT.json: what `simulate` and `relax` write. Written to a temporary file
// beside the target and renamed, so a failure never leaves a partial file.
#include <nlohmann/json.hpp>

#include <optional>
#include <string>

#include "simulation.h"

namespace neurocloth {

// status, time, steps, energy, positions, velocities... of a simulation.
nlohmann::json simulation_result(const Simulation& sim, const std::string& scene_path,
                                 double wall_seconds);
// Positions and velocities as arrays of [x, y, z].
nlohmann::json state_json(const ClothState& s, bool velocities);
nlohmann::json energy_json(const Energy& e);

// The first number in `doc` that is NaN or infinite, as a path ("energy.total",
// "positions[3][1]"), or nothing.
std::optional<std::string> first_non_finite(const nlohmann::json& doc, const std::string& at = "");

// Throws std::runtime_error naming the path when it cannot be written, or when
// a number in `doc` is not finite (nothing is written then).
void write_json_atomically(const std::string& path, const nlohmann::json& doc);

}  // namespace neurocloth
