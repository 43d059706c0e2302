#pragma once
// An annual study written out (docs/annual.md): its summary (settings, space and per-sensor
// metrics) as JSON and its arrays as an .npz.
#include <nlohmann/json.hpp>
#include <string>
#include <utility>

#include "annual/annual_study.h"
#include "scene/scene.h"

namespace fenestra {

// The study's summary (settings, space and per-sensor metrics) and its arrays as an .npz:
// OUT.npz and OUT.json, written together or not at all (write_annual). Returns both paths.
nlohmann::json annual_json(const AnnualStudy& study);
// Its "space" object: the area-weighted metrics, sDA levels, UDI bands and EN 17037 levels.
nlohmann::json annual_space_json(const AnnualMetrics& metrics);
std::pair<std::string, std::string> write_annual(const Scene& scene, const AnnualStudy& study, const std::string& out);

}  // namespace fenestra
