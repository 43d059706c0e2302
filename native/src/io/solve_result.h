#pragma once
// The solver's result as JSON (docs/solver.md): openings (readable by `evaluate --openings`), open
// elements, per-sensor goals and predictions, error metrics, timings and the genetic history.
#include <nlohmann/json.hpp>

#include "scene/scene.h"
#include "solve/solver.h"

namespace fenestra {

nlohmann::json solve_result_json(const Scene& scene, const SolveResult& result);
// The constraints that limit something (lengths in meters), the catalogue's name, and "automatic":
// the keys that took their automatic value. As the result's settings.constraints.
nlohmann::json constraints_json(const OpeningConstraints& constraints);

}  // namespace fenestra
