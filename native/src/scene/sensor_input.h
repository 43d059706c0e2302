#pragma once
// The scene file's "sensors" section and the per-sensor and uniform goals of its "goals" section
// (the climate goals: scene/climate_goals.h).
#include <nlohmann/json_fwd.hpp>

#include "scene/scene.h"
#include "scene/scene_json.h"

namespace fenestra {

// Points (in the scene's local frame), normals, goals, goal units, weights.
Sensors parse_sensors(const scene_json::ScenePath& sp, const nlohmann::json& j, const SiteFrame& frame);
// The "goals" section: per-sensor goals (an alternative to sensors.goals), weights, and uniform
// levels over sets of sensors.
void parse_goals(const scene_json::ScenePath& sp, const nlohmann::json& j, Sensors* s);
// Goals must be reachable quantities: not negative, and at most 1 (all open) when normalized.
void check_goals(const scene_json::ScenePath& sp, const Sensors& s);

}  // namespace fenestra
