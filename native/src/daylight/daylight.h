#pragma once
// Daylight for a place and a time interval: the sky of every time step, averaged into one
// equirectangular environment map (sky above the horizon, ground below), and the sun of every
// step kept as an explicit directional source. Units: radiance in cd/m^2, illuminance in lux.
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "daylight/local_time.h"
#include "daylight/solar_position.h"
#include "daylight/sun_light.h"
#include "util/progress.h"

namespace fenestra {

struct WeatherData;  // daylight/weather_file.h

struct DaylightSettings {
  enum class Model { Preetham, CieOvercast, CieClear, Perez };
  Model model = Model::Preetham;
  Place place;
  TimeZone time_zone = TimeZone::fixed(0.0);
  LocalDate date, date_end;                  // date_end == date: one day
  double start_minutes = 9 * 60.0, end_minutes = 17 * 60.0;  // local clock; end < start crosses midnight
  double step_minutes = 15.0;
  double turbidity = 3.0;                    // Preetham sky and sun (and the CIE clear sky's sun)
  double ground_reflectance = 0.2;           // below the horizon: reflectance * horizontal illuminance / pi
  double north_offset_deg = 0.0;             // true north, clockwise from +Y seen from above
  double zenith_luminance = 0.0;             // cd/m^2; CIE skies (0: see docs/sky.md)
  double horizontal_illuminance = 0.0;       // lux; CIE overcast alternative to zenith_luminance
  int width = 1024, height = 512;            // map size in pixels
  // Perez all-weather sky (daylight/perez_all_weather.h): the irradiance of every step, either
  // constant (W/m^2; dew point deg C, NaN when unknown; only steps with the sun up give light) ...
  double direct_normal_w_m2 = 0.0, diffuse_horizontal_w_m2 = 0.0;
  double dew_point_c = std::numeric_limits<double>::quiet_NaN();
  // ... or from a weather file: each step takes the row whose hour of the file's standard time holds
  // it (month and day only; twilight rows light the sky as in the sky matrix).
  std::shared_ptr<const WeatherData> weather;
  // With `weather`: when not empty, these rows are the steps, each at its own instant and weighted
  // equally, instead of the date and interval above (a climate's occupied hours).
  std::vector<size_t> weather_rows;
  std::string describe() const;
};

// The instants that stand for the interval: midpoints of steps of step_minutes (the last one
// shorter if the interval is not a multiple), each weighted by its share of the whole.
struct TimeStep {
  double utc_seconds = 0.0;
  double weight = 0.0;  // sums to 1 over the steps
  int weather_row = -1;  // Perez sky from a weather file: the row that gives the step's irradiance
};
std::vector<TimeStep> time_steps(const DaylightSettings& settings);

struct Daylight {
  int width = 0, height = 0;
  std::vector<Rgb> pixels;         // row-major, top row = zenith (Blender's convention), cd/m^2
  std::vector<SunLight> suns;      // one per step with the sun above the horizon
  Rgb sky_horizontal = Rgb::Zero();     // lux, interval mean, from the map's upper hemisphere
  Rgb sun_horizontal = Rgb::Zero();     // lux, interval mean, from the sun list
  Rgb analytic_sky_horizontal = Rgb::Zero();  // lux, mean of the per-step values of the analytic model
  size_t steps = 0, steps_with_sun = 0;
  double seconds = 0.0;            // time taken to build it
  std::vector<std::string> warnings;  // a weather file's, and a place far from its station
};

// Throws std::invalid_argument naming the setting at fault. With `progress`, reports the time
// steps done and polls cancellation between them (throws Cancelled).
Daylight make_daylight(const DaylightSettings& settings, Progress* progress = nullptr);

// Horizontal illuminance of an equirectangular map's upper hemisphere (exact per-pixel solid
// angles: pixels are piecewise constant), in the map's radiance units times sr.
Rgb map_horizontal_illuminance(int width, int height, const std::vector<Rgb>& pixels);

// Building a daylight sky must fit in memory (80 bytes per map pixel) and take at most
// kMaxDaylightSeconds on the reference machine (each step with the sun up rasterises the upper
// half of the map, about 40 ns per pixel, and creates its sky: 2 ms, 0.2 ms for a Perez sky).
// check_daylight_cost throws CostError naming the figure and the setting to change.
inline constexpr double kMaxDaylightSeconds = 300.0;
double daylight_build_seconds(const DaylightSettings& settings, size_t* steps = nullptr, size_t* steps_with_sun = nullptr);
void check_daylight_cost(const DaylightSettings& settings);

}  // namespace fenestra
