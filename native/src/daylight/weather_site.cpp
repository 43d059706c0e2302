#include "daylight/weather_site.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "math/constants.h"

namespace fenestra {
namespace {

constexpr double kSecondsPerDay = 86400.0, kSecondsPerHour = 3600.0;
constexpr double kEarthRadiusKm = 6371.0;
// Days before each month in a leap year: every month and day has a slot of its own.
constexpr int kLeapDaysBeforeMonth[12] = {0, 31, 60, 91, 121, 152, 182, 213, 244, 274, 305, 335};
const LocalDate kEpoch{1970, 1, 1};

int day_slot(int month, int day) { return kLeapDaysBeforeMonth[month - 1] + day - 1; }

// The hour of the day (0..23) a row's hour of local standard time starts at.
int row_hour(const WeatherHour& h) {
  const double ending = std::isnan(h.hour_ending) ? std::ceil(h.clock_hours) : h.hour_ending;
  return std::clamp(static_cast<int>(ending) - 1, 0, 23);
}

// Local standard date and seconds after its midnight of a UTC instant.
LocalDate local_date(double utc_seconds, double zone_hours, double* seconds_of_day) {
  const double t = utc_seconds + zone_hours * kSecondsPerHour;
  const double days = std::floor(t / kSecondsPerDay);
  *seconds_of_day = t - days * kSecondsPerDay;
  return add_days(kEpoch, static_cast<int>(days));
}

std::string offset_text(double hours) {
  std::ostringstream s;
  s << "UTC" << (hours < 0 ? "" : "+") << hours;
  return s.str();
}

}  // namespace

WeatherClock::WeatherClock(const WeatherData& weather, double time_zone_hours)
    : year_(weather.year_hours() == 8784 ? kLeapReferenceYear : kReferenceYear),
      time_zone_hours_(time_zone_hours),
      slots_(static_cast<size_t>(kDaySlots) * 24, -1) {
  utc_.reserve(weather.hours.size());
  stamps_.reserve(weather.hours.size());
  for (size_t i = 0; i < weather.hours.size(); ++i) {
    const WeatherHour& h = weather.hours[i];
    const LocalDate date{year_, h.month, h.day};
    const double utc = days_between(kEpoch, date) * kSecondsPerDay + (h.clock_hours - time_zone_hours_) * kSecondsPerHour;
    utc_.push_back(utc);
    // The stamp in [0, 24): a .wea instant at 24.0 is the next day's midnight.
    double seconds = 0.0;
    const LocalDate d = local_date(utc, time_zone_hours_, &seconds);
    stamps_.push_back({d.month, d.day, seconds / kSecondsPerHour});
    int& slot = slots_[static_cast<size_t>(day_slot(h.month, h.day)) * 24 + row_hour(h)];
    if (slot < 0) slot = static_cast<int>(i);
  }
}

HourStamp WeatherClock::stamp(size_t row) const { return stamps_[row]; }

int WeatherClock::row_at(double utc_seconds) const {
  double seconds = 0.0;
  const LocalDate d = local_date(utc_seconds, time_zone_hours_, &seconds);
  const int hour = std::clamp(static_cast<int>(std::floor(seconds / kSecondsPerHour)), 0, 23);
  return slots_[static_cast<size_t>(day_slot(d.month, d.day)) * 24 + hour];
}

std::string WeatherClock::hour_text(double utc_seconds) const {
  double seconds = 0.0;
  const LocalDate d = local_date(utc_seconds, time_zone_hours_, &seconds);
  const int hour = std::clamp(static_cast<int>(std::floor(seconds / kSecondsPerHour)), 0, 23);
  char text[64];
  std::snprintf(text, sizeof text, "%d/%d %02d:00-%02d:00 ", d.month, d.day, hour, hour + 1);
  return text + offset_text(time_zone_hours_) + " (local standard time)";
}

double distance_km(double latitude1_deg, double longitude1_deg, double latitude2_deg, double longitude2_deg) {
  // Haversine: well conditioned for short distances.
  const double r = kPiD / 180.0;
  const double dlat = (latitude2_deg - latitude1_deg) * r, dlon = (longitude2_deg - longitude1_deg) * r;
  const double a = std::sin(0.5 * dlat) * std::sin(0.5 * dlat) +
                   std::cos(latitude1_deg * r) * std::cos(latitude2_deg * r) * std::sin(0.5 * dlon) * std::sin(0.5 * dlon);
  return 2.0 * kEarthRadiusKm * std::asin(std::min(1.0, std::sqrt(a)));
}

std::string far_place_warning(const Place& place, const WeatherData& weather, double far_km) {
  const WeatherLocation& w = weather.location;
  const double km = distance_km(place.latitude_deg, place.longitude_deg, w.latitude_deg, w.longitude_deg);
  if (!(km > far_km)) return "";
  std::ostringstream s;
  s.precision(6);
  s << "the scene's place (latitude " << place.latitude_deg << ", longitude " << place.longitude_deg << ") is "
    << std::lround(km) << " km from the weather file's station '" << weather.path << "' (" << w.to_string()
    << "), more than " << far_km << " km: its sky describes another climate";
  return s.str();
}

}  // namespace fenestra
