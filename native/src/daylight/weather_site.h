#pragma once
// Where and when a weather file's rows are: the UTC instant each row stands for (for the sun), the
// row whose hour holds a given instant, and how far a place is from the file's station.
//
// Weather files give a month, a day and a clock hour of local STANDARD time (a fixed offset from
// UTC, the file's time zone; no daylight saving), but no usable year: a typical year joins months
// of different years. The sun is therefore placed in one reference year, 2022, or the leap year
// 2020 when the rows include 29 February. Over a four-year cycle the sun's place at a given date
// and clock drifts by about a quarter of a day of its yearly path, at most 0.1 degree.
#include <string>
#include <vector>

#include "daylight/annual_metrics.h"  // HourStamp
#include "daylight/solar_position.h"  // Place
#include "daylight/weather_file.h"

namespace fenestra {

class WeatherClock {
 public:
  static constexpr int kReferenceYear = 2022, kLeapReferenceYear = 2020;

  // The file's rows in its own time zone, or in `time_zone_hours` of standard time (east positive)
  // when the caller knows better (ClimateSettings::time_zone_hours).
  explicit WeatherClock(const WeatherData& weather) : WeatherClock(weather, weather.location.time_zone_hours) {}
  WeatherClock(const WeatherData& weather, double time_zone_hours);

  int year() const { return year_; }
  double time_zone_hours() const { return time_zone_hours_; }
  size_t rows() const { return utc_.size(); }

  // POSIX seconds (UTC) of the instant row `row` stands for: its clock_hours (EPW: the middle of the
  // hour the row ends, hour_ending - 0.5; .wea: the decimal hour as written) in local standard time.
  double utc_seconds(size_t row) const { return utc_[row]; }
  // The row's month, day and clock hour in [0, 24) (a .wea instant written as 24.0 is the next
  // day's 0:00), for the annual metrics.
  HourStamp stamp(size_t row) const;

  // The row whose hour of local standard time holds the instant, by month, day and hour only (the
  // instant's year is ignored); -1 when the file has no row there. An EPW row holds
  // [hour_ending - 1, hour_ending); a .wea row the clock hour (h - 1, h] its instant lies in
  // (12.5 and 13.0 both hold 12:00-13:00). When two .wea rows share an hour, the first is used.
  int row_at(double utc_seconds) const;
  // The local standard hour that holds an instant, for messages: "6/21 12:00-13:00 UTC-6".
  std::string hour_text(double utc_seconds) const;

 private:
  static constexpr int kDaySlots = 366;  // 29 February always has its own slot
  int year_ = kReferenceYear;
  double time_zone_hours_ = 0.0;
  std::vector<double> utc_;       // per row
  std::vector<HourStamp> stamps_;  // per row
  std::vector<int> slots_;        // kDaySlots x 24: row index or -1
};

// A place farther than this from a weather file's station is warned about: the file then
// describes another climate (ClimateSettings::kFarKm).
constexpr double kFarFromStationKm = 100.0;

// Great-circle distance between two places on a sphere of the Earth's mean radius (6371 km), km.
double distance_km(double latitude1_deg, double longitude1_deg, double latitude2_deg, double longitude2_deg);

// A warning naming both places when `place` lies more than `far_km` from the weather file's
// station, or "" when it is closer: the file's sky then describes another climate.
std::string far_place_warning(const Place& place, const WeatherData& weather, double far_km);

}  // namespace fenestra
