#include "scene/sky_input.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>

#include "daylight/daylight.h"
#include "daylight/perez_all_weather.h"
#include "daylight/sky_matrix.h"
#include "daylight/weather_file.h"
#include "format/json_keys.h"
#include "scene/environment_map.h"
#include "scene/input_limits.h"
#include "scene/scene.h"
#include "util/quoted_text.h"

namespace fenestra {

using namespace scene_json;  // the path-aware readers
namespace fs = std::filesystem;

namespace {

// sky.resolution: [width, height] of a daylight sky's map, in pixels.
void parse_resolution(const ScenePath& sp, const json& r, int* width, int* height) {
  if (!r.is_array() || r.size() != 2) sp.fail("sky.resolution", "expected [width, height] in pixels, got " + quoted_json(r));
  *width = static_cast<int>(integer_in(sp, r[0], limits::kSkyWidth, limits::kSkyWidth.key));
  *height = static_cast<int>(integer_in(sp, r[1], limits::kSkyHeight, limits::kSkyHeight.key));
}

// The cumulative map of a climate sky averages thousands of hours (the occupied hours of a year:
// 3650 from 08:00 to 18:00): a coarser default than one day's map keeps it to about a second.
// 1.4 degree pixels still resolve the circumsolar brightening (it falls by a factor e over 8
// degrees or more); the suns are separate sources.
constexpr int kClimateMapWidth = 256, kClimateMapHeight = 128;

// A weather file named by sky.weather (relative to the scene file), read and checked whole.
std::shared_ptr<const WeatherData> read_sky_weather(const ScenePath& sp, const json& j, const fs::path& base,
                                                    Scene* scene) {
  if (!j.at("weather").is_string())
    sp.fail("sky.weather", "expected a file name (.epw or .wea), got " + quoted_json(j.at("weather")));
  const fs::path file = base / j.at("weather").get<std::string>();
  try {
    check_input_file(file.string(), "weather file", limits::kMaxWeatherFileBytes);
    auto weather = std::make_shared<const WeatherData>(read_weather(file.string()));
    scene->input_files.push_back(file.string());
    return weather;
  } catch (const std::invalid_argument& e) {
    sp.fail("sky.weather", e.what());
  }
}

// latitude and longitude (both or neither) and elevation, over a default place.
Place parse_place(const ScenePath& sp, const json& j, Place place) {
  if (j.contains("latitude") != j.contains("longitude"))
    sp.fail(j.contains("latitude") ? "sky.longitude" : "sky.latitude", "give latitude and longitude together");
  if (j.contains("latitude")) {
    place.latitude_deg = number_in(sp, j, "latitude", "sky", 0.0, -90.0, 90.0, " degrees");
    place.longitude_deg = number_in(sp, j, "longitude", "sky", 0.0, -180.0, 180.0, " degrees");
  }
  place.elevation_m =
      number_in(sp, j, "elevation", "sky", place.elevation_m, -limits::kMaxElevation, limits::kMaxElevation, " m");
  return place;
}

// A Perez sky's irradiance (W/m^2), at most the extraterrestrial normal irradiance of every date of
// the range: no irradiance at the ground can exceed it.
double perez_irradiance(const ScenePath& sp, const json& j, const std::string& name, const DaylightSettings& d) {
  const double v = number_in(sp, j, name, "sky", 0.0, 0.0, limits::kMaxIlluminance, " W/m^2");
  const int days = std::max(0, days_between(d.date, d.date_end));
  for (int k = 0; k <= days; ++k) {
    const LocalDate date = add_days(d.date, k);
    const double top = extraterrestrial_normal_irradiance(date.month, date.day);
    if (v > top)
      sp.fail("sky." + name, "must not exceed the extraterrestrial normal irradiance of " + to_string(date) + " (" +
                                 show(std::floor(top)) + " W/m^2), got " + quoted_json(j.at(name)));
  }
  return v;
}

// Settings of the daylight skies (preetham, cie_clear, cie_overcast, perez); see docs/sky.md.
DaylightSettings parse_daylight(const ScenePath& sp, const json& j, const std::string& type, const fs::path& base,
                                Scene* scene) {
  static const std::vector<std::string> kPlaceAndTime = {
      "type", "latitude", "longitude", "elevation", "utc_offset", "timezone", "date", "date_end", "start", "end",
      "time", "step_minutes", "ground_reflectance", "north_offset_deg", "resolution"};
  std::vector<std::string> known = kPlaceAndTime;
  if (type == "perez")
    known.insert(known.end(), {"weather", "direct_normal", "diffuse_horizontal", "dew_point"});
  else
    known.insert(known.end(), {"turbidity", "zenith_luminance", "horizontal_illuminance"});
  check_known_keys(sp, j, "sky", known);
  DaylightSettings d;
  d.model = type == "preetham"       ? DaylightSettings::Model::Preetham
            : type == "cie_clear"    ? DaylightSettings::Model::CieClear
            : type == "perez"        ? DaylightSettings::Model::Perez
                                     : DaylightSettings::Model::CieOvercast;
  const bool perez = d.model == DaylightSettings::Model::Perez;
  try {
    if (perez && j.contains("weather")) {
      for (const char* key : {"direct_normal", "diffuse_horizontal", "dew_point"})
        if (j.contains(key))
          sp.fail(std::string("sky.") + key, "give either weather or direct_normal and diffuse_horizontal, not both");
      d.weather = read_sky_weather(sp, j, base, scene);
    }
    if (d.model != DaylightSettings::Model::CieOvercast) {
      // A weather file gives the place and the clock; otherwise the scene must.
      const WeatherLocation* station = d.weather ? &d.weather->location : nullptr;
      for (const char* key : {"latitude", "longitude", "date"})
        if (!j.contains(key) && !(station && std::string(key) != "date"))
          sp.fail(std::string("sky.") + key, "a " + type + " sky needs it");
      Place fallback;
      if (station) fallback = {station->latitude_deg, station->longitude_deg, station->elevation_m};
      d.place = parse_place(sp, j, fallback);
      if (j.contains("timezone") && j.contains("utc_offset"))
        sp.fail("sky.timezone", "give either timezone or utc_offset, not both");
      if (j.contains("timezone")) {
        d.time_zone = TimeZone::named(text(sp, j, "timezone", "sky"));
      } else if (j.contains("utc_offset")) {
        d.time_zone = TimeZone::fixed(number(sp, j.at("utc_offset"), "sky.utc_offset"));
      } else if (station) {
        d.time_zone = TimeZone::fixed(station->time_zone_hours);  // the file's standard time
      } else {
        sp.fail("sky.utc_offset", "a " + type + " sky needs utc_offset (hours) or timezone (an IANA name)");
      }
      d.date = parse_date(text(sp, j, "date", "sky"));
      d.date_end = j.contains("date_end") ? parse_date(text(sp, j, "date_end", "sky")) : d.date;
      if (j.contains("time")) {
        if (j.contains("start") || j.contains("end")) sp.fail("sky.time", "give either time or start and end");
        d.start_minutes = d.end_minutes = parse_clock_minutes(text(sp, j, "time", "sky"));
      } else {
        if (j.contains("start")) d.start_minutes = parse_clock_minutes(text(sp, j, "start", "sky"));
        if (j.contains("end")) d.end_minutes = parse_clock_minutes(text(sp, j, "end", "sky"));
      }
      d.step_minutes = number_in(sp, j, "step_minutes", "sky", d.step_minutes, limits::kMinStepMinutes,
                                 limits::kMaxStepMinutes, " minutes");
      d.turbidity = number_or(sp, j, "turbidity", "sky", d.turbidity);
      d.north_offset_deg = number_in(sp, j, "north_offset_deg", "sky", 0.0, -limits::kMaxTurnDeg,
                                     limits::kMaxTurnDeg, " degrees");
    }
    if (perez && !d.weather) {
      if (!j.contains("direct_normal") || !j.contains("diffuse_horizontal"))
        sp.fail(j.contains("direct_normal") ? "sky.diffuse_horizontal" : "sky.direct_normal",
                "a perez sky needs direct_normal and diffuse_horizontal (W/m^2), or a weather file (weather)");
      d.direct_normal_w_m2 = perez_irradiance(sp, j, "direct_normal", d);
      d.diffuse_horizontal_w_m2 = perez_irradiance(sp, j, "diffuse_horizontal", d);
      d.dew_point_c = number_in(sp, j, "dew_point", "sky", d.dew_point_c, PerezAllWeatherSky::kMinDewPointC,
                                PerezAllWeatherSky::kMaxDewPointC, " deg C");
    }
    d.ground_reflectance = number_or(sp, j, "ground_reflectance", "sky", d.ground_reflectance);
    d.zenith_luminance = number_in(sp, j, "zenith_luminance", "sky", 0.0, 0.0, limits::kMaxRadiance, " cd/m^2");
    d.horizontal_illuminance =
        number_in(sp, j, "horizontal_illuminance", "sky", 0.0, 0.0, limits::kMaxIlluminance, " lux");
    if (d.zenith_luminance > 0.0 && d.horizontal_illuminance > 0.0)
      sp.fail("sky.zenith_luminance", "give either zenith_luminance or horizontal_illuminance, not both");
    if (d.model != DaylightSettings::Model::CieOvercast && d.horizontal_illuminance > 0.0)
      sp.fail("sky.horizontal_illuminance", "only a cie_overcast sky is scaled by its horizontal illuminance");
    if (j.contains("resolution")) parse_resolution(sp, j.at("resolution"), &d.width, &d.height);
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    if (what.rfind("scene '", 0) == 0) throw;
    sp.fail("sky", what);
  }
  return d;
}

// "occupied": ["HH:MM", "HH:MM"], local standard time, start before end.
void parse_occupied(const ScenePath& sp, const json& j, ClimateSettings* c) {
  const json& o = j.at("occupied");
  if (!o.is_array() || o.size() != 2 || !o[0].is_string() || !o[1].is_string())
    sp.fail("sky.occupied", "expected [\"HH:MM\", \"HH:MM\"] (local standard time), got " + quoted_json(o));
  try {
    c->occupied_start_hour = parse_clock_minutes(o[0].get<std::string>()) / 60.0;
    c->occupied_end_hour = parse_clock_minutes(o[1].get<std::string>()) / 60.0;
  } catch (const std::invalid_argument& e) {
    sp.fail("sky.occupied", e.what());
  }
  if (!(c->occupied_start_hour < c->occupied_end_hour))
    sp.fail("sky.occupied", "the start must come before the end on the same day, got " + quoted_json(o));
}

// A "climate" sky: the weather file's hourly sky matrix for annual studies, and, for everything
// else, the cumulative sky of its occupied hours (docs/sky.md, "Climate").
void parse_climate(const ScenePath& sp, const json& j, const fs::path& base, Scene* scene, Progress* progress) {
  check_known_keys(sp, j, "sky",
                   {"type", "weather", "latitude", "longitude", "elevation", "north_offset_deg", "ground_reflectance",
                    "patches", "occupied", "resolution"});
  if (!j.contains("weather")) sp.fail("sky.weather", "a climate sky needs a weather file (.epw or .wea)");
  auto climate = std::make_shared<Climate>();
  climate->weather = read_sky_weather(sp, j, base, scene);
  ClimateSettings& c = climate->settings;
  c = ClimateSettings::for_weather(*climate->weather);
  c.place = parse_place(sp, j, c.place);
  c.north_offset_deg =
      number_in(sp, j, "north_offset_deg", "sky", 0.0, -limits::kMaxTurnDeg, limits::kMaxTurnDeg, " degrees");
  c.ground_reflectance = number_in(sp, j, "ground_reflectance", "sky", c.ground_reflectance, 0.0, 1.0, "");
  if (j.contains("patches")) {
    const json& p = j.at("patches");
    if (!(p == 1 || p == 2 || p == 4))
      sp.fail("sky.patches", "must be 1 (Tregenza, 145 sky patches), 2 (577) or 4 (2305), got " + quoted_json(p));
    c.subdivision = p.get<int>();
  }
  if (j.contains("occupied")) parse_occupied(sp, j, &c);

  // The cumulative sky: a Perez sky over the occupied hours, each at its own instant.
  DaylightSettings d;
  d.model = DaylightSettings::Model::Perez;
  d.width = kClimateMapWidth, d.height = kClimateMapHeight;
  if (j.contains("resolution")) parse_resolution(sp, j.at("resolution"), &d.width, &d.height);
  std::shared_ptr<Daylight> daylight;
  try {
    climate->sky = std::make_shared<const SkyMatrix>(make_sky_matrix(*climate->weather, c, progress));
    d.place = c.place;
    d.time_zone = TimeZone::fixed(c.time_zone_hours);
    d.north_offset_deg = c.north_offset_deg;
    d.ground_reflectance = c.ground_reflectance;
    d.weather = climate->weather;
    d.weather_rows = occupied_hours(climate->sky->hours, c);
    if (d.weather_rows.empty())
      sp.fail("sky.occupied", "no hour of '" + quoted_path(c.weather_path) + "' lies in the occupied period");
    daylight = std::make_shared<Daylight>(make_daylight(d, progress));
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    if (what.rfind("scene '", 0) == 0) throw;
    sp.fail("sky", what);
  }
  scene->sky = std::make_shared<EnvironmentMap>(daylight->width, daylight->height, daylight->pixels, 1.0f, 0.0f,
                                                c.describe());
  scene->suns = SunLights(daylight->suns);
  scene->daylight = daylight;
  scene->climate = climate;
}

}  // namespace

void parse_sky(const ScenePath& sp, const json& j, const fs::path& base, Scene* scene, Progress* progress) {
  if (!j.is_object()) sp.fail("sky", "expected an object");
  check_misspelt(sp, j, "sky", "type");
  if (!j.contains("type")) {
    sp.fail("sky.type", "missing: give \"uniform\", \"envmap\", \"preetham\", \"cie_clear\", \"cie_overcast\", "
                        "\"perez\" or \"climate\"");
  }
  const std::string type = text(sp, j, "type", "sky");
  if (type == "uniform") {
    check_known_keys(sp, j, "sky", {"type", "radiance", "ground_radiance"});
    auto radiance = [&](const char* key, const Rgb& fallback) {
      if (!j.contains(key)) return fallback;
      const std::string name = std::string("sky.") + key;
      const Rgb l = colour(sp, j.at(key), name);
      if ((l < 0.0f).any()) sp.fail(name, "must not be negative");
      if ((l > static_cast<float>(limits::kMaxRadiance)).any())
        sp.fail(name, "must not exceed " + show(limits::kMaxRadiance) + " cd/m^2, got " + quoted_json(j.at(key)));
      return l;
    };
    const Rgb l = radiance("radiance", Rgb::Constant(1000.0f / kPi));
    scene->sky = std::make_shared<UniformSky>(l, radiance("ground_radiance", l));
    return;
  }
  if (type == "envmap") {
    check_known_keys(sp, j, "sky", {"type", "file", "scale", "rotation_deg"});
    if (!j.contains("file") || !j.at("file").is_string()) sp.fail("sky.file", "an envmap sky needs a \"file\"");
    const fs::path file = base / j.at("file").get<std::string>();
    const float scale = static_cast<float>(number_in(sp, j, "scale", "sky", 1.0, 0.0, limits::kMaxRadiance, ""));
    const float rotation = static_cast<float>(
        number_in(sp, j, "rotation_deg", "sky", 0.0, -limits::kMaxTurnDeg, limits::kMaxTurnDeg, " degrees"));
    try {
      check_input_file(file.string(), "environment map", limits::kMaxImageFileBytes);
      scene->sky = EnvironmentMap::load(file.string(), scale, rotation);
      scene->input_files.push_back(file.string());
    } catch (const std::invalid_argument& e) {
      sp.fail("sky.file", e.what());
    }
    return;
  }
  if (type == "climate") {
    parse_climate(sp, j, base, scene, progress);
    return;
  }
  if (type == "preetham" || type == "cie_clear" || type == "cie_overcast" || type == "perez") {
    const DaylightSettings settings = parse_daylight(sp, j, type, base, scene);
    std::shared_ptr<Daylight> daylight;
    try {
      daylight = std::make_shared<Daylight>(make_daylight(settings, progress));
    } catch (const std::invalid_argument& e) {
      sp.fail("sky", e.what());
    }
    scene->sky = std::make_shared<EnvironmentMap>(daylight->width, daylight->height, daylight->pixels, 1.0f, 0.0f,
                                                  settings.describe());
    scene->suns = SunLights(daylight->suns);
    scene->daylight = daylight;
    return;
  }
  sp.fail("sky.type", "unknown sky type '" + quoted_text(type) + "'" +
                          did_you_mean(type, {"uniform", "envmap", "preetham", "cie_clear", "cie_overcast", "perez",
                                              "climate"}) +
                          " (uniform, envmap, preetham, cie_clear, cie_overcast, perez or climate)");
}

}  // namespace fenestra
