#pragma once
// Civil dates and clock times of a place, and their conversion to UTC (fixed offsets or IANA zones).
#include <string>

namespace date {
class time_zone;
}

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
// "YYYY-MM-DD".
std::string to_string(const LocalDate& date);

class TimeZone {
 public:
  // Fixed offset from UTC in hours (e.g. +2 for Athens in summer, -7 for Denver in winter), |offset| <= 14.
  static TimeZone fixed(double utc_offset_hours);
  // An IANA zone name ("Europe/Athens"), read from the system's time zone database (daylight saving
  // time included); throws std::invalid_argument naming the zone when it is unknown.
  static TimeZone named(const std::string& iana_name);

  // POSIX seconds (UTC) of `minutes` after local midnight of `date` (minutes may exceed 24 h or be
  // negative: the wall clock simply runs on into the next or previous days).
  // A wall-clock time that a daylight-saving change skips (spring forward) or repeats (fall back) is
  // read with the offset in force before the change: a skipped 02:30 is the instant the clock would
  // have shown 02:30 had it not jumped, and a repeated 02:30 is its first occurrence.
  double utc_seconds(const LocalDate& date, double minutes) const;
  // The inverse: the wall-clock minutes after local midnight of `date` shown at a UTC instant
  // (beyond 1440 on later days, negative on earlier ones).
  double local_minutes(const LocalDate& date, double utc_seconds) const;
  // Offset from UTC, in hours, in force at a UTC instant.
  double utc_offset_hours(double utc_seconds) const;
  // "UTC+02:00" for a fixed offset, the IANA name otherwise.
  std::string name() const;

 private:
  TimeZone() = default;
  double offset_hours_ = 0.0;
  std::string iana_;                        // empty for a fixed offset
  const date::time_zone* zone_ = nullptr;  // the IANA zone, owned by the time zone database
};

}  // namespace fenestra
