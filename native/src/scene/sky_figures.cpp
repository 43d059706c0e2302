#include "scene/sky_figures.h"

#include "daylight/daylight.h"

namespace fenestra {

SkyImage sky_image(const Scene& scene, int width, int height) {
  SkyImage image;
  if (scene.daylight) {
    image.width = scene.daylight->width;
    image.height = scene.daylight->height;
    image.pixels = scene.daylight->pixels;
    return image;
  }
  image.width = width;
  image.height = height;
  image.pixels.resize(static_cast<size_t>(width) * height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      image.pixels[static_cast<size_t>(y) * width + x] =
          scene.sky->radiance(equirect_direction(Vec2((x + 0.5f) / width, (y + 0.5f) / height)));
  return image;
}

Rgb sky_horizontal(const Scene& scene) {
  if (scene.daylight) return scene.daylight->sky_horizontal;
  const SkyImage image = sky_image(scene, 1024, 512);
  return map_horizontal_illuminance(image.width, image.height, image.pixels);
}

double unobstructed_horizontal_illuminance(const Scene& scene) {
  return luminance(sky_horizontal(scene) + scene.suns.horizontal_illuminance());
}

std::vector<std::string> sky_warnings(const Scene& scene) {
  return scene.daylight ? scene.daylight->warnings : std::vector<std::string>{};
}

std::string dark_sky_warning(const Scene& scene) {
  if (!scene.daylight) return "";
  const Daylight& d = *scene.daylight;
  if (!(d.steps_with_sun == 0 && d.steps > 0 && d.suns.empty() && luminance(d.sky_horizontal) == 0.0f)) return "";
  return scene.sky->to_string() + ": the sun is below the horizon at every time step (polar night, or an interval "
         "at night), so the sky gives no light and every value is 0";
}

}  // namespace fenestra
