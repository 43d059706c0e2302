#include "daylight/weather_file.h"

#include "daylight/perez_all_weather.h"
#include "util/out_of_memory.h"
#include "util/whole_file.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <system_error>
#include <utility>

#include "util/quoted_text.h"

namespace fenestra {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Luminous solar constant: published values run from 127.5 klx (IES) to 133.3 klx (Darula,
// Kittler & Gueymard 2005); 134 klx bounds them all, so no file is refused over the choice.
constexpr double kLuminousSolarConstant = 134000.0;  // lux

// EnergyPlus missing-value codes: a value at or above the code is missing (Auxiliary Programs,
// "EnergyPlus Weather File (EPW) Data Dictionary").
constexpr double kMissingIrradiance = 9999.0;
constexpr double kMissingIlluminance = 999900.0;
constexpr double kMissingDewPoint = 99.9;
constexpr double kMinDewPoint = -70.0, kMaxDewPoint = 70.0;  // exclusive, from the same dictionary

constexpr double kMinTimeZone = -12.0, kMaxTimeZone = 14.0;      // hours: civil offsets in use
constexpr double kMinElevation = -1000.0, kMaxElevation = 9999.9;  // m: EPW dictionary, Radiance
// Diffuse above global horizontal is tolerated up to this, beyond which it is a warning: rounding
// of the two columns to whole Wh/m^2 and their separate quality control leave a few W/m^2.
constexpr double kDiffuseExcessAbsolute = 1.0;   // W/m^2
constexpr double kDiffuseExcessRelative = 0.01;  // of global horizontal
// The clock of a standard time zone stays within this of the sun's (longitude / 15 hours) in every
// real zone (western China is the farthest, about 3 h); beyond it the longitude's sign is suspect.
constexpr double kMaxZoneSolarTimeGap = 3.5;  // hours

constexpr int kEpwHeaderLines = 8;
constexpr int kEpwFields = 35;

// ---- Text ----

std::string quoted(const std::string& text) { return "\"" + quoted_text(text) + "\""; }

std::string trim(const std::string& text) {
  const size_t begin = text.find_first_not_of(" \t");
  if (begin == std::string::npos) return "";
  const size_t end = text.find_last_not_of(" \t");
  return text.substr(begin, end - begin + 1);
}

std::string lower(std::string text) {
  for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return text;
}

bool starts_with_ci(const std::string& text, const std::string& prefix) {
  return text.size() >= prefix.size() && lower(text.substr(0, prefix.size())) == lower(prefix);
}

std::vector<std::string> split(const std::string& line, char separator) {
  std::vector<std::string> fields;
  size_t start = 0;
  for (;;) {
    const size_t end = line.find(separator, start);
    fields.push_back(line.substr(start, end == std::string::npos ? std::string::npos : end - start));
    if (end == std::string::npos) return fields;
    start = end + 1;
  }
}

std::vector<std::string> split_whitespace(const std::string& line) {
  std::vector<std::string> fields;
  std::istringstream in(line);
  std::string token;
  while (in >> token) fields.push_back(token);
  return fields;
}

std::string format_number(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", value);
  return buffer;
}

// A finite decimal number and nothing else (surrounding blanks allowed); independent of the
// C locale, so a decimal comma never passes.
std::optional<double> parse_number(const std::string& raw) {
  std::string text = trim(raw);
  if (!text.empty() && text[0] == '+') text.erase(0, 1);
  if (text.empty() || !(std::isdigit(static_cast<unsigned char>(text[0])) || text[0] == '-' || text[0] == '.'))
    return std::nullopt;
  double value = 0.0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() || !std::isfinite(value)) return std::nullopt;
  return value;
}

std::optional<int> parse_integer(const std::string& raw) {
  std::string text = trim(raw);
  if (!text.empty() && text[0] == '+') text.erase(0, 1);
  int value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || error != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return value;
}

// ---- Where a value came from, for the messages ----

struct Source {
  const std::string& path;
  int line;  // 1-based
};

[[noreturn]] void refuse(const Source& at, const std::string& message) {
  throw std::invalid_argument(at.path + ":" + std::to_string(at.line) + ": " + message);
}

[[noreturn]] void refuse_field(const Source& at, const std::string& field, const std::string& value,
                               const std::string& why) {
  refuse(at, field + " " + quoted(trim(value)) + ": " + why);
}

double number_field(const Source& at, const std::string& field, const std::string& text) {
  const std::optional<double> value = parse_number(text);
  if (!value) refuse_field(at, field, text, trim(text).empty() ? "empty; a number is needed" : "not a number");
  return *value;
}

int integer_field(const Source& at, const std::string& field, const std::string& text) {
  const std::optional<int> value = parse_integer(text);
  if (!value) refuse_field(at, field, text, trim(text).empty() ? "empty; a whole number is needed" : "not a whole number");
  return *value;
}

double checked_range(const Source& at, const std::string& field, const std::string& text, double value,
                     double min, double max, const std::string& what) {
  if (value < min || value > max)
    refuse_field(at, field, text, what + " outside [" + format_number(min) + ", " + format_number(max) + "]");
  return value;
}

// ---- Calendar ----

constexpr int kDaysInMonth[12] = {31, 29, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};  // 29 February allowed
constexpr int kDaysBeforeMonth[12] = {0, 31, 59, 90, 120, 151, 181, 212, 243, 273, 304, 334};

bool valid_date(int month, int day) { return month >= 1 && month <= 12 && day >= 1 && day <= kDaysInMonth[month - 1]; }

// (mean Sun-Earth distance / distance)^2 on a date: the Perez sky's series (Spencer 1971).
double eccentricity_factor(int month, int day) {
  return extraterrestrial_normal_irradiance(day_of_year(month, day)) / kPerezSolarConstant;
}

std::string date_text(int month, int day) { return std::to_string(month) + "/" + std::to_string(day); }

// Month and day fields, checked together (the day depends on the month).
void read_date(const Source& at, const std::string& month_field, const std::string& month_text,
               const std::string& day_field, const std::string& day_text, WeatherHour* hour) {
  hour->month = integer_field(at, month_field, month_text);
  if (hour->month < 1 || hour->month > 12) refuse_field(at, month_field, month_text, "not a month 1 to 12");
  hour->day = integer_field(at, day_field, day_text);
  if (!valid_date(hour->month, hour->day))
    refuse_field(at, day_field, day_text,
                 "month " + std::to_string(hour->month) + " has no such day (1 to " +
                     std::to_string(kDaysInMonth[hour->month - 1]) + ")");
}

// ---- Radiometry ----

enum class Requirement { Required, Optional };

// An irradiance column (W/m^2): at or above `missing_code` it is missing (NaN, or refused when
// required); otherwise it must lie in [0, extraterrestrial normal irradiance of the date].
double irradiance_field(const Source& at, const std::string& field, const std::string& text, const WeatherHour& hour,
                        Requirement requirement, double missing_code) {
  if (requirement == Requirement::Optional && trim(text).empty()) return kNaN;
  const double value = number_field(at, field, text);
  if (missing_code > 0.0 && value >= missing_code) {
    if (requirement == Requirement::Optional) return kNaN;
    refuse_field(at, field, text, "the missing-value code (" + format_number(missing_code) +
                                      " or more), but this value is required");
  }
  if (value < 0.0) refuse_field(at, field, text, "negative irradiance");
  const double limit = extraterrestrial_normal_irradiance(hour.month, hour.day);
  if (value > limit)
    refuse_field(at, field, text, "exceeds the extraterrestrial normal irradiance of " + date_text(hour.month, hour.day) +
                                      " (" + format_number(limit) + " W/m2)");
  return value;
}

// An illuminance column (lux), always optional: missing at 999900 or above, else in
// [0, luminous solar constant x eccentricity factor].
double illuminance_field(const Source& at, const std::string& field, const std::string& text, const WeatherHour& hour) {
  if (trim(text).empty()) return kNaN;
  const double value = number_field(at, field, text);
  if (value >= kMissingIlluminance) return kNaN;
  if (value < 0.0) refuse_field(at, field, text, "negative illuminance");
  const double limit = kLuminousSolarConstant * eccentricity_factor(hour.month, hour.day);
  if (value > limit)
    refuse_field(at, field, text, "exceeds the extraterrestrial normal illuminance of " + date_text(hour.month, hour.day) +
                                      " (" + format_number(limit) + " lux)");
  return value;
}

double dew_point_field(const Source& at, const std::string& field, const std::string& text) {
  if (trim(text).empty()) return kNaN;
  const double value = number_field(at, field, text);
  if (value >= kMissingDewPoint) return kNaN;
  if (value <= kMinDewPoint || value >= kMaxDewPoint)
    refuse_field(at, field, text, "dew point outside (-70, 70) degrees C and not the missing code 99.9");
  return value;
}

// ---- Warnings: one line per kind, counted, with the first occurrence ----

struct WarningTally {
  explicit WarningTally(std::string kind) : what(std::move(kind)) {}
  std::string what;
  int count = 0;
  std::string first;
  void add(const std::string& occurrence) {
    if (count++ == 0) first = occurrence;
  }
  void report(std::vector<std::string>* warnings) const {
    if (count > 0) warnings->push_back(std::to_string(count) + " " + what + " (first: " + first + ")");
  }
};

void check_diffuse_within_global(const Source& at, const WeatherHour& hour, WarningTally* tally) {
  const double global = hour.global_horizontal_w_m2;
  if (std::isnan(global)) return;
  if (hour.diffuse_horizontal_w_m2 > global + kDiffuseExcessAbsolute + kDiffuseExcessRelative * global)
    tally->add("line " + std::to_string(at.line) + ", " + date_text(hour.month, hour.day) + " " +
               format_number(hour.clock_hours) + " h: diffuse " + format_number(hour.diffuse_horizontal_w_m2) +
               " > global " + format_number(global) + " W/m2");
}

void check_time_zone_against_longitude(const WeatherLocation& location, const std::string& longitude_convention,
                                       std::vector<std::string>* warnings) {
  const double gap = std::remainder(location.time_zone_hours - location.longitude_deg / 15.0, 24.0);
  if (std::abs(gap) > kMaxZoneSolarTimeGap)
    warnings->push_back("time zone UTC" + std::string(location.time_zone_hours < 0 ? "" : "+") +
                        format_number(location.time_zone_hours) + " is " + format_number(std::abs(gap)) +
                        " h from the sun's time at longitude " + format_number(location.longitude_deg) +
                        " (east positive); check the sign of the longitude (" + longitude_convention + ")");
}

// ---- Files ----

// The lines of a text file without their line ends (LF or CRLF) and without trailing blank
// lines; a UTF-8 byte order mark is dropped.
std::vector<std::string> read_lines(const std::string& path) {
  std::error_code error;
  const auto status = std::filesystem::status(path, error);
  if (error || !std::filesystem::exists(status))
    throw std::invalid_argument(path + ": cannot be read: no such file");
  if (std::filesystem::is_directory(status)) throw std::invalid_argument(path + ": cannot be read: it is a directory");
  std::vector<std::string> lines;
  out_of_memory_while("reading weather file '" + quoted_path(path) + "'", [&] {
    const std::string text = read_whole_file(path, "weather file");
    for (size_t start = 0; start < text.size();) {
      const size_t end = std::min(text.find('\n', start), text.size());
      lines.emplace_back(text, start, end - start - (end > start && text[end - 1] == '\r' ? 1 : 0));
      start = end + 1;
    }
  });
  if (!lines.empty() && lines[0].rfind("\xEF\xBB\xBF", 0) == 0) lines[0].erase(0, 3);
  while (!lines.empty() && trim(lines.back()).empty()) lines.pop_back();
  return lines;
}

// ---- EPW ----

// EPW field numbers (1-based, as in the EnergyPlus data dictionary) and their names.
enum EpwField {
  kYear = 1, kMonth = 2, kDay = 3, kHour = 4, kMinute = 5, kDewPoint = 8, kGlobalHorizontal = 14,
  kDirectNormal = 15, kDiffuseHorizontal = 16, kGlobalIlluminance = 17, kDirectIlluminance = 18,
  kDiffuseIlluminance = 19,
};

std::string epw_field_name(int field) {
  switch (field) {
    case kYear: return "field 1 (year)";
    case kMonth: return "field 2 (month)";
    case kDay: return "field 3 (day)";
    case kHour: return "field 4 (hour)";
    case kMinute: return "field 5 (minute)";
    case kDewPoint: return "field 8 (dew point temperature)";
    case kGlobalHorizontal: return "field 14 (global horizontal radiation)";
    case kDirectNormal: return "field 15 (direct normal radiation)";
    case kDiffuseHorizontal: return "field 16 (diffuse horizontal radiation)";
    case kGlobalIlluminance: return "field 17 (global horizontal illuminance)";
    case kDirectIlluminance: return "field 18 (direct normal illuminance)";
    case kDiffuseIlluminance: return "field 19 (diffuse horizontal illuminance)";
    default: return "field " + std::to_string(field);
  }
}

WeatherLocation read_epw_location(const Source& at, const std::string& line) {
  const std::vector<std::string> fields = split(line, ',');
  if (lower(trim(fields[0])) != "location")
    refuse(at, "the first line must be the LOCATION record, found " + quoted(line.substr(0, 40)));
  if (fields.size() != 10)
    refuse(at, "LOCATION has " + std::to_string(fields.size()) +
                   " fields; 10 expected (LOCATION,city,region,country,source,WMO,latitude,longitude,time zone,elevation)");
  WeatherLocation location;
  for (int i = 1; i <= 3; ++i) {
    const std::string part = trim(fields[i]);
    if (part.empty()) continue;
    location.name += (location.name.empty() ? "" : ", ") + part;
  }
  location.latitude_deg = checked_range(at, "LOCATION latitude", fields[6], number_field(at, "LOCATION latitude", fields[6]),
                                        -90.0, 90.0, "latitude");
  location.longitude_deg = checked_range(at, "LOCATION longitude", fields[7],
                                         number_field(at, "LOCATION longitude", fields[7]), -180.0, 180.0, "longitude");
  location.time_zone_hours = checked_range(at, "LOCATION time zone", fields[8],
                                           number_field(at, "LOCATION time zone", fields[8]), kMinTimeZone,
                                           kMaxTimeZone, "time zone (hours from UTC)");
  location.elevation_m = checked_range(at, "LOCATION elevation", fields[9],
                                       number_field(at, "LOCATION elevation", fields[9]), kMinElevation,
                                       kMaxElevation, "elevation (m)");
  return location;
}

// Header lines 2 to 8 must be the records the format names, in order; only DATA PERIODS is read.
void check_epw_header(const std::string& path, const std::vector<std::string>& lines) {
  static const char* const kRecords[kEpwHeaderLines - 1] = {
      "DESIGN CONDITIONS", "TYPICAL/EXTREME PERIODS", "GROUND TEMPERATURES", "HOLIDAYS/DAYLIGHT SAVING",
      "COMMENTS 1",        "COMMENTS 2",              "DATA PERIODS"};
  for (int i = 1; i < kEpwHeaderLines; ++i)
    if (!starts_with_ci(lines[i], kRecords[i - 1]))
      refuse(Source{path, i + 1}, "header line " + std::to_string(i + 1) + " must be the " + kRecords[i - 1] +
                                      " record, found " + quoted(lines[i].substr(0, 40)));
  const Source at{path, kEpwHeaderLines};
  const std::vector<std::string> fields = split(lines[kEpwHeaderLines - 1], ',');
  if (fields.size() < 3) refuse(at, "DATA PERIODS needs the number of periods and of records per hour");
  const int periods = integer_field(at, "DATA PERIODS number of periods", fields[1]);
  if (periods != 1) refuse_field(at, "DATA PERIODS number of periods", fields[1], "only files with one data period are read");
  const int per_hour = integer_field(at, "DATA PERIODS records per hour", fields[2]);
  if (per_hour != 1) refuse_field(at, "DATA PERIODS records per hour", fields[2], "only hourly files (1 record per hour) are read");
}

// Whether `next` is the hour right after `previous` (29 February may or may not be present).
bool follows(const WeatherHour& previous, const WeatherHour& next) {
  const int hour = static_cast<int>(previous.hour_ending);
  if (hour < 24) return next.month == previous.month && next.day == previous.day && next.hour_ending == hour + 1;
  if (next.hour_ending != 1) return false;
  if (next.month == previous.month && next.day == previous.day + 1) return true;
  const bool month_end = previous.day == kDaysInMonth[previous.month - 1] || (previous.month == 2 && previous.day == 28);
  return month_end && next.month == previous.month + 1 && next.day == 1;
}

std::string epw_hour_text(const WeatherHour& hour) {
  return date_text(hour.month, hour.day) + " hour " + format_number(hour.hour_ending);
}

WeatherHour read_epw_row(const Source& at, const std::string& line) {
  const std::vector<std::string> fields = split(line, ',');
  if (static_cast<int>(fields.size()) != kEpwFields)
    refuse(at, "data row has " + std::to_string(fields.size()) + " fields; " + std::to_string(kEpwFields) + " expected");
  auto text = [&](int field) -> const std::string& { return fields[field - 1]; };
  WeatherHour hour;
  hour.line = at.line;
  integer_field(at, epw_field_name(kYear), text(kYear));
  read_date(at, epw_field_name(kMonth), text(kMonth), epw_field_name(kDay), text(kDay), &hour);
  const int hour_ending = integer_field(at, epw_field_name(kHour), text(kHour));
  if (hour_ending < 1 || hour_ending > 24) refuse_field(at, epw_field_name(kHour), text(kHour), "not an hour 1 to 24");
  const int minute = integer_field(at, epw_field_name(kMinute), text(kMinute));
  if (minute < 0 || minute > 60) refuse_field(at, epw_field_name(kMinute), text(kMinute), "not a minute 0 to 60");
  hour.hour_ending = hour_ending;
  hour.clock_hours = hour_ending - 0.5;
  hour.dew_point_c = dew_point_field(at, epw_field_name(kDewPoint), text(kDewPoint));
  auto irradiance = [&](int field, Requirement requirement) {
    return irradiance_field(at, epw_field_name(field), text(field), hour, requirement, kMissingIrradiance);
  };
  hour.global_horizontal_w_m2 = irradiance(kGlobalHorizontal, Requirement::Optional);
  hour.direct_normal_w_m2 = irradiance(kDirectNormal, Requirement::Required);
  hour.diffuse_horizontal_w_m2 = irradiance(kDiffuseHorizontal, Requirement::Required);
  auto illuminance = [&](int field) { return illuminance_field(at, epw_field_name(field), text(field), hour); };
  hour.global_horizontal_lux = illuminance(kGlobalIlluminance);
  hour.direct_normal_lux = illuminance(kDirectIlluminance);
  hour.diffuse_horizontal_lux = illuminance(kDiffuseIlluminance);
  return hour;
}

// ---- WEA ----

// "keyword value" header line; returns the value text (the rest of the line, trimmed).
std::string wea_header_value(const Source& at, const std::string& line, const std::string& keyword) {
  const std::string text = trim(line);
  const bool matches = starts_with_ci(text, keyword) &&
                       (text.size() == keyword.size() || text[keyword.size()] == ' ' || text[keyword.size()] == '\t');
  if (!matches)
    refuse(at, "header line " + std::to_string(at.line) + " must be " + quoted(keyword + " VALUE") + ", found " +
                   quoted(line.substr(0, 40)));
  const std::string value = trim(text.substr(keyword.size()));
  if (value.empty()) refuse(at, keyword + " has no value");
  return value;
}

// A numeric header line: its value, refused when not a number or outside [min, max].
double wea_header_number(const std::string& path, const std::vector<std::string>& lines, int index,
                         const std::string& keyword, double min, double max, const std::string& what) {
  const Source at{path, index + 1};
  const std::string raw = wea_header_value(at, lines[index], keyword);
  return checked_range(at, keyword, raw, number_field(at, keyword, raw), min, max, what);
}

constexpr int kWeaHeaderLines = 6;
const char* const kWeaKeywords[kWeaHeaderLines] = {"place",     "latitude",       "longitude",
                                                   "time_zone", "site_elevation", "weather_data_file_units"};

WeatherLocation read_wea_location(const std::string& path, const std::vector<std::string>& lines) {
  WeatherLocation location;
  location.name = wea_header_value(Source{path, 1}, lines[0], "place");  // as written ("City_Country")
  location.latitude_deg = wea_header_number(path, lines, 1, "latitude", -90.0, 90.0, "latitude");
  location.longitude_deg = -wea_header_number(path, lines, 2, "longitude", -180.0, 180.0, "longitude (degrees west)");
  // The standard meridian in degrees west: 15 degrees per hour behind UTC.
  location.time_zone_hours = -wea_header_number(path, lines, 3, "time_zone", -15.0 * kMaxTimeZone,
                                                -15.0 * kMinTimeZone,
                                                "standard meridian (degrees west; UTC-12 to UTC+14)") / 15.0;
  location.elevation_m = wea_header_number(path, lines, 4, "site_elevation", kMinElevation, kMaxElevation, "elevation (m)");
  const Source units_at{path, 6};
  const std::string units_text = wea_header_value(units_at, lines[5], "weather_data_file_units");
  const int units = integer_field(units_at, "weather_data_file_units", units_text);
  if (units != 1)
    refuse_field(units_at, "weather_data_file_units", units_text,
                 units == 2   ? "direct horizontal and diffuse horizontal irradiance are not read; convert the file "
                                "to units 1 (direct normal and diffuse horizontal irradiance, W/m2)"
                 : units == 3 ? "illuminances are not read; convert the file to units 1 (direct normal and diffuse "
                                "horizontal irradiance, W/m2)"
                              : "unknown units; 1 (direct normal and diffuse horizontal irradiance, W/m2) is read");
  return location;
}

const char* const kWeaColumns[7] = {"column 1 (month)", "column 2 (day)", "column 3 (hour)",
                                    "column 4 (direct normal irradiance)", "column 5 (diffuse horizontal irradiance)",
                                    "column 6 (aerosol optical depth)", "column 7 (sky cover)"};

WeatherHour read_wea_row(const Source& at, const std::string& line) {
  const std::vector<std::string> columns = split_whitespace(line);
  if (columns.size() != 5 && columns.size() != 7)
    refuse(at, "data row has " + std::to_string(columns.size()) +
                   " columns; 5 expected (month day hour direct-normal diffuse-horizontal), or 7 with aerosol "
                   "optical depth and sky cover");
  WeatherHour hour;
  hour.line = at.line;
  read_date(at, kWeaColumns[0], columns[0], kWeaColumns[1], columns[1], &hour);
  hour.clock_hours = number_field(at, kWeaColumns[2], columns[2]);
  if (hour.clock_hours < 0.0 || hour.clock_hours > 24.0)
    refuse_field(at, kWeaColumns[2], columns[2], "not a decimal hour 0 to 24");
  hour.hour_ending = kNaN;
  hour.direct_normal_w_m2 = irradiance_field(at, kWeaColumns[3], columns[3], hour, Requirement::Required, 0.0);
  hour.diffuse_horizontal_w_m2 = irradiance_field(at, kWeaColumns[4], columns[4], hour, Requirement::Required, 0.0);
  for (size_t i = 5; i < columns.size(); ++i) number_field(at, kWeaColumns[i], columns[i]);
  hour.global_horizontal_w_m2 = hour.direct_normal_lux = hour.diffuse_horizontal_lux = hour.global_horizontal_lux =
      hour.dew_point_c = kNaN;
  return hour;
}

bool earlier(const WeatherHour& a, const WeatherHour& b) {
  if (a.month != b.month) return a.month < b.month;
  if (a.day != b.day) return a.day < b.day;
  return a.clock_hours < b.clock_hours;
}

}  // namespace

int day_of_year(int month, int day) {
  if (!valid_date(month, day)) throw std::invalid_argument("day_of_year: " + date_text(month, day) + " is not a date");
  return month == 2 && day == 29 ? 60 : kDaysBeforeMonth[month - 1] + day;
}

double extraterrestrial_normal_irradiance(int month, int day) {
  if (!valid_date(month, day))
    throw std::invalid_argument("extraterrestrial_normal_irradiance: " + date_text(month, day) + " is not a date");
  return extraterrestrial_normal_irradiance(day_of_year(month, day));
}

WeatherData read_epw(const std::string& path) {
  const std::vector<std::string> lines = read_lines(path);
  if (lines.empty()) refuse(Source{path, 1}, "the file is empty; an EPW starts with 8 header lines (LOCATION first)");
  WeatherData data;
  data.path = path;
  data.location = read_epw_location(Source{path, 1}, lines[0]);
  if (static_cast<int>(lines.size()) < kEpwHeaderLines)
    refuse(Source{path, static_cast<int>(lines.size())},
           "the file ends inside the header; an EPW has 8 header lines, then its hourly rows");
  check_epw_header(path, lines);
  if (static_cast<int>(lines.size()) == kEpwHeaderLines)
    refuse(Source{path, kEpwHeaderLines}, "no data rows after the header; an EPW holds 8760 or 8784 hourly rows");

  WarningTally diffuse_excess{"hours with diffuse horizontal above global horizontal radiation by more than 1 W/m2 + 1 %"};
  data.hours.reserve(lines.size() - kEpwHeaderLines);
  for (size_t i = kEpwHeaderLines; i < lines.size(); ++i) {
    const Source at{path, static_cast<int>(i) + 1};
    const WeatherHour hour = read_epw_row(at, lines[i]);
    if (data.hours.empty() ? !(hour.month == 1 && hour.day == 1 && hour.hour_ending == 1)
                           : !follows(data.hours.back(), hour))
      refuse(at, "date and hour " + epw_hour_text(hour) +
                     (data.hours.empty() ? " where the year must start (1/1 hour 1)"
                                         : " do not follow " + epw_hour_text(data.hours.back()) +
                                               "; rows must be consecutive hours of one year"));
    check_diffuse_within_global(at, hour, &diffuse_excess);
    data.hours.push_back(hour);
  }
  const WeatherHour& last = data.hours.back();
  if (!(last.month == 12 && last.day == 31 && last.hour_ending == 24))
    refuse(Source{path, static_cast<int>(lines.size())},
           "the data end at " + epw_hour_text(last) + " after " + std::to_string(data.hours.size()) +
               " rows: truncated; an EPW holds a full year, 1/1 hour 1 to 12/31 hour 24 (8760 or 8784 rows)");
  diffuse_excess.report(&data.warnings);
  check_time_zone_against_longitude(data.location, "EPW: east positive", &data.warnings);
  return data;
}

WeatherData read_wea(const std::string& path) {
  const std::vector<std::string> lines = read_lines(path);
  if (lines.empty()) refuse(Source{path, 1}, "the file is empty; a .wea starts with 6 header lines (place first)");
  if (static_cast<int>(lines.size()) < kWeaHeaderLines) {
    // Name the first missing keyword after checking those present.
    for (size_t i = 0; i < lines.size(); ++i)
      wea_header_value(Source{path, static_cast<int>(i) + 1}, lines[i], kWeaKeywords[i]);
    refuse(Source{path, static_cast<int>(lines.size())},
           "the file ends inside the header; " + std::string(kWeaKeywords[lines.size()]) + " is missing");
  }
  WeatherData data;
  data.path = path;
  data.location = read_wea_location(path, lines);
  if (static_cast<int>(lines.size()) == kWeaHeaderLines)
    refuse(Source{path, kWeaHeaderLines}, "no data rows after the header");
  data.hours.reserve(lines.size() - kWeaHeaderLines);
  for (size_t i = kWeaHeaderLines; i < lines.size(); ++i) {
    const Source at{path, static_cast<int>(i) + 1};
    const WeatherHour hour = read_wea_row(at, lines[i]);
    if (!data.hours.empty() && !earlier(data.hours.back(), hour)) {
      const WeatherHour& previous = data.hours.back();
      refuse(at, "date and hour " + date_text(hour.month, hour.day) + " " + format_number(hour.clock_hours) +
                     " h do not come after " + date_text(previous.month, previous.day) + " " +
                     format_number(previous.clock_hours) + " h; rows must be in time order within one year");
    }
    data.hours.push_back(hour);
  }
  check_time_zone_against_longitude(data.location, ".wea: west positive", &data.warnings);
  return data;
}

WeatherData read_weather(const std::string& path) {
  const std::string extension = lower(std::filesystem::path(path).extension().string());
  if (extension == ".epw") return read_epw(path);
  if (extension == ".wea") return read_wea(path);
  throw std::invalid_argument(path + ": unknown weather file extension " + quoted(extension) +
                              "; .epw (EnergyPlus) or .wea (Radiance) expected");
}

int WeatherData::year_hours() const {
  for (const WeatherHour& hour : hours)
    if (hour.month == 2 && hour.day == 29) return 8784;
  return 8760;
}

std::string WeatherLocation::to_string() const {
  std::ostringstream out;
  out << quoted(name) << ", " << format_number(std::abs(latitude_deg)) << (latitude_deg < 0 ? " S " : " N ")
      << format_number(std::abs(longitude_deg)) << (longitude_deg < 0 ? " W" : " E") << ", UTC"
      << (time_zone_hours < 0 ? "" : "+") << format_number(time_zone_hours) << ", " << format_number(elevation_m)
      << " m";
  return out.str();
}

std::string WeatherData::to_string() const {
  std::ostringstream out;
  out << "WeatherData(" << quoted(path) << ": " << location.to_string() << "; " << hours.size() << " rows";
  if (!hours.empty())
    out << " from " << date_text(hours.front().month, hours.front().day) << " to "
        << date_text(hours.back().month, hours.back().day);
  out << ", " << warnings.size() << (warnings.size() == 1 ? " warning)" : " warnings)");
  return out.str();
}

}  // namespace fenestra
