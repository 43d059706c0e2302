#pragma once
// A scene's sky in figures: its map as the tracer sees it, the illuminance it gives an
// unobstructed horizontal surface, and what it says against itself (a dark sky, a weather file's
// warnings). The solver's daylight-factor goals and `fenestra sky` read them.
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
// The sky's own horizontal illuminance (RGB): a daylight sky's as built, others' from their map.
Rgb sky_horizontal(const Scene& scene);
// Illuminance on an unobstructed horizontal surface from the sky and the sun (lux for a sky in
// cd/m^2; a daylight sky's interval mean).
double unobstructed_horizontal_illuminance(const Scene& scene);
// When a daylight sky gives no light at all (the sun below the horizon at every time step: polar
// night, or an interval at night), a sentence naming the sky, place and dates; otherwise "".
std::string dark_sky_warning(const Scene& scene);
// What the sky's weather file says against itself or the scene (its own warnings, a scene place
// far from its station), one sentence each; empty for other skies.
std::vector<std::string> sky_warnings(const Scene& scene);

}  // namespace fenestra
