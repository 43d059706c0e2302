#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <stdexcept>

#include "daylight/daylight.h"
#include "daylight/perez_all_weather.h"
#include "daylight/sky_matrix.h"
#include "daylight/weather_file.h"
#include "format/json_input.h"
#include "format/json_keys.h"
#include "scene/bsdf.h"
#include "scene/input_limits.h"
#include "scene/scene.h"
#include "util/quoted_text.h"
#include "util/whole_file.h"

namespace fenestra {

using nlohmann::json;
namespace fs = std::filesystem;

namespace {

class ScenePath {
 public:
  explicit ScenePath(std::string source) : source_(std::move(source)) {}
  [[noreturn]] void fail(const std::string& key, const std::string& message) const {
    throw std::invalid_argument("scene '" + source_ + "': " + key + ": " + message);
  }
  const std::string& source() const { return source_; }

 private:
  std::string source_;
};

// Refuses a key of `obj` (the section `key`, "" at the top level) that is not in `known`, naming
// the closest known one. Each section lists its keys where it reads them.
void check_known_keys(const ScenePath& sp, const json& obj, const std::string& key,
                      const std::vector<std::string>& known) {
  if (const auto unknown = find_unknown_key(obj, known))
    sp.fail((key.empty() ? "" : key + ".") + quoted_text(unknown->key), unknown->message);
}

// When `name` (a key that chooses which others apply, such as "type") is missing, a key one typo
// away from it is named as such, rather than as unknown to the default it then falls back on.
void check_misspelt(const ScenePath& sp, const json& obj, const std::string& key, const std::string& name) {
  if (!obj.is_object() || obj.contains(name)) return;
  for (const auto& item : obj.items())
    if (closest_word(item.key(), {name}) == name)
      sp.fail(key + "." + quoted_text(item.key()), "unknown key; did you mean `" + name + "`?");
}

double number(const ScenePath& sp, const json& j, const std::string& key) {
  if (!j.is_number()) sp.fail(key, "expected a number, got " + quoted_json(j));
  const double v = j.get<double>();
  if (!std::isfinite(v)) sp.fail(key, "must be finite");
  return v;
}

double number_or(const ScenePath& sp, const json& obj, const std::string& name, const std::string& key, double fallback) {
  return obj.contains(name) ? number(sp, obj.at(name), key + "." + name) : fallback;
}

std::string show(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

// obj[name] (or the fallback) within [lo, hi], `unit` for the message (e.g. " m").
double number_in(const ScenePath& sp, const json& obj, const std::string& name, const std::string& key,
                 double fallback, double lo, double hi, const std::string& unit) {
  if (!obj.contains(name)) return fallback;
  const double v = number(sp, obj.at(name), key + "." + name);
  if (!(v >= lo && v <= hi))
    sp.fail(key + "." + name, "must lie in [" + show(lo) + ", " + show(hi) + "]" + unit + ", got " + quoted_json(obj.at(name)));
  return v;
}

// A whole number within `range`, checked before it is converted to the integer it lands in.
long long integer_in(const ScenePath& sp, const json& j, const IntegerRange& range, const std::string& key) {
  const double v = number(sp, j, key);
  if (v != std::floor(v) || v < static_cast<double>(range.lo) || v > static_cast<double>(range.hi))
    sp.fail(key, range.requirement() + ", got " + quoted_json(j));
  return static_cast<long long>(v);
}

std::string text_or(const ScenePath& sp, const json& obj, const std::string& name, const std::string& key,
                    const std::string& fallback) {
  if (!obj.contains(name)) return fallback;
  if (!obj.at(name).is_string()) sp.fail(key + "." + name, "expected a string, got " + quoted_json(obj.at(name)));
  return obj.at(name).get<std::string>();
}

Rgb colour(const ScenePath& sp, const json& j, const std::string& key) {
  Rgb c;
  if (j.is_number())
    c = Rgb::Constant(static_cast<float>(number(sp, j, key)));
  else if (j.is_array() && j.size() == 3)
    c = Rgb(number(sp, j[0], key), number(sp, j[1], key), number(sp, j[2], key));
  else
    sp.fail(key, "expected a number or [r, g, b], got " + quoted_json(j));
  if (!c.isFinite().all()) sp.fail(key, "is too large for a float (beyond 3.4e38), got " + quoted_json(j));
  return c;
}

// A position in meters, finite and within +-limits::kMaxCoordinate, read in double and returned in
// the scene's local frame (within +-limits::kMaxLocalCoordinate of its origin).
Vec3 point(const ScenePath& sp, const json& j, const std::string& key, const SiteFrame& frame) {
  if (!j.is_array() || j.size() != 3) sp.fail(key, "expected [x, y, z], got " + quoted_json(j));
  const double x = number(sp, j[0], key), y = number(sp, j[1], key), z = number(sp, j[2], key);
  if (!coordinate_in_range(x) || !coordinate_in_range(y) || !coordinate_in_range(z))
    sp.fail(key, "coordinates " + coordinate_requirement() + ", got " + quoted_json(j));
  const Vec3d site(x, y, z);
  if (!local_coordinates_in_range(frame.to_local_exact(site))) sp.fail(key, quoted_json(j) + " " + local_range_problem(frame.origin));
  return frame.to_local(site);
}

// A direction, normalized in double precision: components within +-limits::kMaxNormalComponent, not zero.
Vec3 direction(const ScenePath& sp, const json& j, const std::string& key) {
  if (!j.is_array() || j.size() != 3) sp.fail(key, "expected [x, y, z], got " + quoted_json(j));
  const double x = number(sp, j[0], key), y = number(sp, j[1], key), z = number(sp, j[2], key);
  if (Vec3d(x, y, z).cwiseAbs().maxCoeff() > limits::kMaxNormalComponent)
    sp.fail(key, "components of a normal must lie within +-" + show(limits::kMaxNormalComponent) + ", got " + quoted_json(j));
  const double n = std::sqrt(x * x + y * y + z * z);
  if (!(n > 1e-6)) sp.fail(key, "a normal must not be zero (length at least 1e-6), got " + quoted_json(j));
  return Vec3(x / n, y / n, z / n);
}

std::vector<std::string> names(const ScenePath& sp, const json& obj, const std::string& name, const std::string& key) {
  std::vector<std::string> out;
  if (!obj.contains(name)) return out;
  const json& j = obj.at(name);
  if (!j.is_array()) sp.fail(key + "." + name, "expected a list of names");
  for (const auto& e : j) {
    if (!e.is_string()) sp.fail(key + "." + name, "expected names, got " + quoted_json(e));
    out.push_back(e.get<std::string>());
  }
  return out;
}

void check_range(const ScenePath& sp, const Rgb& c, float lo, float hi, const std::string& key) {
  if ((c < lo).any() || (c > hi).any()) {
    std::ostringstream s;
    s << "must lie in [" << lo << ", " << hi << "], got [" << c.transpose() << "]";
    sp.fail(key, s.str());
  }
}

Material parse_material(const ScenePath& sp, const std::string& name, const json& j) {
  const std::string key = "materials." + quoted_text(name);
  if (!j.is_object()) sp.fail(key, "expected an object");
  Material m;
  m.name = name;
  check_misspelt(sp, j, key, "type");
  const std::string type = text_or(sp, j, "type", key, "diffuse");
  if (type == "diffuse") check_known_keys(sp, j, key, {"type", "reflectance"});
  if (type == "glossy") check_known_keys(sp, j, key, {"type", "reflectance", "roughness", "metallic"});
  if (type == "glass") check_known_keys(sp, j, key, {"type", "transmittance", "ior", "kind"});
  if (j.contains("reflectance")) m.reflectance = colour(sp, j.at("reflectance"), key + ".reflectance");
  if (type == "diffuse") {
    m.type = MaterialType::Diffuse;
    check_range(sp, m.reflectance, 0.0f, 1.0f, key + ".reflectance");
  } else if (type == "glossy") {
    m.type = MaterialType::Glossy;
    check_range(sp, m.reflectance, 0.0f, 1.0f, key + ".reflectance");
    m.roughness = static_cast<float>(number_or(sp, j, "roughness", key, 0.5));
    m.metallic = static_cast<float>(number_or(sp, j, "metallic", key, 0.0));
    if (m.roughness < 0 || m.roughness > 1) sp.fail(key + ".roughness", "must lie in [0, 1]");
    if (m.metallic < 0 || m.metallic > 1) sp.fail(key + ".metallic", "must lie in [0, 1]");
  } else if (type == "glass") {
    m.type = MaterialType::Glass;
    if (j.contains("transmittance")) m.transmittance = colour(sp, j.at("transmittance"), key + ".transmittance");
    check_range(sp, m.transmittance, 0.0f, 1.0f, key + ".transmittance");
    m.ior = static_cast<float>(number_or(sp, j, "ior", key, 1.52));
    if (!(m.ior >= 1.0f && m.ior <= 4.0f)) sp.fail(key + ".ior", "must lie in [1, 4]");
    const std::string kind = text_or(sp, j, "kind", key, "thin");
    if (kind != "thin" && kind != "solid") sp.fail(key + ".kind", "must be \"thin\" or \"solid\"");
    m.thin = kind == "thin";
    if (m.thin) {
      try {
        m.internal_transmittance = thin_glass_internal_transmittance(m.transmittance, m.ior, name);
      } catch (const std::invalid_argument& e) {
        sp.fail(key + ".transmittance", e.what());
      }
    }
  } else {
    sp.fail(key + ".type", "unknown material type '" + quoted_text(type) + "'" +
                               did_you_mean(type, {"diffuse", "glass", "glossy"}) + " (diffuse, glass or glossy)");
  }
  return m;
}

std::string text(const ScenePath& sp, const json& obj, const std::string& name, const std::string& key) {
  if (!obj.contains(name)) sp.fail(key + "." + name, "missing");
  if (!obj.at(name).is_string()) sp.fail(key + "." + name, "expected a string, got " + quoted_json(obj.at(name)));
  return obj.at(name).get<std::string>();
}



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

Sensors parse_sensors(const ScenePath& sp, const json& j, const SiteFrame& frame) {
  if (!j.is_object()) sp.fail("sensors", "expected an object");
  check_known_keys(sp, j, "sensors", {"points", "normals", "goals", "goal_units", "weights", "groups"});
  Sensors s;
  if (!j.contains("points") || !j.at("points").is_array() || j.at("points").empty())
    sp.fail("sensors.points", "the scene has no sensors");
  for (size_t i = 0; i < j.at("points").size(); ++i)
    s.points.push_back(point(sp, j.at("points")[i], "sensors.points[" + std::to_string(i) + "]", frame));
  json normals = j.value("normals", json::array({json::array({0, 0, 1})}));
  if (normals.is_array() && normals.size() == 3 && normals[0].is_number()) normals = json::array({normals});
  if (!normals.is_array() || (normals.size() != 1 && normals.size() != s.points.size()))
    sp.fail("sensors.normals", "give one normal for all sensors or one per sensor");
  for (size_t i = 0; i < s.points.size(); ++i) {
    const std::string key = "sensors.normals[" + std::to_string(normals.size() == 1 ? 0 : i) + "]";
    s.normals.push_back(direction(sp, normals[normals.size() == 1 ? 0 : i], key));
  }
  if (j.contains("goals") && !j.at("goals").is_null()) {
    const json& g = j.at("goals");
    if (!g.is_array() || g.size() != s.points.size())
      sp.fail("sensors.goals", "expected one goal per sensor (" + std::to_string(s.points.size()) + ")");
    for (size_t i = 0; i < g.size(); ++i)
      s.goals.push_back(g[i].is_null() ? std::nan("") : number(sp, g[i], "sensors.goals[" + std::to_string(i) + "]"));
  }
  s.goal_units = text_or(sp, j, "goal_units", "sensors", "normalized");
  if (s.goal_units != "normalized" && s.goal_units != "lux" && s.goal_units != "daylight_factor")
    sp.fail("sensors.goal_units", "must be \"normalized\", \"lux\" or \"daylight_factor\"");
  if (j.contains("weights")) {
    const json& w = j.at("weights");
    if (!w.is_array() || w.size() != s.points.size())
      sp.fail("sensors.weights", "expected one weight per sensor (" + std::to_string(s.points.size()) + ")");
    for (size_t i = 0; i < w.size(); ++i) {
      s.weights.push_back(number(sp, w[i], "sensors.weights[" + std::to_string(i) + "]"));
      if (s.weights.back() < 0.0) sp.fail("sensors.weights[" + std::to_string(i) + "]", "must not be negative");
    }
  }
  return s;
}

std::vector<double> numbers(const ScenePath& sp, const json& j, const std::string& key, size_t count) {
  if (!j.is_array() || j.size() != count)
    sp.fail(key, "expected a list of " + std::to_string(count) + " numbers");
  std::vector<double> out;
  for (size_t i = 0; i < j.size(); ++i) out.push_back(number(sp, j[i], key + "[" + std::to_string(i) + "]"));
  return out;
}

// The "goals" section: per-sensor goals (an alternative to sensors.goals), weights, and uniform
// levels over sets of sensors.
void parse_goals(const ScenePath& sp, const json& j, Sensors* s) {
  if (j.is_null()) return;
  if (!j.is_object()) sp.fail("goals", "expected an object");
  check_known_keys(sp, j, "goals", {"per_sensor", "units", "weights", "uniform", "climate", "least_glazing"});
  const size_t n = s->points.size();
  if (j.contains("per_sensor")) {
    if (!s->goals.empty()) sp.fail("goals.per_sensor", "the goals are already given in sensors.goals");
    const json& g = j.at("per_sensor");
    if (!g.is_array() || g.size() != n) sp.fail("goals.per_sensor", "expected one goal per sensor (" + std::to_string(n) + ")");
    for (size_t i = 0; i < n; ++i)
      s->goals.push_back(g[i].is_null() ? std::nan("") : number(sp, g[i], "goals.per_sensor[" + std::to_string(i) + "]"));
  }
  if (j.contains("units")) {
    s->goal_units = text(sp, j, "units", "goals");
    if (s->goal_units != "normalized" && s->goal_units != "lux" && s->goal_units != "daylight_factor")
      sp.fail("goals.units", "must be \"normalized\", \"lux\" or \"daylight_factor\"");
  }
  if (j.contains("weights")) {
    if (!s->weights.empty()) sp.fail("goals.weights", "the weights are already given in sensors.weights");
    s->weights = numbers(sp, j.at("weights"), "goals.weights", n);
    for (size_t i = 0; i < n; ++i)
      if (s->weights[i] < 0.0) sp.fail("goals.weights[" + std::to_string(i) + "]", "must not be negative");
  }
  if (j.contains("uniform")) {
    const json& list = j.at("uniform");
    if (!list.is_array()) sp.fail("goals.uniform", "expected a list of {\"sensors\", \"level\", \"min\", \"max\"}");
    for (size_t u = 0; u < list.size(); ++u) {
      const std::string key = "goals.uniform[" + std::to_string(u) + "]";
      const json& g = list[u];
      if (!g.is_object()) sp.fail(key, "expected an object");
      check_known_keys(sp, g, key, {"sensors", "level", "min", "max"});
      UniformGoal goal;
      const json& which = g.value("sensors", json("all"));
      if (which.is_string() && which.get<std::string>() == "all") {
        for (size_t i = 0; i < n; ++i) goal.sensors.push_back(static_cast<int>(i));
      } else if (which.is_array() && !which.empty()) {
        for (const json& i : which) {
          if (!i.is_number_integer() || i.get<long long>() < 0 || i.get<long long>() >= static_cast<long long>(n))
            sp.fail(key + ".sensors", "expected sensor indices 0.." + std::to_string(n - 1) + ", got " + quoted_json(i));
          goal.sensors.push_back(i.get<int>());
        }
      } else {
        sp.fail(key + ".sensors", "expected \"all\" or a non-empty list of sensor indices");
      }
      if (!g.contains("level")) sp.fail(key + ".level", "missing");
      goal.level = number(sp, g.at("level"), key + ".level");
      goal.min = number_or(sp, g, "min", key, goal.min);
      goal.max = number_or(sp, g, "max", key, goal.max);
      if (!(goal.min <= goal.level && goal.level <= goal.max))
        sp.fail(key, "needs min <= level <= max");
      s->uniform_goals.push_back(goal);
    }
  }
}

// Goals must be reachable quantities: not negative, and at most 1 (all open) when normalized.
void check_goals(const ScenePath& sp, const Sensors& s) {
  const double top = s.goal_units == "normalized" ? 1.0 : s.goal_units == "daylight_factor" ? 100.0
                                                                                          : limits::kMaxIlluminance;
  for (size_t i = 0; i < s.weights.size(); ++i)
    if (s.weights[i] > limits::kMaxWeight)
      sp.fail("weights[" + std::to_string(i) + "]", "must not exceed " + show(limits::kMaxWeight));
  auto check = [&](double g, const std::string& key) {
    if (std::isnan(g)) return;
    if (g < 0.0) sp.fail(key, "a goal must not be negative, got " + std::to_string(g));
    if (g > top)
      sp.fail(key, "a goal in " + s.goal_units + " units must not exceed " + std::to_string(top) + ", got " +
                       std::to_string(g));
  };
  for (size_t i = 0; i < s.goals.size(); ++i) check(s.goals[i], "goals[" + std::to_string(i) + "]");
  for (size_t u = 0; u < s.uniform_goals.size(); ++u) {
    const std::string key = "goals.uniform[" + std::to_string(u) + "]";
    check(s.uniform_goals[u].level, key + ".level");
    if (std::isfinite(s.uniform_goals[u].min)) check(s.uniform_goals[u].min, key + ".min");
  }
}

// One list of catalogue sizes: [[width, height], ...] or [{"width": w, "height": h}, ...], meters.
std::vector<CatalogueSize> parse_catalogue_sizes(const ScenePath& sp, const json& j, const std::string& key) {
  constexpr size_t kMaxSizes = 1000;
  constexpr double kMaxSide = 100.0;  // meters
  if (!j.is_array()) sp.fail(key, "expected a list of [width, height] sizes in meters");
  if (j.empty()) sp.fail(key, "is empty: give at least one [width, height] size, or leave the catalogue out");
  if (j.size() > kMaxSizes) sp.fail(key, "has " + std::to_string(j.size()) + " sizes, more than 1000");
  std::vector<CatalogueSize> sizes;
  for (size_t i = 0; i < j.size(); ++i) {
    const std::string at = key + "[" + std::to_string(i) + "]";
    const json& e = j[i];
    CatalogueSize size;
    if (e.is_array() && e.size() == 2) {
      size.width = number(sp, e[0], at + "[0]");
      size.height = number(sp, e[1], at + "[1]");
    } else if (e.is_object()) {
      check_known_keys(sp, e, at, {"width", "height"});
      if (!e.contains("width") || !e.contains("height")) sp.fail(at, "expected {\"width\": w, \"height\": h}");
      size.width = number(sp, e.at("width"), at + ".width");
      size.height = number(sp, e.at("height"), at + ".height");
    } else {
      sp.fail(at, "expected [width, height] in meters");
    }
    for (double side : {size.width, size.height})
      if (!(side > 0.0) || !(side <= kMaxSide))
        sp.fail(at, "sides must be positive lengths up to 100 m, got " + quoted_json(e));
    sizes.push_back(size);
  }
  return sizes;
}

// "catalogue": a built-in's name, a list of sizes (walls and roofs), or {"walls": [...], "roofs": [...]}.
WindowCatalogue parse_catalogue(const ScenePath& sp, const json& j, const std::string& key) {
  if (j.is_string()) {
    try {
      return builtin_catalogue(j.get<std::string>());
    } catch (const std::invalid_argument& e) {
      sp.fail(key, e.what());
    }
  }
  WindowCatalogue c;
  c.name = "custom";
  if (j.is_array()) {
    c.walls = parse_catalogue_sizes(sp, j, key);
    c.roofs = c.walls;
    return c;
  }
  if (!j.is_object()) sp.fail(key, "expected a catalogue's name, a list of [width, height] sizes, or {\"walls\", \"roofs\"}");
  check_known_keys(sp, j, key, {"walls", "roofs"});
  if (j.empty()) sp.fail(key, "is empty: give \"walls\" or \"roofs\" sizes, or leave the catalogue out");
  if (j.contains("walls")) c.walls = parse_catalogue_sizes(sp, j.at("walls"), key + ".walls");
  if (j.contains("roofs")) c.roofs = parse_catalogue_sizes(sp, j.at("roofs"), key + ".roofs");
  return c;
}

// "solver.constraints": what an opening may be. Lengths in meters, areas in m^2. The keys not
// given take their automatic values (automatic_constraints()) unless "automatic" is false; an
// automatic value that contradicts the given ones yields to them.
OpeningConstraints parse_constraints(const ScenePath& sp, const json& j, double element_size, const std::string& key) {
  if (!j.is_object()) sp.fail(key, "expected an object");
  check_known_keys(sp, j, key,
                   {"min_area", "max_area", "min_aspect", "max_aspect", "min_width", "max_width", "min_height",
                    "max_height", "max_openings", "min_gap", "margin", "sill_min", "sill_max", "head_min",
                    "head_max", "module", "head_clearance", "max_openings_per_panel", "panel_width_per_opening",
                    "automatic", "full_height", "catalogue", "align_sills", "align_heads", "equal_widths",
                    "same_type_in_row", "symmetric", "equal_spacing", "sill_heights"});
  OpeningConstraints c;
  const std::pair<const char*, double*> values[] = {
      {"min_area", &c.min_area},     {"max_area", &c.max_area},     {"min_aspect", &c.min_aspect},
      {"max_aspect", &c.max_aspect}, {"min_width", &c.min_width},   {"max_width", &c.max_width},
      {"min_height", &c.min_height}, {"max_height", &c.max_height}, {"min_gap", &c.min_gap},
      {"margin", &c.margin},         {"sill_min", &c.sill_min},     {"sill_max", &c.sill_max},
      {"head_min", &c.head_min},     {"head_max", &c.head_max},     {"module", &c.module},
      {"head_clearance", &c.head_clearance}, {"panel_width_per_opening", &c.panel_width_per_opening}};
  for (const auto& [name, value] : values) {
    *value = number_or(sp, j, name, key, *value);
    if (*value < 0.0) sp.fail(key + "." + name, "must not be negative");
  }
  auto whole = [&](const char* name, int* out) {
    if (!j.contains(name)) return;
    const double v = number(sp, j.at(name), key + "." + name);
    if (v != std::floor(v) || v < 0 || v > 1e6) sp.fail(key + "." + name, "expected a whole number from 0 to 10^6");
    *out = static_cast<int>(v);
  };
  whole("max_openings", &c.max_openings);
  whole("max_openings_per_panel", &c.max_openings_per_panel);
  auto flag = [&](const char* name, bool fallback) {
    if (!j.contains(name)) return fallback;
    if (!j.at(name).is_boolean()) sp.fail(key + "." + name, "expected true or false");
    return j.at(name).get<bool>();
  };
  const bool automatic = flag("automatic", true), full_height = flag("full_height", false);
  if (j.contains("catalogue")) c.catalogue = parse_catalogue(sp, j.at("catalogue"), key + ".catalogue");
  c.align_sills = flag("align_sills", false);
  c.align_heads = flag("align_heads", false);
  c.equal_widths = flag("equal_widths", false);
  c.same_type_in_row = flag("same_type_in_row", false);
  c.symmetric = flag("symmetric", false);
  c.equal_spacing = flag("equal_spacing", false);
  if (j.contains("sill_heights")) {
    const json& list = j.at("sill_heights");
    const std::string at = key + ".sill_heights";
    if (!list.is_array() || list.empty()) sp.fail(at, "expected a non-empty list of heights in meters");
    if (list.size() > 100) sp.fail(at, "has more than 100 heights");
    for (size_t i = 0; i < list.size(); ++i) {
      const double h = number(sp, list[i], at + "[" + std::to_string(i) + "]");
      if (!(h >= 0.0) || !(h <= 100.0)) sp.fail(at + "[" + std::to_string(i) + "]", "expected a height from 0 to 100 m");
      c.sill_heights.push_back(h);
    }
  }
  auto feasible = [&](const OpeningConstraints& set) {
    try {
      check_feasible(set, element_size);
      return true;
    } catch (const std::invalid_argument&) {
      return false;
    }
  };
  if (automatic) {
    std::vector<AutomaticConstraint> taken;
    for (const AutomaticConstraint& a : automatic_constraints(full_height)) {
      const bool a_size = std::string(a.key) == "min_width" || std::string(a.key) == "min_height";
      if (!j.contains(a.key) && !(a_size && !c.catalogue.empty())) taken.push_back(a);  // a catalogue sets sizes
    }
    auto with = [&](const std::vector<AutomaticConstraint>& list) {
      OpeningConstraints set = c;
      for (const AutomaticConstraint& a : list) set_constraint(&set, a.key, a.value), set.automatic_keys.push_back(a.key);
      return set;
    };
    // Yield: drop the first automatic value whose absence makes the set feasible, else the last.
    while (!taken.empty() && !feasible(with(taken))) {
      size_t drop = taken.size() - 1;
      for (size_t i = 0; i < taken.size(); ++i) {
        std::vector<AutomaticConstraint> rest = taken;
        rest.erase(rest.begin() + static_cast<std::ptrdiff_t>(i));
        if (feasible(with(rest))) {
          drop = i;
          break;
        }
      }
      taken.erase(taken.begin() + static_cast<std::ptrdiff_t>(drop));
    }
    c = with(taken);
  }
  try {
    check_feasible(c, element_size);
  } catch (const std::invalid_argument& e) {
    sp.fail(key, e.what());
  }
  return c;
}

// "solver.panel_constraints": [{"materials": [...], "groups": [...], "constraints": {...}}]: on the
// panels whose material or a face's group is listed, these keys replace the global constraints'.
void apply_panel_constraints(const ScenePath& sp, const json& solver, Scene* scene) {
  if (!solver.is_object() || !solver.contains("panel_constraints")) return;
  const json& list = solver.at("panel_constraints");
  if (!list.is_array()) sp.fail("solver.panel_constraints", "expected a list of {\"materials\", \"groups\", \"constraints\"}");
  const json global = solver.value("constraints", json::object());
  const auto materials = scene->material_names();
  const auto& panels = scene->domain.panels();
  std::vector<OpeningConstraints> per_panel(panels.size(), scene->solver.constraints);
  for (size_t e = 0; e < list.size(); ++e) {
    const std::string key = "solver.panel_constraints[" + std::to_string(e) + "]";
    const json& entry = list[e];
    if (!entry.is_object()) sp.fail(key, "expected an object");
    check_known_keys(sp, entry, key, {"materials", "groups", "constraints"});
    const auto want_materials = names(sp, entry, "materials", key), want_groups = names(sp, entry, "groups", key);
    json merged = global;
    if (entry.contains("constraints")) {
      if (!entry.at("constraints").is_object()) sp.fail(key + ".constraints", "expected an object");
      merged.update(entry.at("constraints"));
    }
    const OpeningConstraints set = parse_constraints(sp, merged, scene->domain.element_size(), key + ".constraints");
    int matched = 0;
    for (size_t p = 0; p < panels.size(); ++p) {
      bool match = panels[p].material >= 0 &&
                   std::count(want_materials.begin(), want_materials.end(), materials[panels[p].material]) > 0;
      for (uint32_t t : panels[p].triangles) {
        const int g = scene->mesh.triangle_group[t];
        if (g >= 0 && std::count(want_groups.begin(), want_groups.end(), scene->mesh.group_names[g]) > 0) match = true;
      }
      if (match) per_panel[p] = set, ++matched;
    }
    if (matched == 0) sp.fail(key, "matches no panel of the opening domain");
  }
  for (OpeningConstraints& set : per_panel) set.max_openings = scene->solver.constraints.max_openings;
  scene->solver.constraints.per_panel = std::move(per_panel);
}

SolverSettings parse_solver(const ScenePath& sp, const json& j) {
  SolverSettings s;
  if (j.is_null()) return s;
  if (!j.is_object()) sp.fail("solver", "expected an object");
  check_known_keys(sp, j, "solver",
                   {"element_size", "paths", "population", "generations", "seed", "time_budget_s", "shape_weights",
                    "bound_weight", "coarse_to_fine", "elite", "constraints", "panel_constraints", "improve_iterations",
                    "verify", "verify_paths", "refine_edges", "tradeoffs"});
  auto integer = [&](const char* name, int lo, int hi, int fallback) {
    if (!j.contains(name)) return fallback;
    const double v = number(sp, j.at(name), std::string("solver.") + name);
    if (v != std::floor(v) || v < lo || v > hi)
      sp.fail(std::string("solver.") + name,
              "expected a whole number in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
    return static_cast<int>(v);
  };
  s.paths_per_sensor = integer("paths", 1, 1 << 24, 0);
  s.population = integer("population", 4, 100000, s.population);
  s.generations = integer("generations", 0, 10000000, s.generations);
  s.elite = integer("elite", 1, 1000, s.elite);
  if (j.contains("seed")) s.seed = static_cast<uint64_t>(integer("seed", 0, 2147483647, 1));
  s.time_budget_s = number_or(sp, j, "time_budget_s", "solver", 0.0);
  if (s.time_budget_s < 0.0) sp.fail("solver.time_budget_s", "must not be negative");
  s.bound_weight = number_or(sp, j, "bound_weight", "solver", s.bound_weight);
  if (s.bound_weight < 0.0) sp.fail("solver.bound_weight", "must not be negative");
  if (j.contains("coarse_to_fine")) {
    if (!j.at("coarse_to_fine").is_boolean()) sp.fail("solver.coarse_to_fine", "expected true or false");
    s.coarse_to_fine = j.at("coarse_to_fine").get<bool>();
  }
  s.improve_iterations = integer("improve_iterations", 0, 100000000, s.improve_iterations);
  if (j.contains("refine_edges")) {
    if (!j.at("refine_edges").is_boolean()) sp.fail("solver.refine_edges", "expected true or false");
    s.refine_edges = j.at("refine_edges").get<bool>();
  }
  if (j.contains("verify")) {
    if (!j.at("verify").is_boolean()) sp.fail("solver.verify", "expected true or false");
    s.verify = j.at("verify").get<bool>();
  }
  s.verify_paths = integer("verify_paths", 0, 1 << 24, s.verify_paths);
  if (j.contains("tradeoffs")) {
    if (!j.at("tradeoffs").is_boolean()) sp.fail("solver.tradeoffs", "expected true or false");
    s.tradeoffs = j.at("tradeoffs").get<bool>();
  }
  if (j.contains("shape_weights")) {
    const json& w = j.at("shape_weights");
    if (!w.is_object()) sp.fail("solver.shape_weights", "expected {\"isolated\", \"boundary\", \"regions\"}");
    check_known_keys(sp, w, "solver.shape_weights", {"isolated", "boundary", "regions"});
    s.isolated_weight = number_or(sp, w, "isolated", "solver.shape_weights", s.isolated_weight);
    s.boundary_weight = number_or(sp, w, "boundary", "solver.shape_weights", s.boundary_weight);
    s.regions_weight = number_or(sp, w, "regions", "solver.shape_weights", s.regions_weight);
    if (s.isolated_weight < 0 || s.boundary_weight < 0 || s.regions_weight < 0)
      sp.fail("solver.shape_weights", "weights must not be negative");
  }
  return s;
}

RenderSettings parse_render(const ScenePath& sp, const json& j) {
  RenderSettings r;
  if (j.is_null()) return r;
  if (!j.is_object()) sp.fail("render", "expected an object");
  check_known_keys(sp, j, "render", {"paths_per_sensor", "max_bounces", "seed", "threads", "sampler"});
  auto integer = [&](const IntegerRange& range, long long fallback) {
    const std::string name = std::string(range.key).substr(std::string("render.").size());
    return j.contains(name) ? integer_in(sp, j.at(name), range, range.key) : fallback;
  };
  r.paths_per_sensor = static_cast<int>(integer(limits::kPathsPerSensor, r.paths_per_sensor));
  r.max_bounces = static_cast<int>(integer(limits::kMaxBounces, r.max_bounces));
  r.seed = static_cast<uint64_t>(integer(limits::kSeed, 1));
  r.threads = static_cast<int>(integer(limits::kThreads, 0));
  if (j.contains("sampler")) {
    const json& v = j.at("sampler");
    if (!v.is_string() || !parse_sampler(v.get<std::string>(), &r.sampler))
      sp.fail("render.sampler", "expected \"sobol\" or \"independent\", got " + quoted_json(v));
  }
  return r;
}

}  // namespace

std::vector<std::string> Scene::material_names() const {
  std::vector<std::string> out;
  for (const auto& m : materials) out.push_back(m.name);
  return out;
}

const char* sampler_name(RenderSettings::Sampler sampler) {
  return sampler == RenderSettings::Sampler::kSobol ? "sobol" : "independent";
}

bool parse_sampler(const std::string& name, RenderSettings::Sampler* out) {
  if (name == "sobol") *out = RenderSettings::Sampler::kSobol;
  else if (name == "independent") *out = RenderSettings::Sampler::kIndependent;
  else return false;
  return true;
}

std::string RenderSettings::to_string() const {
  std::ostringstream s;
  s << "RenderSettings(paths_per_sensor=" << paths_per_sensor << ", max_bounces=" << max_bounces << ", seed=" << seed
    << ", threads=" << threads << ", sampler='" << sampler_name(sampler) << "')";
  return s.str();
}

std::string Scene::to_string() const {
  std::ostringstream s;
  s << "Scene('" << source << "', " << mesh.triangle_count() << " triangles, " << materials.size() << " materials, "
    << domain.panels().size() << " panels, " << domain.element_count() << " elements of " << domain.element_size()
    << " m, " << sensors.size() << " sensors, " << (sky ? sky->to_string() : "no sky");
  if (site.shifted()) s << ", local origin at " << site.to_string();
  s << ")";
  return s.str();
}

Scene parse_scene(const std::string& text, const std::string& base_dir, const std::string& source_name,
                  Progress* progress) {
  const ScenePath sp(source_name);
  const json j = parse_json_text(text, "scene", source_name);
  if (!j.is_object()) sp.fail("(top level)", "expected a JSON object");
  // Compared as a double: an integer such as 4294967297 must not wrap to 1.
  const bool version_1 = j.contains("fenestra") && j.at("fenestra").is_number_integer() &&
                         j.at("fenestra").get<double>() == 1.0;
  auto fail_version = [&] {
    sp.fail("fenestra", "expected the format version 1 (\"fenestra\": 1), got " +
                            (j.contains("fenestra") ? quoted_json(j.at("fenestra")) : std::string("nothing")));
  };
  if (j.contains("fenestra") && !version_1) fail_version();  // another version may have other keys
  check_known_keys(sp, j, "",
                   {"fenestra", "geometry", "materials", "opening_domain", "sensors", "goals", "sky", "render",
                    "solver"});
  if (!version_1) fail_version();

  Scene scene;
  scene.source = source_name;
  const fs::path base(base_dir);
  try {
    if (!j.contains("materials") || !j.at("materials").is_object() || j.at("materials").empty())
      sp.fail("materials", "the scene defines no materials");
    for (const auto& [name, m] : j.at("materials").items()) scene.materials.push_back(parse_material(sp, name, m));

    if (!j.contains("geometry") || !j.at("geometry").is_string()) sp.fail("geometry", "expected the OBJ file name");
    try {
      scene.mesh = load_obj((base / j.at("geometry").get<std::string>()).string(), scene.material_names(), &scene.site);
      scene.input_files.push_back((base / j.at("geometry").get<std::string>()).string());
    } catch (const std::invalid_argument& e) {
      sp.fail("geometry", e.what());
    }

    if (!j.contains("opening_domain") || !j.at("opening_domain").is_object())
      sp.fail("opening_domain", "expected an object naming the materials or groups that may host openings");
    const json& od = j.at("opening_domain");
    check_known_keys(sp, od, "opening_domain", {"materials", "groups", "element_size", "thickness"});
    OpeningDomainSelection sel;
    sel.materials = names(sp, od, "materials", "opening_domain");
    sel.groups = names(sp, od, "groups", "opening_domain");
    sel.element_size = static_cast<float>(number_or(sp, od, "element_size", "opening_domain", 0.25));
    // The solver's element size, when given, is the one the domain is diced with.
    if (j.contains("solver") && j.at("solver").is_object() && j.at("solver").contains("element_size"))
      sel.element_size = static_cast<float>(number(sp, j.at("solver").at("element_size"), "solver.element_size"));
    if (od.contains("thickness"))
      sel.thickness =
          static_cast<float>(number_in(sp, od, "thickness", "opening_domain", 0.0, 0.0, limits::kMaxThickness, " m"));
    sel.site = scene.site;
    try {
      scene.domain = OpeningDomain::build(scene.mesh, scene.material_names(), sel);
    } catch (const std::invalid_argument& e) {
      sp.fail("opening_domain", e.what());
    }

    if (!j.contains("sensors")) sp.fail("sensors", "the scene has no sensors");
    scene.sensors = parse_sensors(sp, j.at("sensors"), scene.site);
    scene.domain.orient(scene.sensors.points);
    try {
      scene.domain.build_walls(&scene.mesh);
    } catch (const std::invalid_argument& e) {
      sp.fail("opening_domain", e.what());
    }
    parse_goals(sp, j.value("goals", json()), &scene.sensors);
    check_goals(sp, scene.sensors);
    // No "sky" at all: the default uniform sky; a "sky" must name its type.
    // Before the sky: a climate sky takes seconds to build, a bad goal should not wait for it.
    scene.sensors.climate_goals = parse_climate_goals(j.value("goals", json()), j.at("sensors").value("groups", json()),
                                                      scene.sensors.size(), sp.source());
    parse_sky(sp, j.contains("sky") ? j.at("sky") : json{{"type", "uniform"}}, base, &scene, progress);
    if (!scene.sensors.climate_goals.empty() && !scene.climate)
      sp.fail("goals.climate", "climate goals need a sky of type \"climate\" (a weather file)");
    scene.render = parse_render(sp, j.value("render", json()));
    scene.solver = parse_solver(sp, j.value("solver", json()));
    const json solver = j.value("solver", json());
    const json given = solver.is_object() ? solver.value("constraints", json::object()) : json::object();
    scene.solver.constraints = parse_constraints(sp, given, scene.domain.element_size(), "solver.constraints");
    apply_panel_constraints(sp, j.value("solver", json()), &scene);
    const std::string no_fit = catalogue_fit_problem(scene.domain, scene.solver.constraints);
    if (!no_fit.empty()) sp.fail("solver.constraints.catalogue", no_fit);
    const std::string no_facade = composition_problem(scene.domain, scene.solver.constraints);
    if (!no_facade.empty()) sp.fail("solver.constraints", no_facade);
  } catch (const json::exception& e) {
    sp.fail("(structure)", "a value has the wrong type: " + json_error_text(e));
  }
  return scene;
}

Scene load_scene(const std::string& path, Progress* progress) {
  check_input_file(path, "scene file", limits::kMaxSceneFileBytes);
  const std::string text = read_whole_file(path, "scene file");
  const fs::path p(path);
  Scene scene = parse_scene(text, p.parent_path().string().empty() ? "." : p.parent_path().string(), path, progress);
  scene.input_files.insert(scene.input_files.begin(), path);
  return scene;
}

}  // namespace fenestra
