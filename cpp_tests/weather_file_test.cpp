#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "daylight/weather_file.h"

using namespace fenestra;

namespace {

const std::string kChicago =
    std::string(FENESTRA_EXAMPLES) + "/weather/USA_IL_Chicago-OHare.Intl.AP.725300_TMY3.epw";
constexpr int kEpwHeaderLines = 8;

// ---- Plain text handling, independent of the reader ----

std::vector<std::string> text_lines(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  std::string line;
  while (std::getline(in, line)) lines.push_back(line);
  return lines;
}

std::vector<std::string> split_commas(const std::string& line) {
  std::vector<std::string> fields;
  std::string field;
  for (char c : line) {
    if (c == ',') {
      fields.push_back(field);
      field.clear();
    } else {
      field += c;
    }
  }
  fields.push_back(field);
  return fields;
}

std::string join(const std::vector<std::string>& parts, const std::string& separator) {
  std::string text;
  for (size_t i = 0; i < parts.size(); ++i) text += (i ? separator : "") + parts[i];
  return text;
}

std::string join_lines(const std::vector<std::string>& lines) { return join(lines, "\n") + "\n"; }

// Field `field` (1-based, as the EPW dictionary numbers them) of a data line, as a number.
double epw_value(const std::string& line, int field) { return std::stod(split_commas(line)[field - 1]); }

// Sets field `field` (1-based) of line `line_number` (1-based, as the file numbers lines).
void set_field(std::vector<std::string>& lines, int line_number, int field, const std::string& value) {
  std::vector<std::string> fields = split_commas(lines[line_number - 1]);
  fields[field - 1] = value;
  lines[line_number - 1] = join(fields, ",");
}

// The EPW line number (1-based) of a date and hour in a file of 365 days.
int epw_line(int month, int day, int hour) {
  static const int kDaysBefore[12] = {0, 31, 59, 90, 120, 151, 181, 212, 243, 273, 304, 334};
  return kEpwHeaderLines + 24 * (kDaysBefore[month - 1] + day - 1) + hour;
}

// A Radiance .wea written as Radiance's epw2wea writes one: "place City_Country", longitude and
// standard meridian in degrees west, and per row "month day decimal-hour DNI DHI", the hour being
// the middle of the EPW's hour.
std::string wea_from_epw(const std::vector<std::string>& epw, size_t rows) {
  const std::vector<std::string> location = split_commas(epw[0]);
  char buffer[128];
  std::string text = "place " + location[1] + "_" + location[3] + "\n";
  text += "latitude " + location[6] + "\n";
  std::snprintf(buffer, sizeof buffer, "longitude %f\ntime_zone %.0f\n", -std::stod(location[7]),
                -15.0 * std::stod(location[8]));
  text += buffer;
  text += "site_elevation " + location[9] + "\nweather_data_file_units 1\n";
  for (size_t i = kEpwHeaderLines; i < epw.size() && i < kEpwHeaderLines + rows; ++i) {
    const std::vector<std::string> f = split_commas(epw[i]);
    std::snprintf(buffer, sizeof buffer, "%s %s %.3f %.0f %.0f\n", f[1].c_str(), f[2].c_str(), std::stod(f[3]) - 0.5,
                  std::stod(f[14]), std::stod(f[15]));
    text += buffer;
  }
  return text;
}

const std::string kWeaHeader =
    "place Test_Place\nlatitude 41.98\nlongitude 87.92\ntime_zone 90\nsite_elevation 201.0\nweather_data_file_units 1\n";

// Every value a reader returns lies where the documentation says, whatever the file held.
void expect_in_range(const WeatherData& data, bool epw) {
  const WeatherLocation& l = data.location;
  EXPECT_TRUE(l.latitude_deg >= -90 && l.latitude_deg <= 90) << l.latitude_deg;
  EXPECT_TRUE(l.longitude_deg >= -180 && l.longitude_deg <= 180) << l.longitude_deg;
  EXPECT_TRUE(l.time_zone_hours >= -12 && l.time_zone_hours <= 14) << l.time_zone_hours;
  EXPECT_TRUE(l.elevation_m >= -1000 && l.elevation_m <= 9999.9) << l.elevation_m;
  ASSERT_FALSE(data.hours.empty());
  if (epw) {
    EXPECT_TRUE(data.hours.size() == 8760 || data.hours.size() == 8784) << data.hours.size();
  }
  static const int kDaysInMonth[12] = {31, 29, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  const double max_irradiance = 1367.0 * 1.0351;  // the eccentricity factor peaks at 1.03505
  const double max_illuminance = 134000.0 * 1.0351;
  auto optional_in = [](double value, double lo, double hi) { return std::isnan(value) || (value >= lo && value <= hi); };
  for (const WeatherHour& h : data.hours) {
    ASSERT_TRUE(h.month >= 1 && h.month <= 12 && h.day >= 1 && h.day <= kDaysInMonth[h.month - 1]);
    if (epw) {
      ASSERT_TRUE(h.hour_ending >= 1 && h.hour_ending <= 24 && h.hour_ending == std::floor(h.hour_ending));
      ASSERT_EQ(h.clock_hours, h.hour_ending - 0.5);
    } else {
      ASSERT_TRUE(std::isnan(h.hour_ending));
      ASSERT_TRUE(h.clock_hours >= 0 && h.clock_hours <= 24);
    }
    ASSERT_TRUE(h.direct_normal_w_m2 >= 0 && h.direct_normal_w_m2 <= max_irradiance) << h.direct_normal_w_m2;
    ASSERT_TRUE(h.diffuse_horizontal_w_m2 >= 0 && h.diffuse_horizontal_w_m2 <= max_irradiance);
    ASSERT_TRUE(optional_in(h.global_horizontal_w_m2, 0, max_irradiance));
    ASSERT_TRUE(optional_in(h.direct_normal_lux, 0, max_illuminance));
    ASSERT_TRUE(optional_in(h.diffuse_horizontal_lux, 0, max_illuminance));
    ASSERT_TRUE(optional_in(h.global_horizontal_lux, 0, max_illuminance));
    ASSERT_TRUE(optional_in(h.dew_point_c, -70, 70));
  }
}

}  // namespace

// Each test writes its files into a directory of its own, removed afterwards.
class WeatherFile : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = std::filesystem::temp_directory_path() /
           ("fenestra_weather_" + std::string(info->name()) + "_" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
    chicago_ = text_lines(kChicago);
    ASSERT_EQ(chicago_.size(), 8768u) << kChicago;
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  std::string write(const std::string& name, const std::string& text) const {
    const std::string path = (dir_ / name).string();
    std::ofstream(path, std::ios::binary) << text;
    return path;
  }
  // The Chicago EPW after `edit`, written as `name`.
  std::string chicago_with(const std::function<void(std::vector<std::string>&)>& edit,
                           const std::string& name = "edited.epw") const {
    std::vector<std::string> lines = chicago_;
    edit(lines);
    return write(name, join_lines(lines));
  }

  // Reading `path` must throw std::invalid_argument whose message starts with "path:line:" (or
  // "path:" when line is 0) and contains every one of `parts`.
  static void expect_refused(const std::string& path, int line, const std::vector<std::string>& parts) {
    try {
      const WeatherData data = read_weather(path);
      ADD_FAILURE() << path << " was accepted: " << data.to_string();
    } catch (const std::invalid_argument& e) {
      const std::string message = e.what();
      const std::string where = path + ":" + (line > 0 ? std::to_string(line) + ":" : "");
      EXPECT_EQ(message.rfind(where, 0), 0u) << "expected to start with " << where << ": " << message;
      for (const std::string& part : parts)
        EXPECT_NE(message.find(part), std::string::npos) << "\"" << part << "\" missing from: " << message;
    }
  }
  // The Chicago EPW with one field of one line replaced must be refused at that line, naming it.
  void expect_field_refused(int line, int field, const std::string& value, const std::vector<std::string>& parts) {
    SCOPED_TRACE("line " + std::to_string(line) + " field " + std::to_string(field) + " = \"" + value + "\"");
    std::vector<std::string> expected = parts;
    expected.push_back("field " + std::to_string(field) + " (");
    expect_refused(chicago_with([&](auto& lines) { set_field(lines, line, field, value); }), line, expected);
  }

  std::filesystem::path dir_;
  std::vector<std::string> chicago_;
};

// ---- The shipped file ----

TEST_F(WeatherFile, ChicagoReadsAsOneFullYearWithItsLocation) {
  const WeatherData data = read_epw(kChicago);
  EXPECT_EQ(data.path, kChicago);
  EXPECT_EQ(data.hours.size(), 8760u);
  EXPECT_EQ(data.year_hours(), 8760);
  EXPECT_TRUE(data.warnings.empty()) << join(data.warnings, "\n");
  EXPECT_EQ(data.location.name, "Chicago Ohare Intl Ap, IL, USA");
  EXPECT_DOUBLE_EQ(data.location.latitude_deg, 41.98);
  EXPECT_DOUBLE_EQ(data.location.longitude_deg, -87.92);  // west of Greenwich: negative
  EXPECT_DOUBLE_EQ(data.location.time_zone_hours, -6.0);
  EXPECT_DOUBLE_EQ(data.location.elevation_m, 201.0);
  EXPECT_EQ(data.hours.front().month, 1);
  EXPECT_EQ(data.hours.front().day, 1);
  EXPECT_EQ(data.hours.front().hour_ending, 1.0);
  EXPECT_EQ(data.hours.front().clock_hours, 0.5);  // the middle of 00:00-01:00
  EXPECT_EQ(data.hours.back().month, 12);
  EXPECT_EQ(data.hours.back().day, 31);
  EXPECT_EQ(data.hours.back().clock_hours, 23.5);
  expect_in_range(data, true);
  EXPECT_NE(data.to_string().find("8760 rows"), std::string::npos) << data.to_string();
  EXPECT_NE(data.to_string().find("87.92 W"), std::string::npos) << data.to_string();
}

// Line 16 of the file, the year's first hour with sun, reads "1986,1,1,8,0,...,-10.0,-13.3,...,
// 12,22,10,1272,873,1226,...": global 12, direct 22, diffuse 10 W/m^2; 1272, 873, 1226 lux.
TEST_F(WeatherFile, ChicagoFirstSunnyHourIsTheRawText) {
  const WeatherData data = read_epw(kChicago);
  size_t first_sun = 0;
  while (epw_value(chicago_[kEpwHeaderLines + first_sun], 15) == 0 &&
         epw_value(chicago_[kEpwHeaderLines + first_sun], 16) == 0)
    ++first_sun;
  ASSERT_EQ(kEpwHeaderLines + first_sun + 1, 16u);
  const WeatherHour& h = data.hours[first_sun];
  EXPECT_EQ(h.month, 1);
  EXPECT_EQ(h.day, 1);
  EXPECT_EQ(h.hour_ending, 8.0);
  EXPECT_EQ(h.clock_hours, 7.5);
  EXPECT_EQ(h.global_horizontal_w_m2, 12.0);
  EXPECT_EQ(h.direct_normal_w_m2, 22.0);
  EXPECT_EQ(h.diffuse_horizontal_w_m2, 10.0);
  EXPECT_EQ(h.global_horizontal_lux, 1272.0);
  EXPECT_EQ(h.direct_normal_lux, 873.0);
  EXPECT_EQ(h.diffuse_horizontal_lux, 1226.0);
  EXPECT_EQ(h.dew_point_c, -13.3);
}

// Every row against a plain split of its line: date, hour and the eight values read.
TEST_F(WeatherFile, ChicagoEveryRowMatchesAPlainSplit) {
  const WeatherData data = read_epw(kChicago);
  ASSERT_EQ(data.hours.size(), chicago_.size() - kEpwHeaderLines);
  for (size_t i = 0; i < data.hours.size(); ++i) {
    const std::string& line = chicago_[kEpwHeaderLines + i];
    const WeatherHour& h = data.hours[i];
    SCOPED_TRACE("line " + std::to_string(kEpwHeaderLines + i + 1));
    ASSERT_EQ(h.month, epw_value(line, 2));
    ASSERT_EQ(h.day, epw_value(line, 3));
    ASSERT_EQ(h.hour_ending, epw_value(line, 4));
    ASSERT_EQ(h.dew_point_c, epw_value(line, 8));  // this file has no missing values
    ASSERT_EQ(h.global_horizontal_w_m2, epw_value(line, 14));
    ASSERT_EQ(h.direct_normal_w_m2, epw_value(line, 15));
    ASSERT_EQ(h.diffuse_horizontal_w_m2, epw_value(line, 16));
    ASSERT_EQ(h.global_horizontal_lux, epw_value(line, 17));
    ASSERT_EQ(h.direct_normal_lux, epw_value(line, 18));
    ASSERT_EQ(h.diffuse_horizontal_lux, epw_value(line, 19));
  }
}

// Annual direct normal and diffuse horizontal irradiation, kWh/m^2: the reader's sum against a
// plain split, and against awk over the same columns (1294.257 and 660.253 kWh/m^2).
TEST_F(WeatherFile, ChicagoAnnualIrradiation) {
  const WeatherData data = read_epw(kChicago);
  double direct = 0, diffuse = 0, direct_raw = 0, diffuse_raw = 0;
  for (const WeatherHour& h : data.hours) {
    direct += h.direct_normal_w_m2 / 1000.0;  // one hour at W/m^2 is Wh/m^2
    diffuse += h.diffuse_horizontal_w_m2 / 1000.0;
  }
  for (size_t i = kEpwHeaderLines; i < chicago_.size(); ++i) {
    direct_raw += epw_value(chicago_[i], 15) / 1000.0;
    diffuse_raw += epw_value(chicago_[i], 16) / 1000.0;
  }
  EXPECT_NEAR(direct, direct_raw, 1e-9);
  EXPECT_NEAR(diffuse, diffuse_raw, 1e-9);
  EXPECT_NEAR(direct, 1294.257, 0.0005);
  EXPECT_NEAR(diffuse, 660.253, 0.0005);
}

// ---- The extraterrestrial bound ----

// The file's own column 12 (NREL's extraterrestrial direct normal radiation, from the same
// Spencer series) at the noon hour, when the sun is up all hour, rounded to 1 W/m^2: agreement
// within the rounding. NREL counts days in the row's own year, so in a leap year's month after
// February its day n is our day n + 1 (May of this file is from 1980).
TEST_F(WeatherFile, ExtraterrestrialIrradianceMatchesTheFilesOwnColumn) {
  static const int kDaysInMonth[12] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  double worst = 0;
  for (size_t i = kEpwHeaderLines; i < chicago_.size(); ++i) {
    const std::vector<std::string> f = split_commas(chicago_[i]);
    if (std::stoi(f[3]) != 12) continue;
    const int year = std::stoi(f[0]);
    int month = std::stoi(f[1]), day = std::stoi(f[2]);
    const bool leap = year % 4 == 0 && (year % 100 != 0 || year % 400 == 0);
    if (leap && month > 2 && ++day > kDaysInMonth[month - 1]) {
      day = 1;
      month = month % 12 + 1;
    }
    worst = std::max(worst, std::abs(extraterrestrial_normal_irradiance(month, day) - std::stod(f[11])));
  }
  EXPECT_LE(worst, 0.5 + 1e-9);
  // Against the orbit: 1367 W/m^2 / r^2 at perihelion (0.98329 AU) and aphelion (1.01671 AU). A
  // bound within 0.1 % is all the checks need (the clearest sky takes 20 % or more of the beam).
  double lo = 1e9, hi = 0;
  for (int month = 1; month <= 12; ++month)
    for (int day = 1; day <= 28; ++day) {
      lo = std::min(lo, extraterrestrial_normal_irradiance(month, day));
      hi = std::max(hi, extraterrestrial_normal_irradiance(month, day));
    }
  const double perihelion = 1367.0 / (0.98329 * 0.98329), aphelion = 1367.0 / (1.01671 * 1.01671);
  EXPECT_NEAR(hi, perihelion, 1e-3 * perihelion);
  EXPECT_NEAR(lo, aphelion, 1e-3 * aphelion);
  std::printf("[ orbit    ] extraterrestrial %.2f to %.2f W/m2 (Kepler: %.2f to %.2f); file column within %.4f\n", lo, hi,
              aphelion, perihelion, worst);
  EXPECT_THROW(extraterrestrial_normal_irradiance(2, 30), std::invalid_argument);
  EXPECT_THROW(extraterrestrial_normal_irradiance(13, 1), std::invalid_argument);
}

TEST_F(WeatherFile, DirectNormalBeyondTheExtraterrestrialIsRefused) {
  // 1 January allows 1414.9 W/m^2, early July only 1321.4: the bound follows the orbit.
  const std::string january = chicago_with([](auto& lines) { set_field(lines, epw_line(1, 1, 12), 15, "1410"); });
  EXPECT_EQ(read_epw(january).hours[11].direct_normal_w_m2, 1410.0);
  expect_field_refused(epw_line(7, 4, 12), 15, "1330", {"exceeds the extraterrestrial", "1321"});
  expect_field_refused(epw_line(1, 1, 12), 15, "1416", {"exceeds the extraterrestrial", "1414.9"});
  expect_field_refused(epw_line(7, 4, 12), 16, "1330", {"(diffuse horizontal radiation)", "exceeds the extraterrestrial"});
  expect_field_refused(epw_line(1, 1, 12), 14, "5000", {"exceeds the extraterrestrial"});
  expect_field_refused(epw_line(1, 1, 12), 17, "150000", {"exceeds the extraterrestrial normal illuminance"});
}

// ---- Leap years ----

TEST_F(WeatherFile, LeapYearHas8784Hours) {
  const std::string path = chicago_with(
      [](auto& lines) {
        std::vector<std::string> leap_day;
        for (int hour = 1; hour <= 24; ++hour) {
          std::vector<std::string> f = split_commas(lines[epw_line(2, 28, hour) - 1]);
          f[2] = "29";
          leap_day.push_back(join(f, ","));
        }
        lines.insert(lines.begin() + epw_line(2, 28, 24), leap_day.begin(), leap_day.end());
      },
      "leap.epw");
  const WeatherData data = read_epw(path);
  EXPECT_EQ(data.hours.size(), 8784u);
  EXPECT_EQ(data.year_hours(), 8784);
  EXPECT_EQ(data.hours[24 * 59].month, 2);
  EXPECT_EQ(data.hours[24 * 59].day, 29);
  EXPECT_EQ(data.hours[24 * 60].month, 3);
  EXPECT_EQ(read_epw(kChicago).year_hours(), 8760);
}

// ---- Radiance .wea ----

TEST_F(WeatherFile, WeaWrittenFromTheEpwReadsBackWithConventionsConverted) {
  const std::string path = write("chicago.wea", wea_from_epw(chicago_, 8760));
  const WeatherData wea = read_wea(path);
  const WeatherData epw = read_epw(kChicago);
  EXPECT_EQ(wea.location.name, "Chicago Ohare Intl Ap_USA");  // as Radiance writes it
  EXPECT_DOUBLE_EQ(wea.location.latitude_deg, 41.98);
  EXPECT_DOUBLE_EQ(wea.location.longitude_deg, -87.92);  // "longitude 87.920000" is west
  EXPECT_DOUBLE_EQ(wea.location.time_zone_hours, -6.0);  // "time_zone 90" is 90 degrees west
  EXPECT_DOUBLE_EQ(wea.location.elevation_m, 201.0);
  EXPECT_TRUE(wea.warnings.empty()) << join(wea.warnings, "\n");
  ASSERT_EQ(wea.hours.size(), epw.hours.size());
  EXPECT_EQ(wea.year_hours(), 8760);
  for (size_t i = 0; i < wea.hours.size(); ++i) {
    const WeatherHour &w = wea.hours[i], &e = epw.hours[i];
    SCOPED_TRACE("row " + std::to_string(i));
    ASSERT_EQ(w.month, e.month);
    ASSERT_EQ(w.day, e.day);
    ASSERT_EQ(w.clock_hours, e.clock_hours);
    ASSERT_EQ(w.direct_normal_w_m2, e.direct_normal_w_m2);
    ASSERT_EQ(w.diffuse_horizontal_w_m2, e.diffuse_horizontal_w_m2);
    ASSERT_TRUE(std::isnan(w.hour_ending));
    ASSERT_TRUE(std::isnan(w.global_horizontal_w_m2) && std::isnan(w.global_horizontal_lux) &&
                std::isnan(w.direct_normal_lux) && std::isnan(w.diffuse_horizontal_lux) && std::isnan(w.dew_point_c));
  }
  expect_in_range(wea, false);
}

TEST_F(WeatherFile, WeaEastOfGreenwichAndWithAtmosphericColumns) {
  // Sydney: 151.21 E is "longitude -151.21"; UTC+10 is the meridian 150 degrees east, "-150".
  // Seven columns, as Radiance's epw2wea -a writes (aerosol optical depth, sky cover), CRLF ends.
  const std::string path = write("sydney.WEA",
                                 "place Sydney_AUS\r\nlatitude -33.87\r\nlongitude -151.21\r\ntime_zone -150\r\n"
                                 "site_elevation 6\r\nweather_data_file_units 1\r\n"
                                 "6 21 11.5 512 120 0.085 0.3\r\n6 21 12.5 530 118 0.090 0.4\r\n\r\n");
  const WeatherData data = read_weather(path);
  EXPECT_DOUBLE_EQ(data.location.latitude_deg, -33.87);
  EXPECT_DOUBLE_EQ(data.location.longitude_deg, 151.21);
  EXPECT_DOUBLE_EQ(data.location.time_zone_hours, 10.0);
  EXPECT_EQ(data.location.name, "Sydney_AUS");
  ASSERT_EQ(data.hours.size(), 2u);
  EXPECT_EQ(data.hours[1].clock_hours, 12.5);
  EXPECT_EQ(data.hours[1].direct_normal_w_m2, 530.0);
  EXPECT_EQ(data.hours[1].diffuse_horizontal_w_m2, 118.0);
  EXPECT_TRUE(data.warnings.empty()) << join(data.warnings, "\n");
  EXPECT_EQ(data.year_hours(), 8760);
}

// A longitude whose sign is flipped puts the sun hours away from the zone's clock: a warning.
TEST_F(WeatherFile, LongitudeFarFromTheTimeZoneWarns) {
  const std::string wea = write("flipped.wea",
                                "place X\nlatitude 41.98\nlongitude -87.92\ntime_zone 90\nsite_elevation 201\n"
                                "weather_data_file_units 1\n1 1 12.5 100 50\n");
  const WeatherData data = read_wea(wea);
  ASSERT_EQ(data.warnings.size(), 1u);
  EXPECT_NE(data.warnings[0].find("sign of the longitude"), std::string::npos) << data.warnings[0];
  const std::string epw = chicago_with([](auto& lines) { set_field(lines, 1, 8, "87.92"); });
  const WeatherData east = read_epw(epw);
  ASSERT_EQ(east.warnings.size(), 1u);
  EXPECT_NE(east.warnings[0].find("sign of the longitude"), std::string::npos) << east.warnings[0];
}

TEST_F(WeatherFile, WeaRefusals) {
  const std::string row = "1 1 12.5 100 50\n";
  auto wea = [&](const std::string& text) { return write("bad.wea", text); };
  auto header_with = [&](const std::string& from, const std::string& to) {
    std::string header = kWeaHeader;
    header.replace(header.find(from), from.size(), to);
    return header;
  };
  expect_refused(wea(""), 1, {"empty"});
  expect_refused(wea(kWeaHeader), 6, {"no data rows"});
  expect_refused(wea("place X\nlatitude 41.98\n"), 2, {"longitude is missing"});
  expect_refused(wea(header_with("latitude 41.98", "lattitude 41.98") + row), 2, {"\"latitude VALUE\""});
  expect_refused(wea(header_with("latitude 41.98", "latitude 91") + row), 2, {"latitude \"91\"", "outside [-90, 90]"});
  expect_refused(wea(header_with("latitude 41.98", "latitude north") + row), 2, {"latitude \"north\"", "not a number"});
  expect_refused(wea(header_with("longitude 87.92", "longitude 200") + row), 3, {"longitude \"200\"", "[-180, 180]"});
  expect_refused(wea(header_with("time_zone 90", "time_zone 195") + row), 4, {"time_zone \"195\"", "UTC-12 to UTC+14"});
  expect_refused(wea(header_with("time_zone 90", "time_zone -225") + row), 4, {"time_zone \"-225\""});
  expect_refused(wea(header_with("site_elevation 201.0", "site_elevation 12000") + row), 5, {"site_elevation \"12000\""});
  expect_refused(wea(header_with("units 1", "units 2") + row), 6, {"weather_data_file_units \"2\"", "direct horizontal"});
  expect_refused(wea(header_with("units 1", "units 3") + row), 6, {"weather_data_file_units \"3\"", "illuminances"});
  expect_refused(wea(kWeaHeader + "1 1 12.5 100\n"), 7, {"4 columns"});
  expect_refused(wea(kWeaHeader + row + "1 1 13.5 100 50 7\n"), 8, {"6 columns"});
  expect_refused(wea(kWeaHeader + "1 1 noon 100 50\n"), 7, {"column 3 (hour) \"noon\"", "not a number"});
  expect_refused(wea(kWeaHeader + "1 1 24.5 100 50\n"), 7, {"column 3 (hour) \"24.5\""});
  expect_refused(wea(kWeaHeader + "13 1 12.5 100 50\n"), 7, {"column 1 (month) \"13\""});
  expect_refused(wea(kWeaHeader + "2 30 12.5 100 50\n"), 7, {"column 2 (day) \"30\"", "month 2 has no such day"});
  expect_refused(wea(kWeaHeader + "1 1 12.5 -5 50\n"), 7, {"column 4 (direct normal irradiance) \"-5\"", "negative"});
  expect_refused(wea(kWeaHeader + "1 1 12.5 100 nan\n"), 7, {"column 5 (diffuse horizontal irradiance) \"nan\""});
  expect_refused(wea(kWeaHeader + "1 1 12.5 9999 50\n"), 7, {"column 4", "exceeds the extraterrestrial"});
  expect_refused(wea(kWeaHeader + "1 1 12.5 100 50 abc 0.3\n"), 7, {"column 6 (aerosol optical depth) \"abc\""});
  expect_refused(wea(kWeaHeader + row + row), 8, {"do not come after", "time order"});
  expect_refused(wea(kWeaHeader + "1 2 12.5 100 50\n" + row), 8, {"do not come after"});
  expect_refused(wea(kWeaHeader + row + "\n" + row), 8, {"0 columns"});
}

// ---- Files, names, extensions ----

TEST_F(WeatherFile, ReadWeatherDispatchesOnTheExtension) {
  const std::string upper = (dir_ / "chicago.EPW").string();
  std::filesystem::copy_file(kChicago, upper);
  EXPECT_EQ(read_weather(upper).hours.size(), 8760u);
  const std::string wea = write("x.Wea", kWeaHeader + "1 1 12.5 100 50\n");
  EXPECT_EQ(read_weather(wea).hours.size(), 1u);
  expect_refused(write("x.csv", kWeaHeader), 0, {"unknown weather file extension \".csv\"", ".epw", ".wea"});
  expect_refused(write("noextension", kWeaHeader), 0, {"unknown weather file extension"});
  // An EPW named .wea is read as a .wea and refused at its first line.
  const std::string misnamed = (dir_ / "chicago.wea").string();
  std::filesystem::copy_file(kChicago, misnamed);
  expect_refused(misnamed, 1, {"\"place VALUE\""});
}

TEST_F(WeatherFile, UnreadableFilesAreRefused) {
  expect_refused((dir_ / "absent.epw").string(), 0, {"cannot be read", "no such file"});
  std::filesystem::create_directories(dir_ / "folder.epw");
  expect_refused((dir_ / "folder.epw").string(), 0, {"directory"});
}

// ---- EPW refusals ----

TEST_F(WeatherFile, EpwStructureRefusals) {
  expect_refused(write("empty.epw", ""), 1, {"empty"});
  expect_refused(write("blank.epw", "\n\n"), 1, {"empty"});
  const std::vector<std::string> header(chicago_.begin(), chicago_.begin() + kEpwHeaderLines);
  expect_refused(write("header.epw", join_lines(header)), 8, {"no data rows"});
  expect_refused(write("short.epw", join_lines({chicago_[0], chicago_[1], chicago_[2]})), 3, {"ends inside the header"});
  expect_refused(chicago_with([](auto& l) { l.erase(l.begin() + 2); }), 3, {"TYPICAL/EXTREME PERIODS"});
  expect_refused(chicago_with([](auto& l) { l.erase(l.begin()); }), 1, {"LOCATION"});
  expect_refused(chicago_with([](auto& l) { l[0] += ",extra"; }), 1, {"LOCATION has 11 fields"});
  expect_refused(chicago_with([](auto& l) { l[7] = "DATA PERIODS,1,4,Data,Sunday, 1/ 1,12/31"; }), 8,
                 {"records per hour \"4\"", "only hourly"});
  expect_refused(chicago_with([](auto& l) { l[7] = "DATA PERIODS,2,1,Data,Sunday, 1/ 1,6/30,B,Sunday,7/1,12/31"; }), 8,
                 {"number of periods \"2\""});
  // Truncated: rows missing at the end, or the last row cut short.
  expect_refused(chicago_with([](auto& l) { l.resize(l.size() - 100); }), 8668,
                 {"truncated", "12/27 hour 20", "8660 rows", "8760 or 8784"});
  expect_refused(chicago_with([](auto& l) { l.back().resize(l.back().size() / 2); }), 8768,
                 {"data row has", "35 expected"});
  expect_refused(chicago_with([](auto& l) { l[99] += ",1"; }), 100, {"36 fields; 35 expected"});
  expect_refused(chicago_with([](auto& l) { l.insert(l.begin() + 500, ""); }), 501, {"1 fields; 35 expected"});
}

TEST_F(WeatherFile, EpwNumberRefusals) {
  const int line = epw_line(3, 15, 12);  // a sunny noon
  expect_field_refused(line, 15, "abc", {"(direct normal radiation) \"abc\"", "not a number"});
  expect_field_refused(line, 15, "", {"(direct normal radiation)", "empty"});
  expect_field_refused(line, 15, "9999", {"(direct normal radiation) \"9999\"", "missing-value code", "required"});
  expect_field_refused(line, 16, "9999", {"(diffuse horizontal radiation) \"9999\"", "missing-value code"});
  expect_field_refused(line, 16, "12000", {"(diffuse horizontal radiation)", "missing-value code"});
  expect_field_refused(line, 15, "-5", {"(direct normal radiation) \"-5\"", "negative irradiance"});
  expect_field_refused(line, 14, "-1", {"(global horizontal radiation) \"-1\"", "negative"});
  expect_field_refused(line, 18, "-1", {"(direct normal illuminance) \"-1\"", "negative illuminance"});
  expect_field_refused(line, 16, "nan", {"\"nan\"", "not a number"});
  expect_field_refused(line, 16, "inf", {"\"inf\"", "not a number"});
  expect_field_refused(line, 16, "1e400", {"\"1e400\"", "not a number"});
  expect_field_refused(line, 15, "0x20", {"\"0x20\"", "not a number"});
  expect_field_refused(line, 15, "12 W", {"\"12 W\"", "not a number"});
  expect_field_refused(line, 8, "abc", {"(dew point temperature) \"abc\""});
  expect_field_refused(line, 8, "75", {"(dew point temperature) \"75\"", "outside (-70, 70)"});
  expect_field_refused(line, 8, "-80", {"(dew point temperature) \"-80\""});
  expect_field_refused(line, 1, "year", {"(year) \"year\"", "whole number"});
}

TEST_F(WeatherFile, EpwDateRefusals) {
  const int line = epw_line(4, 30, 5);
  expect_field_refused(line, 2, "13", {"(month) \"13\"", "1 to 12"});
  expect_field_refused(line, 2, "4.5", {"(month) \"4.5\"", "whole number"});
  expect_field_refused(line, 3, "31", {"(day) \"31\"", "month 4 has no such day (1 to 30)"});
  expect_field_refused(line, 3, "0", {"(day) \"0\""});
  expect_field_refused(line, 4, "0", {"(hour) \"0\"", "1 to 24"});
  expect_field_refused(line, 4, "25", {"(hour) \"25\"", "1 to 24"});
  expect_field_refused(line, 5, "61", {"(minute) \"61\""});
  // Out of sequence: an hour skipped, a line duplicated, two lines swapped, the year not starting at 1/1.
  expect_refused(chicago_with([&](auto& l) { set_field(l, line, 4, "6"); }), line,
                 {"date and hour 4/30 hour 6 do not follow 4/30 hour 4", "consecutive"});
  expect_refused(chicago_with([&](auto& l) { l.insert(l.begin() + line, l[line - 1]); }), line + 1, {"do not follow"});
  expect_refused(chicago_with([&](auto& l) { std::swap(l[line - 1], l[line]); }), line, {"do not follow"});
  // A whole day missing: 4/29 hour 24 followed by 5/1 hour 1 (the first day of the next month).
  expect_refused(chicago_with([](auto& l) {
                   l.erase(l.begin() + epw_line(4, 30, 1) - 1, l.begin() + epw_line(4, 30, 24));
                 }),
                 epw_line(4, 30, 1), {"5/1 hour 1 do not follow 4/29 hour 24"});
  expect_refused(chicago_with([](auto& l) { l.erase(l.begin() + kEpwHeaderLines); }), kEpwHeaderLines + 1,
                 {"1/1 hour 2 where the year must start (1/1 hour 1)"});
  expect_refused(chicago_with([](auto& l) { l.push_back(l.back()); }), 8769, {"do not follow 12/31 hour 24"});
}

TEST_F(WeatherFile, EpwLocationRefusals) {
  auto location = [&](int field, const std::string& value) {
    return chicago_with([&](auto& l) { set_field(l, 1, field, value); });
  };
  expect_refused(location(7, "91"), 1, {"LOCATION latitude \"91\"", "[-90, 90]"});
  expect_refused(location(7, "N"), 1, {"LOCATION latitude \"N\"", "not a number"});
  expect_refused(location(8, "-181"), 1, {"LOCATION longitude \"-181\"", "[-180, 180]"});
  expect_refused(location(9, "-13"), 1, {"LOCATION time zone \"-13\"", "[-12, 14]"});
  expect_refused(location(9, "15"), 1, {"LOCATION time zone \"15\""});
  expect_refused(location(10, "10000"), 1, {"LOCATION elevation \"10000\""});
  // Kiribati's Line Islands: UTC+14, the farthest zone in use, at 157 W: accepted, no warning.
  const WeatherData kiribati = read_epw(chicago_with([](auto& l) {
    set_field(l, 1, 8, "-157.4");
    set_field(l, 1, 9, "14");
  }));
  EXPECT_DOUBLE_EQ(kiribati.location.time_zone_hours, 14.0);
  EXPECT_TRUE(kiribati.warnings.empty()) << join(kiribati.warnings, "\n");
}

// ---- Missing optional values and warnings ----

TEST_F(WeatherFile, EpwMissingOptionalValuesAreNaN) {
  const int line = epw_line(3, 15, 12);
  const size_t row = line - kEpwHeaderLines - 1;
  const WeatherData data = read_epw(chicago_with([&](auto& l) {
    set_field(l, line, 14, "9999");
    set_field(l, line, 17, "999999");
    set_field(l, line, 18, "999900");
    set_field(l, line, 19, "");
    set_field(l, line, 8, "99.9");
  }));
  const WeatherHour& h = data.hours[row];
  EXPECT_TRUE(std::isnan(h.global_horizontal_w_m2));
  EXPECT_TRUE(std::isnan(h.global_horizontal_lux));
  EXPECT_TRUE(std::isnan(h.direct_normal_lux));
  EXPECT_TRUE(std::isnan(h.diffuse_horizontal_lux));
  EXPECT_TRUE(std::isnan(h.dew_point_c));
  EXPECT_EQ(h.direct_normal_w_m2, epw_value(chicago_[line - 1], 15));  // the required values stay
  EXPECT_TRUE(data.warnings.empty());
  // 999899 lux is a value, not the missing code, and beyond any daylight.
  expect_field_refused(line, 17, "999899", {"exceeds the extraterrestrial normal illuminance"});
}

// Diffuse above global horizontal by more than 1 W/m^2 + 1 % of global is a warning, counted.
TEST_F(WeatherFile, DiffuseAboveGlobalIsAWarning) {
  const int a = epw_line(3, 15, 12), b = epw_line(3, 16, 12), c = epw_line(3, 17, 12);
  const WeatherData data = read_epw(chicago_with([&](auto& l) {
    set_field(l, a, 14, "100");
    set_field(l, a, 16, "102");  // at the tolerance: 100 + 1 + 1
    set_field(l, b, 14, "100");
    set_field(l, b, 16, "103");  // beyond it
    set_field(l, c, 14, "200");
    set_field(l, c, 16, "250");
  }));
  ASSERT_EQ(data.warnings.size(), 1u) << join(data.warnings, "\n");
  const std::string& warning = data.warnings[0];
  EXPECT_EQ(warning.rfind("2 hours with diffuse horizontal above global", 0), 0u) << warning;
  EXPECT_NE(warning.find("first: line " + std::to_string(b)), std::string::npos) << warning;
  EXPECT_NE(warning.find("diffuse 103 > global 100"), std::string::npos) << warning;
  EXPECT_EQ(data.hours[b - kEpwHeaderLines - 1].diffuse_horizontal_w_m2, 103.0);  // kept as written
  EXPECT_NE(data.to_string().find("1 warning)"), std::string::npos) << data.to_string();
}

// ---- Fuzz: every mutant is read in range or refused with std::invalid_argument ----

namespace {

const char* const kGarbage[] = {"abc", "9999", "-5",   "1e30", "-1e30", "",   "nan",  "inf", "0x1A",  "1e-400", "99.9",
                                "999999", "1415", "1,5", " 7 ", "+3",   "2.5", "-0", "13",   "32",  "0",     "25",
                                "1e308", "\t", "1 2", "\xEF\xBB\xBF"};

// One random edit of a file's lines: delete or insert a character, duplicate, delete or swap
// lines, replace a field by garbage, or truncate the text. `data_start`: the first data line.
std::string mutate(std::vector<std::string> lines, size_t data_start, char separator, std::mt19937& rng) {
  auto pick = [&](size_t n) { return static_cast<size_t>(rng() % n); };
  const size_t line = pick(4) == 0 ? pick(data_start) : data_start + pick(lines.size() - data_start);
  std::string& text = lines[line];
  switch (pick(7)) {
    case 0:
      if (!text.empty()) text.erase(pick(text.size()), 1);
      break;
    case 1: text.insert(pick(text.size() + 1), 1, "0123456789-.,eE +x\t"[pick(19)]); break;
    case 2: lines.insert(lines.begin() + line, text); break;
    case 3: lines.erase(lines.begin() + line); break;
    case 4:
      if (line + 1 < lines.size()) std::swap(lines[line], lines[line + 1]);
      break;
    case 5: {
      std::vector<std::string> fields;
      std::string field;
      for (char ch : text + separator) {
        if (ch == separator) {
          fields.push_back(field);
          field.clear();
        } else {
          field += ch;
        }
      }
      fields[pick(fields.size())] = kGarbage[pick(sizeof kGarbage / sizeof kGarbage[0])];
      text = join(fields, std::string(1, separator));
      break;
    }
    default: {
      std::string all = join_lines(lines);
      all.resize(pick(all.size()));
      return all;
    }
  }
  return join_lines(lines);
}

}  // namespace

TEST_F(WeatherFile, MutantsAreReadInRangeOrRefused) {
  std::vector<std::string> wea_lines = text_lines(write("base.wea", wea_from_epw(chicago_, 96)));
  int accepted = 0, refused = 0;
  for (unsigned seed = 0; seed < 200; ++seed) {
    std::mt19937 rng(seed);
    const bool epw = seed % 2 == 0;
    const std::string path = epw ? write("mutant.epw", mutate(chicago_, kEpwHeaderLines, ',', rng))
                                 : write("mutant.wea", mutate(wea_lines, 6, ' ', rng));
    SCOPED_TRACE("seed " + std::to_string(seed));
    try {
      const WeatherData data = read_weather(path);
      expect_in_range(data, epw);
      ++accepted;
    } catch (const std::invalid_argument& e) {
      EXPECT_EQ(std::string(e.what()).rfind(path + ":", 0), 0u) << e.what();
      ++refused;
    } catch (const std::exception& e) {
      ADD_FAILURE() << "not std::invalid_argument: " << e.what();
    } catch (...) {
      ADD_FAILURE() << "unknown exception";
    }
  }
  // Both outcomes occur, so the check on each is exercised.
  EXPECT_GT(accepted, 20);
  EXPECT_GT(refused, 20);
  std::printf("[ fuzz     ] 200 mutants: %d read, %d refused\n", accepted, refused);
}
