#include "daylight/local_time.h"

#include <date/date.h>
#include <date/tz.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "util/quoted_text.h"

namespace fenestra {

namespace {

constexpr double kSecondsPerDay = 86400.0;
constexpr double kMaxOffsetHours = 14.0;  // the farthest civil offsets in use are -12 and +14

bool is_digit(char c) { return c >= '0' && c <= '9'; }

// Reads exactly `count` decimal digits at `pos`; false when any of them is not a digit.
bool read_digits(const std::string& text, size_t pos, size_t count, int* value) {
  if (pos + count > text.size()) return false;
  *value = 0;
  for (size_t i = pos; i < pos + count; ++i) {
    if (!is_digit(text[i])) return false;
    *value = 10 * *value + (text[i] - '0');
  }
  return true;
}

std::string quoted(const std::string& text) { return "\"" + quoted_text(text) + "\""; }

date::sys_days to_sys_days(const LocalDate& d) {
  return date::sys_days(date::year(d.year) / date::month(static_cast<unsigned>(d.month)) /
                        date::day(static_cast<unsigned>(d.day)));
}

LocalDate from_sys_days(date::sys_days days) {
  const date::year_month_day ymd(days);
  return {static_cast<int>(ymd.year()), static_cast<int>(static_cast<unsigned>(ymd.month())),
          static_cast<int>(static_cast<unsigned>(ymd.day()))};
}

// Seconds from 1970-01-01T00:00 to midnight starting `d` (on the same clock, local or UTC).
double midnight_seconds(const LocalDate& d) {
  return kSecondsPerDay * static_cast<double>(to_sys_days(d).time_since_epoch().count());
}

}  // namespace

LocalDate parse_date(const std::string& text) {
  LocalDate d;
  if (text.size() != 10 || text[4] != '-' || text[7] != '-' || !read_digits(text, 0, 4, &d.year) ||
      !read_digits(text, 5, 2, &d.month) || !read_digits(text, 8, 2, &d.day))
    throw std::invalid_argument("date " + quoted(text) + " is not of the form YYYY-MM-DD");
  if (d.year < 1) throw std::invalid_argument("date " + quoted(text) + ": the year must be 0001 or later");
  if (d.month < 1 || d.month > 12)
    throw std::invalid_argument("date " + quoted(text) + ": month " + std::to_string(d.month) + " is not 1 to 12");
  const date::year_month_day_last last(date::year(d.year), date::month_day_last(date::month(d.month)));
  const int days_in_month = static_cast<int>(static_cast<unsigned>(last.day()));
  if (d.day < 1 || d.day > days_in_month)
    throw std::invalid_argument("date " + quoted(text) + " does not exist: that month has " +
                                std::to_string(days_in_month) + " days");
  return d;
}

double parse_clock_minutes(const std::string& text) {
  // Hours take one or two digits ("7:30" or "07:30"); minutes and seconds take two.
  const size_t colon = text.find(':');
  int hours = 0, minutes = 0, seconds = 0;
  bool ok = (colon == 1 || colon == 2) && read_digits(text, 0, colon, &hours) && read_digits(text, colon + 1, 2, &minutes);
  const size_t after_minutes = colon + 3;
  if (ok && text.size() != after_minutes)
    ok = text.size() == after_minutes + 3 && text[after_minutes] == ':' && read_digits(text, after_minutes + 1, 2, &seconds);
  if (!ok) throw std::invalid_argument("clock time " + quoted(text) + " is not of the form HH:MM or HH:MM:SS");
  if (minutes > 59 || seconds > 59)
    throw std::invalid_argument("clock time " + quoted(text) + ": minutes and seconds must be 00 to 59");
  const double total = 60.0 * hours + minutes + seconds / 60.0;
  if (total > 1440.0) throw std::invalid_argument("clock time " + quoted(text) + " is past 24:00");
  return total;
}

LocalDate add_days(const LocalDate& d, int days) { return from_sys_days(to_sys_days(d) + date::days(days)); }

int days_between(const LocalDate& from, const LocalDate& to) {
  return static_cast<int>((to_sys_days(to) - to_sys_days(from)).count());
}

std::string to_string(const LocalDate& d) {
  char text[32];
  std::snprintf(text, sizeof text, "%04d-%02d-%02d", d.year, d.month, d.day);
  return text;
}

TimeZone TimeZone::fixed(double utc_offset_hours) {
  if (!std::isfinite(utc_offset_hours) || std::abs(utc_offset_hours) > kMaxOffsetHours)
    throw std::invalid_argument("UTC offset " + std::to_string(utc_offset_hours) + " h is outside -14 to +14 h");
  TimeZone zone;
  zone.offset_hours_ = utc_offset_hours;
  return zone;
}

TimeZone TimeZone::named(const std::string& iana_name) {
  TimeZone zone;
  try {
    zone.zone_ = date::locate_zone(iana_name);
  } catch (const std::exception& e) {
    throw std::invalid_argument("unknown time zone " + quoted(iana_name) + " (" + e.what() + ")");
  }
  zone.iana_ = iana_name;
  return zone;
}

double TimeZone::utc_offset_hours(double utc_seconds) const {
  if (!zone_) return offset_hours_;
  if (!std::isfinite(utc_seconds)) throw std::invalid_argument("time zone " + iana_ + ": the instant is not finite");
  const date::sys_seconds instant{std::chrono::seconds(static_cast<long long>(std::floor(utc_seconds)))};
  return zone_->get_info(instant).offset.count() / 3600.0;
}

double TimeZone::utc_seconds(const LocalDate& d, double minutes) const {
  if (!std::isfinite(minutes)) throw std::invalid_argument("clock minutes after midnight of " + to_string(d) + " are not finite");
  const double local = midnight_seconds(d) + 60.0 * minutes;
  if (!zone_) return local - 3600.0 * offset_hours_;
  const date::local_seconds wall{std::chrono::seconds(static_cast<long long>(std::floor(local)))};
  // For a skipped or repeated wall time, `first` is the period in force before the change.
  const date::local_info info = zone_->get_info(wall);
  return local - static_cast<double>(info.first.offset.count());
}

double TimeZone::local_minutes(const LocalDate& d, double utc_seconds) const {
  const double local = utc_seconds + 3600.0 * utc_offset_hours(utc_seconds);
  return (local - midnight_seconds(d)) / 60.0;
}

std::string TimeZone::name() const {
  if (zone_) return iana_;
  const long total_minutes = std::lround(60.0 * offset_hours_);
  char text[32];
  std::snprintf(text, sizeof text, "UTC%c%02ld:%02ld", total_minutes < 0 ? '-' : '+', std::labs(total_minutes) / 60,
                std::labs(total_minutes) % 60);
  return text;
}

}  // namespace fenestra
