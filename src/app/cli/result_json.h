#pragma once
// RESULT.json: what `simulate` and `relax` write. Written to a temporary file
// beside the target and renamed, so a failure never leaves a partial file.
#include <nlohmann/json.hpp>

#include <string>
#include <vector>

#include "core/io/json_writer.h"
#include "core/scene/scene.h"
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

// What a fabric lab would read off `state`, for each test the scene is: the
// drape test's (ISO 9073-9, tradeoff/drape_shape.h) when it has a support to
// drape over, RESULT.json's "drape" {"coefficient", "nodes", "support"} (the
// flat cloth is the scene's at its start); the cantilever's (ASTM D1388,
// core/scene/cantilever.h) when it is one, "cantilever" {"chord_angle"
// (degrees), "overhang", "bending_length", "peirce_length" (m),
// "bending_rigidity" (N m)}. Each with the line that says it.
struct FabricTestReading {
  std::string key;  // "drape", "cantilever"
  nlohmann::json json;
  std::string line;
};
std::vector<FabricTestReading> fabric_test_readings(const Scene& scene, const ClothState& state);

}  // namespace neurocloth
