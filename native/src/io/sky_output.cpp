#include "io/sky_output.h"

#include <cstdio>
#include <ctime>
#include <sstream>

#include "daylight/daylight.h"
#include "format/image_writer.h"
#include "daylight/sky_figures.h"

namespace fenestra {

void write_sky_image(const std::string& path, const SkyImage& image) {
  std::vector<float> flat;
  flat.reserve(image.pixels.size() * 3);
  for (const Rgb& p : image.pixels) flat.insert(flat.end(), {p[0], p[1], p[2]});
  write_image(path, image.width, image.height, 3, flat);
}

namespace {

nlohmann::json rgb(const Rgb& c) { return {c[0], c[1], c[2]}; }

std::string iso_utc(double seconds) {
  const std::time_t t = static_cast<std::time_t>(std::llround(seconds));
  std::tm tm{};
  gmtime_r(&t, &tm);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return text;
}

}  // namespace

nlohmann::json sky_summary(const Scene& scene) {
  nlohmann::json j;
  j["description"] = scene.sky->to_string();
  const Rgb sky = sky_horizontal(*scene.sky, scene.daylight.get());
  const Rgb sun = scene.suns.horizontal_illuminance();
  j["horizontal_illuminance"] = {{"sky", luminance(sky)}, {"sun", luminance(sun)}, {"total", luminance(sky + sun)}};
  j["horizontal_illuminance_rgb"] = {{"sky", rgb(sky)}, {"sun", rgb(sun)}};
  if (scene.daylight) {
    const Daylight& d = *scene.daylight;
    j["map"] = {{"width", d.width}, {"height", d.height}};
    j["steps"] = d.steps;
    j["steps_with_sun"] = d.steps_with_sun;
    j["analytic_sky_horizontal_illuminance"] = luminance(d.analytic_sky_horizontal);
    j["build_seconds"] = d.seconds;
    if (!dark_sky_warning(*scene.sky, scene.daylight.get()).empty())
      j["warning"] = "the sun is below the horizon at every time step: the sky is dark";
    if (!d.warnings.empty()) j["warnings"] = d.warnings;
  }
  j["suns"] = nlohmann::json::array();
  for (const SunLight& s : scene.suns.suns()) {
    const Rgb instant = s.normal_illuminance / static_cast<float>(s.weight);
    j["suns"].push_back({{"utc", iso_utc(s.utc_seconds)},
                         {"direction", {s.direction.x(), s.direction.y(), s.direction.z()}},
                         {"zenith_deg", s.zenith_deg},
                         {"azimuth_deg", s.azimuth_deg},
                         {"weight", s.weight},
                         {"normal_illuminance", luminance(instant)},
                         {"normal_illuminance_rgb", rgb(instant)}});
  }
  return j;
}

std::string sky_report(const nlohmann::json& j) {
  std::ostringstream s;
  char line[256];
  s << j["description"].get<std::string>() << "\n";
  const auto& e = j["horizontal_illuminance"];
  std::snprintf(line, sizeof line, "horizontal illuminance, interval mean: sky %.0f lx + sun %.0f lx = %.0f lx\n",
                e["sky"].get<double>(), e["sun"].get<double>(), e["total"].get<double>());
  s << line;
  if (j.contains("steps")) {
    std::snprintf(line, sizeof line, "%d time steps, %d with the sun up; map built in %.2f s\n", j["steps"].get<int>(),
                  j["steps_with_sun"].get<int>(), j["build_seconds"].get<double>());
    s << line;
  }
  if (j.contains("warning")) s << "warning: " << j["warning"].get<std::string>() << "\n";
  if (j.contains("warnings"))
    for (const auto& w : j["warnings"]) s << "warning: " << w.get<std::string>() << "\n";
  if (!j["suns"].empty()) {
    s << "suns (one per step; normal illuminance at that instant):\n"
      << "  UTC                   zenith  azimuth   weight  normal lx\n";
    // A climate's thousands of suns: the first ones, the rest in the --json summary.
    constexpr size_t kListed = 48;
    size_t listed = 0;
    for (const auto& sun : j["suns"]) {
      if (++listed > kListed) {
        s << "  ... and " << j["suns"].size() - kListed << " more (all in the --json summary)\n";
        break;
      }
      std::snprintf(line, sizeof line, "  %s  %6.2f  %7.2f  %7.4f  %9.0f\n", sun["utc"].get<std::string>().c_str(),
                    sun["zenith_deg"].get<double>(), sun["azimuth_deg"].get<double>(), sun["weight"].get<double>(),
                    sun["normal_illuminance"].get<double>());
      s << line;
    }
  }
  return s.str();
}

}  // namespace fenestra
