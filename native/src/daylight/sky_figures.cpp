#include "daylight/sky_figures.h"

#include "math/equirect.h"

namespace fenestra {

SkyImage sky_image(const Sky& sky, const Daylight* daylight, int width, int height) {
  SkyImage image;
  if (daylight) {
    image.width = daylight->width;
    image.height = daylight->height;
    image.pixels = daylight->pixels;
    return image;
  }
  image.width = width;
  image.height = height;
  image.pixels.resize(static_cast<size_t>(width) * height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      image.pixels[static_cast<size_t>(y) * width + x] =
          sky.radiance(equirect_direction(Vec2((x + 0.5f) / width, (y + 0.5f) / height)));
  return image;
}

Rgb sky_horizontal(const Sky& sky, const Daylight* daylight) {
  if (daylight) return daylight->sky_horizontal;
  const SkyImage image = sky_image(sky, daylight, 1024, 512);
  return map_horizontal_illuminance(image.width, image.height, image.pixels);
}

double unobstructed_horizontal_illuminance(const Sky& sky, const SunLights& suns, const Daylight* daylight) {
  return luminance(sky_horizontal(sky, daylight) + suns.horizontal_illuminance());
}

std::vector<std::string> sky_warnings(const Daylight* daylight) {
  return daylight ? daylight->warnings : std::vector<std::string>{};
}

std::string dark_sky_warning(const Sky& sky, const Daylight* daylight) {
  if (!daylight) return "";
  const Daylight& d = *daylight;
  if (!(d.steps_with_sun == 0 && d.steps > 0 && d.suns.empty() && luminance(d.sky_horizontal) == 0.0f)) return "";
  return sky.to_string() + ": the sun is below the horizon at every time step (polar night, or an interval "
         "at night), so the sky gives no light and every value is 0";
}

}  // namespace fenestra
