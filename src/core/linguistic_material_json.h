#pragma once
// Reading {"rules": FCL, "inputs": {...}} out of a JSON document (a scene's
// material block or a preset file). Internal to the core: it exposes nlohmann.
#include <nlohmann/json.hpp>

#include "fuzzy_material.h"
#include "json_fields.h"

namespace neurocloth {

LinguisticMaterial read_linguistic_material(const JsonFields& in, const nlohmann::json& m,
                                            const std::string& field);

}  // namespace neurocloth
