#pragma once
// The solver's result as JSON (docs/solver.md): openings (readable by `evaluate --openings`), open
// elements, per-sensor goals and predictions, error metrics, timings and the genetic history.
#include <nlohmann/json.hpp>

#include "scene/scene.h"
#include "solve/solver.h"

namespace fenestra {

nlohmann::json solve_result_json(const Scene& scene, const SolveResult& result);

}  // namespace fenestra
