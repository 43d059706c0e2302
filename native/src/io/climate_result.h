#pragma once
// The solve result's "climate" object (docs/outputs.md): each climate goal with its figure from
// the path records and with real cutters, the space metrics and per-sensor DA, mean and ASE hours.
#include <nlohmann/json.hpp>

#include "scene/scene.h"
#include "solve/climate_design.h"

namespace fenestra {

nlohmann::json climate_result_json(const Scene& scene, const ClimateOutcome& climate);

}  // namespace fenestra
