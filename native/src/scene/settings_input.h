#pragma once
// The scene file's "solver" settings (its constraints: scene/constraint_input.h) and "render"
// settings.
#include <nlohmann/json_fwd.hpp>

#include "scene/scene.h"
#include "scene/scene_json.h"

namespace fenestra {

// Null: the defaults.
SolverSettings parse_solver(const scene_json::ScenePath& sp, const nlohmann::json& j);
RenderSettings parse_render(const scene_json::ScenePath& sp, const nlohmann::json& j);

}  // namespace fenestra
