#pragma once
// The arithmetic of the spring layer's force neurons (SolverSettings::precision).
// Only the force neurons change: the state, the node sums and every integrator
// stay double (docs/network.md, "Float springs").
#include <optional>
#include <string>

namespace neurocloth {

// float64: the default, and what learning and the paper's runs use. float32:
// relative positions and velocities taken in double and rounded to float, the
// length, 1/length and force in float, the force added to the double sums.
enum class SpringPrecision { float64, float32 };

// The scene's names: "double", "float".
inline const char* to_string(SpringPrecision p) {
  return p == SpringPrecision::float32 ? "float" : "double";
}

inline std::optional<SpringPrecision> parse_precision(const std::string& name) {
  if (name == "double") return SpringPrecision::float64;
  if (name == "float") return SpringPrecision::float32;
  return std::nullopt;
}

inline constexpr const char* kPrecisionNames = "double, float";

}  // namespace neurocloth
