#include "daylight/daylight.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <sstream>
#include <stdexcept>

#include "daylight/perez_all_weather.h"
#include "daylight/sky_models.h"
#include "daylight/weather_file.h"
#include "daylight/weather_site.h"
#include "math/equirect.h"
#include "math/gauss_legendre.h"
#include "util/byte_size.h"
#include "util/cost_error.h"
#include "util/memory_limit.h"

namespace fenestra {
namespace {

constexpr double kDegree = 3.14159265358979323846 / 180.0;
constexpr size_t kMaxSteps = 200000;  // about 5 years at 15-minute steps

void check(bool ok, const std::string& key, const std::string& message) {
  if (!ok) throw std::invalid_argument("sky." + key + ": " + message);
}

using RadianceOf = std::function<Rgb(const Vec3&)>;

// Horizontal illuminance of an analytic sky: Gauss-Legendre in cos(theta), trapezoid in azimuth
// (periodic, so spectrally accurate); fill_row evaluates one ring of directions.
Rgb analytic_horizontal_illuminance(const std::function<void(const Vec3*, int, Rgb*)>& fill_row) {
  constexpr int kRings = 96, kAzimuths = 192;
  static const QuadratureRule rule = gauss_legendre(kRings);
  std::vector<Eigen::Array3d> rings(kRings);
  tbb::parallel_for(0, kRings, [&](int i) {
    const double mu = rule.nodes[i], s = std::sqrt(std::max(0.0, 1.0 - mu * mu));
    Vec3 directions[kAzimuths];
    Rgb values[kAzimuths];
    for (int j = 0; j < kAzimuths; ++j) {
      const double phi = 2.0 * 3.14159265358979323846 * (j + 0.5) / kAzimuths;
      directions[j] = Vec3(float(s * std::cos(phi)), float(s * std::sin(phi)), float(mu));
    }
    fill_row(directions, kAzimuths, values);
    Eigen::Array3d ring = Eigen::Array3d::Zero();
    for (const Rgb& v : values) ring += v.cast<double>();
    rings[i] = rule.weights[i] * mu * ring * (2.0 * 3.14159265358979323846 / kAzimuths);
  });
  Eigen::Array3d sum = Eigen::Array3d::Zero();
  for (const auto& r : rings) sum += r;
  return sum.cast<float>();
}

// Directions of the pixel centres of a map's upper half, row by row (shared by every step).
std::vector<Vec3> upper_directions(int width, int height) {
  std::vector<Vec3> d(static_cast<size_t>(width) * (height / 2));
  for (int y = 0; y < height / 2; ++y)
    for (int x = 0; x < width; ++x)
      d[static_cast<size_t>(y) * width + x] = equirect_direction(Vec2((x + 0.5f) / width, (y + 0.5f) / height));
  return d;
}

// One step's sky, rasterised into the map's upper half (pixel centres): fill_row(directions,
// count, out) evaluates directions that share a polar angle.
using RowFiller = std::function<void(const Vec3* directions, int count, Rgb* out)>;
void rasterise_sky(int width, int height, const std::vector<Vec3>& directions, const RowFiller& fill_row,
                   std::vector<Rgb>* upper) {
  upper->resize(directions.size());
  tbb::parallel_for(0, height / 2, [&](int y) {
    const size_t first = static_cast<size_t>(y) * width;
    fill_row(directions.data() + first, width, upper->data() + first);
  });
}

// Day of the year (1..365) of the UTC date of an instant: the Earth-Sun distance for constant
// Perez irradiances.
int utc_day_of_year(double utc_seconds) {
  const LocalDate d = add_days(LocalDate{1970, 1, 1}, static_cast<int>(std::floor(utc_seconds / 86400.0)));
  return day_of_year(d.month, d.day);
}

std::string clock(double minutes) {
  const int m = static_cast<int>(std::lround(minutes));
  std::ostringstream s;
  s << (m / 60 < 10 ? "0" : "") << (m / 60) << ":" << (m % 60 < 10 ? "0" : "") << (m % 60);
  return s.str();
}

}  // namespace

std::string DaylightSettings::describe() const {
  std::ostringstream s;
  const char* names[] = {"Preetham", "CIE overcast", "CIE clear", "Perez"};
  s << names[static_cast<int>(model)] << " sky";
  if (model == Model::Perez && weather && !weather_rows.empty()) {
    s << " over " << weather_rows.size() << " hours of '" << weather->path << "' at " << place.latitude_deg << ", "
      << place.longitude_deg;
  } else if (model != Model::CieOvercast) {
    s << " at " << place.latitude_deg << ", " << place.longitude_deg << " (" << time_zone.name() << "), "
      << to_string(date);
    if (days_between(date, date_end) > 0) s << " to " << to_string(date_end);
    if (start_minutes == end_minutes)
      s << " at " << clock(start_minutes);
    else
      s << ", " << clock(start_minutes) << "-" << clock(end_minutes) << " every " << step_minutes << " min";
    if (model == Model::Perez && weather)
      s << ", weather '" << weather->path << "'";
    else if (model == Model::Perez)
      s << ", direct normal " << direct_normal_w_m2 << " W/m2, diffuse horizontal " << diffuse_horizontal_w_m2 << " W/m2";
    else
      s << ", turbidity " << turbidity;
  }
  return s.str();
}

std::vector<TimeStep> time_steps(const DaylightSettings& settings) {
  const bool from_weather = settings.model == DaylightSettings::Model::Perez && settings.weather;
  if (from_weather && !settings.weather_rows.empty()) {  // the rows are the steps
    const WeatherClock clock(*settings.weather);
    std::vector<TimeStep> steps;
    const double weight = 1.0 / static_cast<double>(settings.weather_rows.size());
    for (const size_t row : settings.weather_rows) {
      check(row < clock.rows(), "weather", "row " + std::to_string(row) + " is not in '" + settings.weather->path + "'");
      steps.push_back({clock.utc_seconds(row), weight, static_cast<int>(row)});
    }
    return steps;
  }
  check(std::isfinite(settings.step_minutes) && settings.step_minutes > 0.0, "step_minutes", "must be positive");
  const int days = days_between(settings.date, settings.date_end) + 1;
  check(days >= 1, "date_end", "must not be before sky.date");
  double end = settings.end_minutes;
  if (end < settings.start_minutes) end += 24.0 * 60.0;  // the interval crosses midnight
  const double length = end - settings.start_minutes;
  const size_t per_day = length > 0.0 ? static_cast<size_t>(std::ceil(length / settings.step_minutes - 1e-9)) : 1;
  check(per_day * days <= kMaxSteps, "step_minutes",
        "the interval needs " + std::to_string(per_day * days) + " steps (at most " + std::to_string(kMaxSteps) + ")");
  std::vector<TimeStep> steps;
  for (int day = 0; day < days; ++day) {
    const LocalDate date = add_days(settings.date, day);
    for (size_t k = 0; k < per_day; ++k) {
      const double a = settings.start_minutes + k * settings.step_minutes;
      const double b = std::min(a + settings.step_minutes, end);
      const double duration = length > 0.0 ? b - a : 1.0;  // a zero-length interval is one instant
      steps.push_back({settings.time_zone.utc_seconds(date, length > 0.0 ? 0.5 * (a + b) : a), duration});
    }
  }
  double total = 0.0;
  for (const TimeStep& s : steps) total += s.weight;
  for (TimeStep& s : steps) s.weight /= total;
  if (from_weather) {  // each step takes the row whose hour holds it
    const WeatherClock clock(*settings.weather);
    for (TimeStep& step : steps) {
      step.weather_row = clock.row_at(step.utc_seconds);
      check(step.weather_row >= 0, "date",
            "the weather file '" + settings.weather->path + "' has no row for " + clock.hour_text(step.utc_seconds));
    }
  }
  return steps;
}

Rgb map_horizontal_illuminance(int width, int height, const std::vector<Rgb>& pixels) {
  // A pixel row between polar angles t0 and t1 subtends, per unit azimuth, the integral of
  // cos(theta) sin(theta) dtheta = (sin^2 t1 - sin^2 t0) / 2.
  Eigen::Array3d e = Eigen::Array3d::Zero();
  const double pi = 3.14159265358979323846, d_phi = 2.0 * pi / width;
  for (int y = 0; y < height; ++y) {
    const double t0 = pi * y / height, t1 = std::min(pi * (y + 1) / height, 0.5 * pi);
    if (t0 >= 0.5 * pi) break;
    const double weight = 0.5 * (std::sin(t1) * std::sin(t1) - std::sin(t0) * std::sin(t0)) * d_phi;
    Eigen::Array3d row = Eigen::Array3d::Zero();
    for (int x = 0; x < width; ++x) row += pixels[static_cast<size_t>(y) * width + x].cast<double>();
    e += weight * row;
  }
  return e.cast<float>();
}

Daylight make_daylight(const DaylightSettings& s, Progress* progress) {
  const auto start = std::chrono::steady_clock::now();
  check(s.width >= 4 && s.height >= 2 && s.height % 2 == 0 && s.width <= 16384 && s.height <= 8192, "resolution",
        "needs width 4..16384 and an even height 2..8192");
  check(std::isfinite(s.ground_reflectance) && s.ground_reflectance >= 0.0 && s.ground_reflectance <= 1.0,
        "ground_reflectance", "must be in [0, 1]");
  check(std::isfinite(s.place.latitude_deg) && std::abs(s.place.latitude_deg) <= 90.0, "latitude",
        "must be in [-90, 90] degrees");
  check(std::isfinite(s.place.longitude_deg) && std::abs(s.place.longitude_deg) <= 180.0, "longitude",
        "must be in [-180, 180] degrees");
  check(std::isfinite(s.north_offset_deg), "north_offset_deg", "must be a number");
  check(std::isfinite(s.zenith_luminance) && s.zenith_luminance >= 0.0, "zenith_luminance", "must not be negative");
  check(std::isfinite(s.horizontal_illuminance) && s.horizontal_illuminance >= 0.0, "horizontal_illuminance",
        "must not be negative");
  if (s.model == DaylightSettings::Model::Perez && !s.weather) {
    check(std::isfinite(s.direct_normal_w_m2) && s.direct_normal_w_m2 >= 0.0, "direct_normal",
          "must be a number of W/m^2, 0 or more");
    check(std::isfinite(s.diffuse_horizontal_w_m2) && s.diffuse_horizontal_w_m2 >= 0.0, "diffuse_horizontal",
          "must be a number of W/m^2, 0 or more");
  }
  if (s.model == DaylightSettings::Model::Preetham || s.model == DaylightSettings::Model::CieClear)
    check(std::isfinite(s.turbidity) && s.turbidity >= PreethamSky::kMinTurbidity &&
              s.turbidity <= PreethamSky::kMaxTurbidity,
          "turbidity", "must be in [1.7, 10], the range the Preetham model was fitted for");
  check_daylight_cost(s);  // the map's memory and the steps' time, before building

  const auto per_pixel = [](const RadianceOf& radiance) -> RowFiller {
    return [radiance](const Vec3* d, int count, Rgb* out) {
      for (int x = 0; x < count; ++x) out[x] = radiance(d[x]);
    };
  };
  Daylight out;
  out.width = s.width;
  out.height = s.height;
  const size_t upper_size = static_cast<size_t>(s.width) * (s.height / 2);
  std::vector<Eigen::Array3d> sum(upper_size, Eigen::Array3d::Zero());
  std::vector<Rgb> step_pixels;
  Eigen::Array3d analytic = Eigen::Array3d::Zero(), map_total = Eigen::Array3d::Zero();

  const std::vector<Vec3> directions = upper_directions(s.width, s.height);
  // Adds one step's sky: rasterised, then scaled so that its map has the analytic horizontal
  // illuminance (the map is piecewise constant; the correction is a fraction of a percent).
  // `known`: the sky's horizontal illuminance when the model gives it (the Perez sky's).
  auto add_sky = [&](const RowFiller& fill_row, double weight, const Rgb* known = nullptr) {
    const Rgb exact = known ? *known : analytic_horizontal_illuminance(fill_row);
    rasterise_sky(s.width, s.height, directions, fill_row, &step_pixels);
    if (progress) progress->throw_if_cancelled();  // large maps take a while per step
    const Rgb mapped = map_horizontal_illuminance(s.width, s.height, step_pixels);  // reads the upper half only
    const double scale = luminance(mapped) > 0.0f ? luminance(exact) / luminance(mapped) : 1.0;
    tbb::parallel_for(size_t(0), upper_size, [&](size_t i) { sum[i] += (weight * scale) * step_pixels[i].cast<double>(); });
    analytic += weight * exact.cast<double>();
    map_total += (weight * scale) * mapped.cast<double>();
  };

  // One step of a Perez sky: the sky into the map, the sun as its own source.
  auto add_perez_step = [&](const TimeStep& step, const SunPosition& position, const Vec3& sun, bool sun_up) {
    const WeatherHour* row = step.weather_row >= 0 ? &s.weather->hours[static_cast<size_t>(step.weather_row)] : nullptr;
    PerezSkyInput input;
    input.sun = sun;
    if (row) {
      input.day_of_year = day_of_year(row->month, row->day);
      input.direct_normal_w_m2 = row->direct_normal_w_m2;
      input.diffuse_horizontal_w_m2 = row->diffuse_horizontal_w_m2;
      input.dew_point_c = row->dew_point_c;
      input.where = s.weather->path + " line " + std::to_string(row->line);
      if (!sun_up && row->diffuse_horizontal_w_m2 == 0.0) return;  // night
    } else {
      if (!sun_up) return;  // constant irradiances describe the day: no twilight
      input.day_of_year = utc_day_of_year(step.utc_seconds);
      input.direct_normal_w_m2 = s.direct_normal_w_m2;
      input.diffuse_horizontal_w_m2 = s.diffuse_horizontal_w_m2;
      input.dew_point_c = s.dew_point_c;
      input.where = "sky.direct_normal, sky.diffuse_horizontal";
    }
    const PerezAllWeatherSky sky = PerezAllWeatherSky::create(input);
    if (sky.diffuse_horizontal_illuminance() > 0.0) {
      const Rgb known = Rgb::Constant(static_cast<float>(sky.diffuse_horizontal_illuminance()));
      const RowFiller rows = [&sky](const Vec3* d, int count, Rgb* out) {
        const PerezAllWeatherSky::Row row = sky.row(d[0].z());
        for (int x = 0; x < count; ++x)
          out[x] = Rgb::Constant(static_cast<float>(sky.luminance(row, d[x].cast<double>())));
      };
      add_sky(rows, step.weight, &known);
    }
    const double direct = sun_up ? sky.direct_normal_illuminance() : 0.0;
    if (direct > 0.0)
      out.suns.push_back({sun, Rgb::Constant(static_cast<float>(direct * step.weight)), step.weight, step.utc_seconds,
                          position.zenith_deg, position.azimuth_deg});
  };

  if (s.model == DaylightSettings::Model::CieOvercast) {
    const double lz = s.zenith_luminance > 0.0 ? s.zenith_luminance
                      : s.horizontal_illuminance > 0.0 ? s.horizontal_illuminance * 9.0 / (7.0 * kPi)
                                                       : 10000.0 * 9.0 / (7.0 * kPi);
    const RadianceOf overcast = [lz](const Vec3& d) {
      return Rgb::Constant(static_cast<float>(lz * cie_overcast_relative(d.z())));
    };
    add_sky(per_pixel(overcast), 1.0);
    out.steps = 1;
  } else {
    const std::vector<TimeStep> steps = time_steps(s);
    if (progress) progress->start("building the daylight sky", steps.size());
    for (const TimeStep& step : steps) {
      if (progress) {  // a step takes a few milliseconds at the default resolution
        progress->throw_if_cancelled();
        progress->advance();
      }
      ++out.steps;
      const SunPosition position = model_sun_position(step.utc_seconds, s.place, s.north_offset_deg);
      const Vec3 sun = sun_direction(position);
      const bool sun_up = position.zenith_deg < 90.0 && sun.z() > 0.0f;
      out.steps_with_sun += sun_up;
      if (s.model == DaylightSettings::Model::Perez) {
        add_perez_step(step, position, sun, sun_up);
        continue;
      }
      if (!sun_up) continue;  // night: no sky, no sun in these models
      if (s.model == DaylightSettings::Model::Preetham) {
        const PreethamSky sky(s.turbidity, sun);
        const RowFiller rows = [&sky](const Vec3* d, int count, Rgb* out) {
          const PreethamSky::Row row = sky.row(d[0].z());
          for (int x = 0; x < count; ++x) out[x] = sky.radiance(row, d[x]);
        };
        add_sky(rows, step.weight);
      } else {
        const double lz = s.zenith_luminance > 0.0 ? s.zenith_luminance
                                                   : PreethamSky(s.turbidity, sun).zenith_luminance();
        const RadianceOf clear = [lz, sun](const Vec3& d) {
          return Rgb::Constant(static_cast<float>(lz * cie_clear_relative(d, sun)));
        };
        add_sky(per_pixel(clear), step.weight);
      }
      const SunDisk disk = preetham_sun(s.turbidity, position.zenith_deg * kDegree);
      const Rgb e = disk.normal_illuminance() * static_cast<float>(step.weight);
      if (luminance(e) > 0.0f) out.suns.push_back({sun, e, step.weight, step.utc_seconds, position.zenith_deg, position.azimuth_deg});
    }
  }

  out.analytic_sky_horizontal = analytic.cast<float>();
  out.sky_horizontal = map_total.cast<float>();
  out.sun_horizontal = horizontal_illuminance(out.suns);
  // Below the horizon, a diffuse ground lit by the sky and the sun of each step.
  const Rgb ground =
      (out.sky_horizontal + out.sun_horizontal) * static_cast<float>(s.ground_reflectance / kPi);
  out.pixels.assign(static_cast<size_t>(s.width) * s.height, ground);
  for (size_t i = 0; i < upper_size; ++i) out.pixels[i] = sum[i].cast<float>();
  if (s.model == DaylightSettings::Model::Perez && s.weather) {
    out.warnings = s.weather->warnings;
    const std::string far = far_place_warning(s.place, *s.weather, kFarFromStationKm);
    if (!far.empty()) out.warnings.push_back(far);
  }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

namespace {

constexpr double kDaylightBytesPerPixel = 80.0;
constexpr double kDaylightSecondsPerPixel = 40e-9, kDaylightSecondsPerStep = 5e-6;
// Per step with light, besides its pixels: the model's creation, its horizontal illuminance by
// quadrature (96 x 192 directions: Preetham, CIE clear; a Perez sky gives its own) and the sun's
// disk. Measured as CPU time against the pixels' (so that the machine's load cancels): a Preetham or
// CIE clear step costs as much as 24 600 pixels of the map's upper half, 1.0 ms at 40 ns a pixel,
// 1.8 ms measured on the reference machine; a Perez step 3 300 pixels. Rounded up.
constexpr double kDaylightSecondsPerAnalyticStep = 2e-3, kDaylightSecondsPerPerezStep = 0.2e-3;

}  // namespace

double daylight_build_seconds(const DaylightSettings& settings, size_t* steps_out, size_t* up_out) {
  size_t steps = 1, up = 1, lit = 1;
  const bool perez = settings.model == DaylightSettings::Model::Perez;
  if (settings.model != DaylightSettings::Model::CieOvercast) {
    const std::vector<TimeStep> list = time_steps(settings);
    steps = list.size(), up = 0, lit = 0;
    for (const TimeStep& step : list) {
      const bool sun_up = solar_position(step.utc_seconds, settings.place, true).zenith_deg < 90.0;
      up += sun_up;
      // A weather file's twilight rows light the Perez sky too (daylight.cpp).
      lit += sun_up || (perez && settings.weather && step.weather_row >= 0 &&
                        settings.weather->hours[static_cast<size_t>(step.weather_row)].diffuse_horizontal_w_m2 > 0.0);
    }
  }
  if (steps_out) *steps_out = steps;
  if (up_out) *up_out = up;
  const double upper_pixels = static_cast<double>(settings.width) * (settings.height / 2);
  const double per_step = perez ? kDaylightSecondsPerPerezStep : kDaylightSecondsPerAnalyticStep;
  return static_cast<double>(lit) * (upper_pixels * kDaylightSecondsPerPixel + per_step) +
         static_cast<double>(steps) * kDaylightSecondsPerStep;
}

void check_daylight_cost(const DaylightSettings& settings) {
  const double pixels = static_cast<double>(settings.width) * settings.height;
  const MemoryLimit limit = memory_limit();
  const double need = kDaylightBytesPerPixel * pixels;
  std::ostringstream s;
  if (need > static_cast<double>(limit.bytes)) {
    s << "resolution " << settings.width << " x " << settings.height << ": "
      << memory_refusal("building the sky map", need, need, limit, "a smaller sky.resolution");
    throw CostError(s.str());
  }
  size_t steps = 0, up = 0;
  const double seconds = daylight_build_seconds(settings, &steps, &up);
  if (seconds <= kMaxDaylightSeconds) return;
  s << "the interval needs " << format_count(static_cast<double>(steps)) << " time steps of " << settings.step_minutes
    << " min (" << format_count(static_cast<double>(up)) << " with the sun up) at " << settings.width << " x "
    << settings.height << " pixels: building the sky would take about " << std::lround(seconds / 60.0) << " min ("
    << format_count(seconds) << " s on the 2-core reference machine; at most " << format_count(kMaxDaylightSeconds)
    << " s): use a larger sky.step_minutes, a shorter interval (sky.date_end, sky.start, sky.end) or a smaller "
       "sky.resolution";
  throw CostError(s.str());
}

}  // namespace fenestra
