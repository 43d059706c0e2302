#pragma once
// The year's skies as the daylight-coefficient method needs them (Radiance's gendaymtx): for every
// hour of a weather file, the mean luminance of each sky patch under the Perez all-weather sky
// (patch 0, the ground: a diffuse ground lit by that hour's global illuminance), and the sun kept
// apart as a direction and a direct normal illuminance. See docs/sky.md, "Climate".
// Units: luminance cd/m^2, illuminance lux, clock hours of local standard time.
#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "daylight/annual_metrics.h"  // HourStamp
#include "daylight/sky_patches.h"
#include "daylight/solar_position.h"  // Place
#include "daylight/weather_file.h"
#include "daylight/weather_site.h"  // kFarFromStationKm
#include "math/vec.h"

namespace fenestra {

class Progress;  // util/progress.h

struct ClimateSettings {
  std::string weather_path;        // .epw or .wea, as given (resolved against the scene file)
  // Where: the weather file's location unless the scene gives latitude and longitude (then the
  // scene's, with a warning when the two are more than kFarKm apart).
  Place place;
  double time_zone_hours = 0.0;    // standard time, east positive (the weather file's)
  double north_offset_deg = 0.0;   // true north, clockwise from +Y seen from above
  double ground_reflectance = 0.2;
  int subdivision = 1;             // sky patches: 1 Tregenza (145), 2 (577), 4 (2305) Reinhart
  double occupied_start_hour = 8.0, occupied_end_hour = 18.0;  // local standard time, every day
  static constexpr double kFarKm = kFarFromStationKm;  // daylight/weather_site.h: 100 km
  std::string describe() const;

  // The settings of a weather file as it stands: its path, place and time zone, the defaults else.
  static ClimateSettings for_weather(const WeatherData& weather);
  // Patch means use n x n points per patch (SkyPatches::patch_means).
  static constexpr int kPointsPerSide = 4;
};

struct SkyMatrix {
  SkyPatches patches;
  std::vector<HourStamp> hours;      // one per weather row
  // patches.count() x hours: mean luminance of each patch (cd/m^2); row 0 is the ground,
  // ground_reflectance x (diffuse + direct horizontal illuminance) / pi. Zero columns at night.
  Eigen::MatrixXf radiance;
  // Per hour: the unit direction toward the sun (world, +Z up, north offset applied) and its direct
  // normal illuminance in lux (Perez direct efficacy x DNI); zero illuminance when the sun is down.
  std::vector<Vec3> sun_direction;
  std::vector<float> sun_normal_illuminance;
  // Per hour, lux: the model's diffuse horizontal illuminance (DHI x diffuse efficacy) and the
  // global horizontal one (diffuse + direct x cos zenith). EN 17037's daylight hours use these.
  std::vector<double> diffuse_horizontal_lux, global_horizontal_lux;
  std::vector<std::string> warnings;  // the weather file's, and the place check's
};

// Throws std::invalid_argument naming the file, the record and the value for a record the Perez
// model refuses (see PerezAllWeatherSky::create).
SkyMatrix make_sky_matrix(const WeatherData& weather, const ClimateSettings& settings);
// The same, reporting the hours done to `progress` and polling its cancellation (throws Cancelled).
// Also refuses (CostError) a matrix beyond the memory limit or the time limit (check_sky_matrix_cost below).
SkyMatrix make_sky_matrix(const WeatherData& weather, const ClimateSettings& settings, Progress* progress);

// Indices of the hours whose clock hour lies in [occupied_start_hour, occupied_end_hour) (local
// standard time), as the annual metrics count them.
std::vector<size_t> occupied_hours(const std::vector<HourStamp>& hours, const ClimateSettings& settings);

// What a "climate" sky of a scene holds (scene.h: Scene::climate).
struct Climate {
  ClimateSettings settings;
  std::shared_ptr<const WeatherData> weather;
  std::shared_ptr<const SkyMatrix> sky;
};

// A climate's sky matrix: its patches x hours floats and per-hour vectors must fit in memory, and
// its patch means (points^2 Perez evaluations per sky patch for every hour with light) take at
// most kMaxSkyMatrixSeconds on the reference machine; else CostError naming the figure.
inline constexpr double kMaxSkyMatrixSeconds = 300.0;
double sky_matrix_bytes(int patches, size_t hours);
double sky_matrix_build_seconds(int patches, size_t hours_with_light, int points_per_side);
void check_sky_matrix_cost(int subdivision, int patches, size_t hours, size_t hours_with_light, int points_per_side);

}  // namespace fenestra
