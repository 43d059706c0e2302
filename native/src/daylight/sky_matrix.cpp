#include "daylight/sky_matrix.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

#include "daylight/perez_all_weather.h"
#include "daylight/weather_site.h"
#include "math/constants.h"
#include "util/byte_size.h"
#include "util/cost_error.h"
#include "util/memory_limit.h"
#include "util/number_text.h"
#include "util/progress.h"
#include "util/quoted_text.h"

namespace fenestra {
namespace {

constexpr double kDegree = kPiD / 180.0;
constexpr size_t kHoursPerTask = 24;  // one day of rows: a task of a few milliseconds

void check(bool ok, const std::string& key, const std::string& message) {
  if (!ok) throw std::invalid_argument("sky." + key + ": " + message);
}

std::string clock(double hours) {
  const int minutes = static_cast<int>(std::lround(std::clamp(hours, 0.0, 24.0) * 60.0));
  char text[16];
  std::snprintf(text, sizeof text, "%02d:%02d", minutes / 60, minutes % 60);
  return text;
}

// The points SkyPatches::patch_means averages over, in its order (u across the azimuth outside, v
// up the sine of the altitude inside), made once for the year: every hour evaluates the same
// directions, and the points of a patch at one v share a zenith angle (one Perez gradation).
class PatchPoints {
 public:
  PatchPoints(const SkyPatches& patches, int n) : n_(n), count_(patches.count()) {
    directions_.reserve(static_cast<size_t>(count_) * n * n);
    for (int p = 0; p < count_; ++p)
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
          directions_.push_back(p == SkyPatches::kGround ? Vec3d(0.0, 0.0, -1.0)
                                                         : patches.square_to_patch(p, (i + 0.5) / n, (j + 0.5) / n));
  }
  // Mean luminance of every sky patch into `column` (patch 0, the ground, untouched).
  template <typename Column>
  void means(const PerezAllWeatherSky& sky, Column&& column) const {
    std::vector<PerezAllWeatherSky::Row> rows(static_cast<size_t>(n_));
    for (int p = 1; p < count_; ++p) {
      const Vec3d* d = &directions_[static_cast<size_t>(p) * n_ * n_];
      for (int j = 0; j < n_; ++j) rows[j] = sky.row(d[j].z());
      double sum = 0.0;
      for (int i = 0; i < n_; ++i)
        for (int j = 0; j < n_; ++j) sum += sky.luminance(rows[j], d[i * n_ + j]);
      column(p) = static_cast<float>(sum / (double(n_) * n_));
    }
  }

 private:
  int n_, count_;
  std::vector<Vec3d> directions_;  // count x n x n, patch by patch
};

void check_settings(const WeatherData& weather, const ClimateSettings& s) {
  check(!weather.hours.empty(), "weather", "'" + quoted_path(weather.path) + "' holds no rows");
  check(std::isfinite(s.place.latitude_deg) && std::abs(s.place.latitude_deg) <= 90.0, "latitude",
        "must be in [-90, 90] degrees, got " + decimal_text(s.place.latitude_deg));
  check(std::isfinite(s.place.longitude_deg) && std::abs(s.place.longitude_deg) <= 180.0, "longitude",
        "must be in [-180, 180] degrees, got " + decimal_text(s.place.longitude_deg));
  check(std::isfinite(s.place.elevation_m), "elevation", "must be a number of meters");
  check(std::isfinite(s.time_zone_hours) && std::abs(s.time_zone_hours) <= 14.0, "time_zone",
        "the standard-time offset must be within 14 h of UTC, got " + decimal_text(s.time_zone_hours));
  check(std::isfinite(s.north_offset_deg), "north_offset_deg", "must be a number of degrees");
  check(std::isfinite(s.ground_reflectance) && s.ground_reflectance >= 0.0 && s.ground_reflectance <= 1.0,
        "ground_reflectance", "must be in [0, 1], got " + decimal_text(s.ground_reflectance));
  check(s.occupied_start_hour >= 0.0 && s.occupied_start_hour < s.occupied_end_hour && s.occupied_end_hour <= 24.0,
        "occupied", "needs 0 <= start < end <= 24 h of local standard time, got [" + decimal_text(s.occupied_start_hour) +
                        ", " + decimal_text(s.occupied_end_hour) + "]");
}

}  // namespace

std::string ClimateSettings::describe() const {
  std::ostringstream s;
  s << "climate of '" << weather_path << "' at " << place.latitude_deg << ", " << place.longitude_deg << " (UTC"
    << (time_zone_hours < 0 ? "" : "+") << time_zone_hours << " standard time), ";
  const int patches = 144 * subdivision * subdivision + 1;
  s << patches << " sky patches (" << (subdivision == 1 ? "Tregenza" : "Reinhart MF " + std::to_string(subdivision))
    << "), occupied " << clock(occupied_start_hour) << "-" << clock(occupied_end_hour) << ", ground reflectance "
    << ground_reflectance;
  if (north_offset_deg != 0.0) s << ", north offset " << north_offset_deg << " deg";
  return s.str();
}

ClimateSettings ClimateSettings::for_weather(const WeatherData& weather) {
  ClimateSettings s;
  s.weather_path = weather.path;
  s.place.latitude_deg = weather.location.latitude_deg;
  s.place.longitude_deg = weather.location.longitude_deg;
  s.place.elevation_m = weather.location.elevation_m;
  s.time_zone_hours = weather.location.time_zone_hours;
  return s;
}

std::vector<size_t> occupied_hours(const std::vector<HourStamp>& hours, const ClimateSettings& settings) {
  std::vector<size_t> rows;
  for (size_t i = 0; i < hours.size(); ++i)
    if (hours[i].clock_hour >= settings.occupied_start_hour && hours[i].clock_hour < settings.occupied_end_hour)
      rows.push_back(i);
  return rows;
}

SkyMatrix make_sky_matrix(const WeatherData& weather, const ClimateSettings& settings) {
  return make_sky_matrix(weather, settings, nullptr);
}

SkyMatrix make_sky_matrix(const WeatherData& weather, const ClimateSettings& s, Progress* progress) {
  check_settings(weather, s);
  SkyMatrix m;
  m.patches = SkyPatches(s.subdivision, s.north_offset_deg);  // refuses a subdivision outside 1..64
  const size_t n = weather.hours.size();
  size_t with_light = 0;
  for (const WeatherHour& h : weather.hours) with_light += h.direct_normal_w_m2 > 0.0 || h.diffuse_horizontal_w_m2 > 0.0;
  check_sky_matrix_cost(s.subdivision, m.patches.count(), n, with_light, ClimateSettings::kPointsPerSide);

  const WeatherClock weather_clock(weather, s.time_zone_hours);
  m.hours.resize(n);
  m.radiance = Eigen::MatrixXf::Zero(m.patches.count(), static_cast<Eigen::Index>(n));
  m.sun_direction.resize(n);
  m.sun_normal_illuminance.assign(n, 0.0f);
  m.diffuse_horizontal_lux.assign(n, 0.0);
  m.global_horizontal_lux.assign(n, 0.0);
  if (progress) progress->start("building the sky matrix", n);
  const PatchPoints points(m.patches, ClimateSettings::kPointsPerSide);

  // Each hour fills its own column and entries: the result does not depend on the thread count.
  tbb::parallel_for(tbb::blocked_range<size_t>(0, n, kHoursPerTask), [&](const tbb::blocked_range<size_t>& range) {
    if (progress) progress->throw_if_cancelled();
    for (size_t i = range.begin(); i != range.end(); ++i) {
      const WeatherHour& h = weather.hours[i];
      m.hours[i] = weather_clock.stamp(i);
      const SunPosition position = model_sun_position(weather_clock.utc_seconds(i), s.place, s.north_offset_deg);
      const Vec3 sun = sun_direction(position);
      m.sun_direction[i] = sun;
      // The sun is up as make_daylight counts it; twilight (sun down, DHI > 0) still lights the sky.
      const bool sun_up = position.zenith_deg < 90.0 && sun.z() > 0.0f;
      if (!sun_up && h.diffuse_horizontal_w_m2 == 0.0) continue;  // night: a zero column
      PerezSkyInput input;
      input.sun = sun;
      input.day_of_year = day_of_year(h.month, h.day);
      input.direct_normal_w_m2 = h.direct_normal_w_m2;
      input.diffuse_horizontal_w_m2 = h.diffuse_horizontal_w_m2;
      input.dew_point_c = h.dew_point_c;
      input.where = weather.path + " line " + std::to_string(h.line);
      const PerezAllWeatherSky sky = PerezAllWeatherSky::create(input);
      const double direct = sun_up ? sky.direct_normal_illuminance() : 0.0;
      const double diffuse = sky.diffuse_horizontal_illuminance();
      const double global = diffuse + direct * std::max(0.0, std::cos(position.zenith_deg * kDegree));
      m.sun_normal_illuminance[i] = static_cast<float>(direct);
      m.diffuse_horizontal_lux[i] = diffuse;
      m.global_horizontal_lux[i] = global;
      if (diffuse > 0.0) points.means(sky, m.radiance.col(static_cast<Eigen::Index>(i)));
      // The ground: a diffuse (Lambertian) plane lit by the hour's sky and sun.
      m.radiance(SkyPatches::kGround, static_cast<Eigen::Index>(i)) = static_cast<float>(s.ground_reflectance * global / kPiD);
    }
    if (progress) progress->advance(range.size());
  });

  m.warnings = weather.warnings;
  const std::string far = far_place_warning(s.place, weather, ClimateSettings::kFarKm);
  if (!far.empty()) m.warnings.push_back(far);
  return m;
}

namespace {

// The sky matrix: one float per patch and hour, and per hour a HourStamp, a sun direction and
// illuminance, two doubles; the Perez sky of an hour takes about 0.1 ms to create.
constexpr double kSkyMatrixBytesPerHour = sizeof(double) * 2 + 16 + 12 + 4, kSkyMatrixSecondsPerHour = 1e-4;
constexpr double kSkyMatrixSecondsPerEvaluation = 15e-9;  // one luminance of a patch mean, 2 cores

}  // namespace

double sky_matrix_bytes(int patches, size_t hours) {
  return (4.0 * patches + kSkyMatrixBytesPerHour) * static_cast<double>(hours);
}

double sky_matrix_build_seconds(int patches, size_t hours_with_light, int points_per_side) {
  const double evaluations = static_cast<double>(patches) * points_per_side * points_per_side;
  return static_cast<double>(hours_with_light) * (evaluations * kSkyMatrixSecondsPerEvaluation + kSkyMatrixSecondsPerHour);
}

void check_sky_matrix_cost(int subdivision, int patches, size_t hours, size_t hours_with_light, int points_per_side) {
  const MemoryLimit limit = memory_limit();
  const double need = sky_matrix_bytes(patches, hours);
  std::ostringstream s;
  s << "patches " << subdivision << " gives " << format_count(patches) << " patches x " << format_count(static_cast<double>(hours))
    << " hours: ";
  if (need > static_cast<double>(limit.bytes)) {
    s << memory_refusal("the sky matrix", need, need, limit, "fewer sky patches (sky.patches 1, 2 or 4)");
    throw CostError(s.str());
  }
  const double seconds = sky_matrix_build_seconds(patches, hours_with_light, points_per_side);
  if (seconds <= kMaxSkyMatrixSeconds) return;
  s << "building the sky matrix would take about " << std::lround(seconds / 60.0) << " min ("
    << format_count(seconds) << " s on the 2-core reference machine; at most " << format_count(kMaxSkyMatrixSeconds)
    << " s): use fewer sky patches (sky.patches 1, 2 or 4)";
  throw CostError(s.str());
}

}  // namespace fenestra
