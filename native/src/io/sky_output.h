#pragma once
// What `fenestra sky` shows of a scene's sky: the environment map the tracer uses, and a summary
// (horizontal illuminances, the sun list).
#include <nlohmann/json.hpp>

#include <string>
#include <vector>

#include "scene/scene.h"

namespace fenestra {

struct SkyImage {
  int width = 0, height = 0;
  std::vector<Rgb> pixels;  // row-major, top row = zenith, Blender's equirectangular convention; cd/m^2
};

// A daylight sky's averaged map as built; other skies rasterised at pixel centres.
SkyImage sky_image(const Scene& scene, int width = 1024, int height = 512);
// .exr or .hdr (any format OpenImageIO writes from the extension); all or nothing.
void write_sky_image(const std::string& path, const SkyImage& image);

// {"description", "horizontal_illuminance": {"sky", "sun", "total"} (lux), "suns": [...], ...}
nlohmann::json sky_summary(const Scene& scene);
// Illuminance on an unobstructed horizontal surface from the sky and the sun (lux for a sky in
// cd/m^2; a daylight sky's interval mean).
double unobstructed_horizontal_illuminance(const Scene& scene);
// When a daylight sky gives no light at all (the sun below the horizon at every time step: polar
// night, or an interval at night), a sentence naming the sky, place and dates; otherwise "".
std::string dark_sky_warning(const Scene& scene);
// What the sky's weather file says against itself or the scene (its own warnings, a scene place
// far from its station), one sentence each; empty for other skies.
std::vector<std::string> sky_warnings(const Scene& scene);
// Human-readable form of the summary, for the command line.
std::string sky_report(const nlohmann::json& summary);

}  // namespace fenestra
