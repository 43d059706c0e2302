#pragma once
// Civil dates and clock times of a place, and their conversion to UTC (fixed offsets or IANA zones).
#include <string>

namespace fenestra {

struct LocalDate {
  int year = 2000, month = 1, day = 1;
};

// "YYYY-MM-DD"; throws std::invalid_argument naming the text when it is not a real date.
LocalDate parse_date(const std::string& text);
// "HH:MM" or "HH:MM:SS" (00:00 to 24:00) -> minutes after midnight; throws std::invalid_argument.
double parse_clock_minutes(const std::string& text);
// The date `days` after `date` (negative allowed).
LocalDate add_days(const LocalDate& date, int days);
// Days from `from` to `to` (negative when `to` is earlier).
int days_between(const LocalDate& from, const LocalDate& to);

class TimeZone {
 public:
  // Fixed offset from UTC in hours (e.g. +2 for Athens in summer, -7 for Denver in winter), |offset| <= 14.
  static TimeZone fixed(double utc_offset_hours);
  // An IANA zone name ("Europe/Athens"), read from the system's time zone database (daylight saving
  // time included); throws std::invalid_argument naming the zone when it is unknown.
  static TimeZone named(const std::string& iana_name);

  // POSIX seconds (UTC) of `minutes` after local midnight of `date` (minutes may exceed 24 h).
  double utc_seconds(const LocalDate& date, double minutes) const;
  std::string name() const;

 private:
  TimeZone() = default;
  double offset_hours_ = 0.0;
  std::string iana_;  // empty for a fixed offset
};

}  // namespace fenestra
