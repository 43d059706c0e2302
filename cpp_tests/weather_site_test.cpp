// Where and when weather rows are (daylight/weather_site.h): the instants of EPW and .wea rows,
// the row that holds an instant, 29 February, distances.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "daylight/local_time.h"
#include "daylight/weather_site.h"

using namespace fenestra;

namespace {

const WeatherData& chicago() {
  static const WeatherData w =
      read_weather(std::string(FENESTRA_EXAMPLES) + "/weather/USA_IL_Chicago-OHare.Intl.AP.725300_TMY3.epw");
  return w;
}

double utc(int year, int month, int day, double hours) {
  return TimeZone::fixed(0.0).utc_seconds(LocalDate{year, month, day}, hours * 60.0);
}

WeatherHour wea_row(int month, int day, double clock) {
  WeatherHour h;
  h.month = month, h.day = day;
  h.hour_ending = std::numeric_limits<double>::quiet_NaN();
  h.clock_hours = clock;
  return h;
}

TEST(WeatherClock, EpwRowsStandForTheMiddleOfTheHourTheyEnd) {
  const WeatherData& w = chicago();
  const WeatherClock clock(w);
  EXPECT_EQ(clock.year(), 2022);
  EXPECT_DOUBLE_EQ(clock.time_zone_hours(), -6.0);
  // 1 January hour 1 covers 00:00-01:00 of UTC-6: its middle is 06:30 UTC.
  EXPECT_DOUBLE_EQ(clock.utc_seconds(0), utc(2022, 1, 1, 6.5));
  EXPECT_DOUBLE_EQ(clock.utc_seconds(8759), utc(2023, 1, 1, 5.5));  // 31 December hour 24
  for (size_t row = 0; row < clock.rows(); ++row) {
    ASSERT_EQ(clock.row_at(clock.utc_seconds(row)), int(row));
    const HourStamp s = clock.stamp(row);
    ASSERT_EQ(s.month, w.hours[row].month);
    ASSERT_EQ(s.day, w.hours[row].day);
    ASSERT_DOUBLE_EQ(s.clock_hour, w.hours[row].hour_ending - 0.5);
  }
  // The hour's ends: 12:00:00 standard time belongs to hour 13, 11:59:59 to hour 12; the year of
  // the instant does not matter.
  const size_t noon_row = (31 + 28 + 31 + 30 + 31 + 20) * 24 + 12;  // 21 June, hour 13
  EXPECT_EQ(clock.row_at(utc(2026, 6, 21, 18.0)), int(noon_row));
  EXPECT_EQ(clock.row_at(utc(2031, 6, 21, 18.0) - 1.0), int(noon_row) - 1);
  EXPECT_EQ(clock.hour_text(utc(2026, 6, 21, 18.25)), "6/21 12:00-13:00 UTC-6 (local standard time)");
  // A leap day the file does not have.
  EXPECT_EQ(clock.row_at(utc(2024, 2, 29, 18.0)), -1);
  EXPECT_EQ(clock.hour_text(utc(2024, 2, 29, 18.0)), "2/29 12:00-13:00 UTC-6 (local standard time)");
  // Another standard time for the same rows moves every instant.
  const WeatherClock east(w, -5.0);
  EXPECT_DOUBLE_EQ(east.utc_seconds(0), utc(2022, 1, 1, 5.5));
}

TEST(WeatherClock, WeaRowsHoldTheHourTheirInstantLiesIn) {
  WeatherData w;
  w.location.time_zone_hours = 2.0;
  w.hours = {wea_row(2, 28, 23.5), wea_row(2, 29, 0.0), wea_row(2, 29, 12.5), wea_row(2, 29, 13.0),
             wea_row(2, 29, 24.0)};
  const WeatherClock clock(w);
  EXPECT_EQ(clock.year(), 2020);  // 29 February: a leap reference year
  EXPECT_DOUBLE_EQ(clock.utc_seconds(2), utc(2020, 2, 29, 10.5));
  EXPECT_EQ(clock.row_at(utc(2020, 2, 28, 21.75)), 0);  // 23:45 local: 23:00-24:00 of 2/28
  EXPECT_EQ(clock.row_at(utc(2020, 2, 28, 22.25)), 1);  // 00:15 local: 0.0 is put in 00:00-01:00
  EXPECT_EQ(clock.row_at(utc(2020, 2, 29, 10.9)), 2);   // 12:54: the first of the two rows of 12:00-13:00
  EXPECT_EQ(clock.row_at(utc(2020, 2, 29, 11.1)), -1);  // 13:06: no row
  EXPECT_EQ(clock.row_at(utc(2020, 2, 29, 21.5)), 4);   // 23:30: 24.0 ends 23:00-24:00
  // The instant written 24.0 is the next day's midnight for the annual metrics.
  const HourStamp last = clock.stamp(4);
  EXPECT_EQ(last.month, 3);
  EXPECT_EQ(last.day, 1);
  EXPECT_DOUBLE_EQ(last.clock_hour, 0.0);
}

TEST(WeatherSite, DistancesAndTheFarPlaceWarning) {
  EXPECT_NEAR(distance_km(0.0, 0.0, 0.0, 1.0), 2.0 * 3.14159265358979 * 6371.0 / 360.0, 1e-6);
  EXPECT_NEAR(distance_km(90.0, 0.0, -90.0, 45.0), 3.14159265358979 * 6371.0, 1e-6);
  EXPECT_NEAR(distance_km(10.0, 179.5, 10.0, -179.5), distance_km(10.0, 0.0, 10.0, 1.0), 1e-9);  // across 180
  const WeatherData& w = chicago();
  EXPECT_EQ(far_place_warning({41.98, -87.92, 0.0}, w, 100.0), "");
  const std::string far = far_place_warning({37.98, 23.73, 0.0}, w, 100.0);
  EXPECT_NE(far.find("latitude 37.98, longitude 23.73"), std::string::npos) << far;
  EXPECT_NE(far.find("Chicago Ohare Intl Ap"), std::string::npos) << far;
  EXPECT_NE(far.find(w.path), std::string::npos) << far;
}

}  // namespace
