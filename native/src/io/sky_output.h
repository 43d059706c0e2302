#pragma once
// What `fenestra sky` shows of a scene's sky: the environment map the tracer uses, and a summary
// (horizontal illuminances, the sun list).
#include <nlohmann/json.hpp>

#include <string>
#include <vector>

#include "scene/scene.h"
#include "daylight/sky_figures.h"

namespace fenestra {

// .exr or .hdr (any format OpenImageIO writes from the extension); all or nothing.
void write_sky_image(const std::string& path, const SkyImage& image);

// {"description", "horizontal_illuminance": {"sky", "sun", "total"} (lux), "suns": [...], ...}
nlohmann::json sky_summary(const Scene& scene);
// Human-readable form of the summary, for the command line.
std::string sky_report(const nlohmann::json& summary);

}  // namespace fenestra
