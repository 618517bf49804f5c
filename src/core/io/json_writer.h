#pragma once
// Writing a JSON document (RESULT.json, the window's report): never a NaN or
// an infinity where a reader expects a number (JSON has neither; the library
// would write null), and never half a file.
#include <nlohmann/json.hpp>

#include <optional>
#include <string>

namespace neurocloth {

// The first number in `doc` that is NaN or infinite, as a path ("energy.total",
// "positions[3][1]"), or nothing.
std::optional<std::string> first_non_finite(const nlohmann::json& doc, const std::string& at = "");

// Throws std::runtime_error naming the path when it cannot be written, or when
// a number in `doc` is not finite (nothing is written then). Written through
// a temporary file renamed into place (write_file_atomically).
void write_json_atomically(const std::string& path, const nlohmann::json& doc);

}  // namespace neurocloth
