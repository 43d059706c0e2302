#pragma once
// A sky in figures: its map as the tracer sees it, the illuminance it gives an unobstructed
// horizontal surface, and what it says against itself (a dark sky, a weather file's warnings).
// The solver's daylight-factor goals and `fenestra sky` read them for a scene's sky, suns and
// daylight build (`daylight`: null for a sky that is not a daylight or climate sky).
#include <string>
#include <vector>

#include "daylight/daylight.h"
#include "daylight/sky.h"
#include "daylight/sun_lights.h"

namespace fenestra {

struct SkyImage {
  int width = 0, height = 0;
  std::vector<Rgb> pixels;  // row-major, top row = zenith, Blender's equirectangular convention; cd/m^2
};

// A daylight sky's averaged map as built; other skies rasterised at pixel centres.
SkyImage sky_image(const Sky& sky, const Daylight* daylight, int width = 1024, int height = 512);
// The sky's own horizontal illuminance (RGB): a daylight sky's as built, others' from their map.
Rgb sky_horizontal(const Sky& sky, const Daylight* daylight);
// Illuminance on an unobstructed horizontal surface from the sky and the sun (lux for a sky in
// cd/m^2; a daylight sky's interval mean).
double unobstructed_horizontal_illuminance(const Sky& sky, const SunLights& suns, const Daylight* daylight);
// When a daylight sky gives no light at all (the sun below the horizon at every time step: polar
// night, or an interval at night), a sentence naming the sky, place and dates; otherwise "".
std::string dark_sky_warning(const Sky& sky, const Daylight* daylight);
// What the sky's weather file says against itself or the scene (its own warnings, a scene place
// far from its station), one sentence each; empty for other skies.
std::vector<std::string> sky_warnings(const Daylight* daylight);

}  // namespace fenestra
