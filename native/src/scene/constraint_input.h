#pragma once
// The scene file's "solver.constraints" and "solver.panel_constraints": what an opening may be,
// with its window catalogue (docs/solver.md).
#include <nlohmann/json_fwd.hpp>

#include <string>

#include "scene/opening_constraints.h"
#include "scene/scene.h"
#include "scene/scene_json.h"

namespace fenestra {

// "solver.constraints" (read at `key`): lengths in meters, areas in m^2. The keys not given take
// their automatic values (automatic_constraints(), with `climate` goals among them) unless
// "automatic" is false; an automatic value that contradicts the given ones yields to them.
OpeningConstraints parse_constraints(const scene_json::ScenePath& sp, const nlohmann::json& j, double element_size,
                                     const std::string& key, bool climate = false);
// "solver.panel_constraints": [{"materials": [...], "groups": [...], "constraints": {...}}]: on the
// panels whose material or a face's group is listed, these keys replace the global constraints'
// (scene->solver.constraints.per_panel).
void apply_panel_constraints(const scene_json::ScenePath& sp, const nlohmann::json& solver, Scene* scene);

}  // namespace fenestra
