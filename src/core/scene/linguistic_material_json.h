#pragma once
// Reading {"rules": FCL, "inputs": {...}} out of a JSON document (a scene's
// material block or a preset file). Internal to the core: it exposes nlohmann.
#include <nlohmann/json.hpp>

#include "core/io/json_fields.h"
#include "core/scene/fuzzy_material.h"

namespace neurocloth {

LinguisticMaterial read_linguistic_material(const JsonFields& in, const nlohmann::json& m,
                                            const std::string& field);

}  // namespace neurocloth
