#pragma once
// The scene file's "materials" section: each material's type and its optical parameters.
#include <nlohmann/json_fwd.hpp>

#include <string>

#include "scene/material.h"
#include "scene/scene_json.h"

namespace fenestra {

// materials.NAME: diffuse (the default), glossy or glass, with their ranges checked.
Material parse_material(const scene_json::ScenePath& sp, const std::string& name, const nlohmann::json& j);

}  // namespace fenestra
