#pragma once
// Hourly weather files read for climate-based daylight: EnergyPlus weather (.epw) and Radiance /
// DAYSIM weather tapes (.wea). Every value is checked where it is read (docs/sky.md, "Weather
// files"): a file that breaks the format or physics is refused with std::invalid_argument naming
// file:line, the field and its value; oddities that real files have are kept as warnings.
// Units: irradiance W/m^2 (an hour's Wh/m^2 is its mean W/m^2), illuminance lux, degrees, meters.
#include <string>
#include <vector>

namespace fenestra {

struct WeatherLocation {
  std::string name;             // city, region, country as the file gives them
  double latitude_deg = 0.0;    // north positive, [-90, 90]
  double longitude_deg = 0.0;   // EAST positive, [-180, 180] (a .wea stores it west positive)
  double time_zone_hours = 0.0; // standard-time offset from UTC, east positive, [-12, 14]
                                // (Chicago: -6; a .wea stores 15 degrees per hour, west positive)
  double elevation_m = 0.0;     // above sea level, [-1000, 9999.9]
  std::string to_string() const;
};

struct WeatherHour {
  int month = 1, day = 1;
  // EPW: the row's hour, 1 to 24; the row covers [hour_ending - 1, hour_ending) of local standard
  // time. .wea: NaN (the format gives an instant, not the interval it stands for).
  double hour_ending = 0.0;
  // Local standard time (hours after midnight) of the instant the row stands for: the middle of
  // the hour for EPW (hour_ending - 0.5); for .wea the decimal hour as written (usually x.5).
  double clock_hours = 0.0;
  double direct_normal_w_m2 = 0.0;       // required
  double diffuse_horizontal_w_m2 = 0.0;  // required
  double global_horizontal_w_m2 = 0.0;   // NaN when missing (always for .wea)
  double direct_normal_lux = 0.0;        // NaN when missing (always for .wea)
  double diffuse_horizontal_lux = 0.0;   // NaN when missing (always for .wea)
  double global_horizontal_lux = 0.0;    // NaN when missing (always for .wea)
  double dew_point_c = 0.0;              // NaN when missing (always for .wea)
  int line = 0;                          // line of the file the row was read from (1-based), for messages
};

struct WeatherData {
  std::string path;
  WeatherLocation location;
  // EPW: one full year, 8760 or 8784 rows from 1 January hour 1 to 31 December hour 24.
  // .wea: the rows the file holds (any number from one), in time order within one year.
  std::vector<WeatherHour> hours;
  // Non-fatal oddities, one line per kind with a count and the first occurrence (docs/sky.md).
  std::vector<std::string> warnings;

  // Hours in the year the rows belong to: 8784 when they include 29 February, else 8760.
  int year_hours() const;
  std::string to_string() const;
};

// Both throw std::invalid_argument ("path:line: field ...: value ...") for any refused input.
WeatherData read_epw(const std::string& path);
WeatherData read_wea(const std::string& path);
// By extension, case-insensitive: .epw or .wea; any other extension is refused.
WeatherData read_weather(const std::string& path);

// Day of the year, 1..365, of a month and day, for the Earth-Sun distance: 29 February counts as day
// 60, like 1 March (weather rows carry no year). Throws std::invalid_argument for an impossible date.
int day_of_year(int month, int day);

// The solar irradiance at normal incidence outside the atmosphere on a date, W/m^2: the solar
// constant 1367 W/m^2 times the orbit's eccentricity factor (Spencer 1971, in Iqbal 1983 eq.
// 1.2.1: 1415 W/m^2 on 1 January, 1322 W/m^2 in early July). 29 February counts as day 60. No
// hourly irradiance can exceed it. Throws std::invalid_argument for an impossible date.
double extraterrestrial_normal_irradiance(int month, int day);

}  // namespace fenestra
