#pragma once
// A random session for the window's soak (viewer_soak): timed input from a
// seed — moves, drags, clicks, pins, wheel, keys, parameter values in range,
// at the extremes and far outside, unknown names, scene and rule-base loads
// (good, broken and missing files), resizes (minimised included), probes and
// screenshots — as a script in the format of docs/viewer.md. The same seed
// gives the same script.
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace neurocloth {

struct SoakFiles {
  std::vector<std::string> scenes;  // what "load" picks from (broken and missing ones too)
  std::vector<std::string> rules;   // what "rules" picks from
  std::string screenshot_prefix;    // screenshots go to PREFIX<n>.png
};

// Events from t = 0 to `seconds` (script time), ending with a quit at `seconds`.
nlohmann::json random_soak_script(std::mt19937_64& rng, double seconds, const SoakFiles& files);

}  // namespace neurocloth
