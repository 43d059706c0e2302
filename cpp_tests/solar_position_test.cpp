#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "daylight/local_time.h"
#include "daylight/solar_position.h"

using namespace fenestra;

namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;
// Required agreement with NREL's Solar Position Algorithm, degrees.
constexpr double kSpaTolerance = 0.05;

double utc(const std::string& date, const std::string& clock, double utc_offset_hours) {
  return TimeZone::fixed(utc_offset_hours).utc_seconds(parse_date(date), parse_clock_minutes(clock));
}

// Azimuth difference wrapped to [-180, 180] and scaled by sin(zenith): the arc on the sky it spans,
// which stays meaningful near the zenith where azimuth itself is ill-defined.
double azimuth_arc(double azimuth, double reference_azimuth, double zenith) {
  const double d = std::remainder(azimuth - reference_azimuth, 360.0);
  return d * std::sin(zenith * kDeg);
}

// Expects a local_time parser to throw std::invalid_argument whose message quotes the text.
template <class Parse>
void expect_rejected(Parse parse, const std::string& text) {
  try {
    parse(text);
    ADD_FAILURE() << "accepted \"" << text << "\"";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("\"" + text + "\""), std::string::npos) << e.what();
  }
}

}  // namespace

// ---- Solar position ----

// Reda & Andreas, "Solar Position Algorithm for Solar Radiation Applications" (NREL/TP-560-34302,
// 2008), table A4: the paper's worked example.
TEST(SolarPosition, MatchesTheSpaPaperExample) {
  const double t = utc("2003-10-17", "12:30:30", -7.0);
  const Place golden{39.742476, -105.1786, 1830.14};
  const SunPosition p = solar_position(t, golden, Atmosphere{820.0, 11.0});
  EXPECT_NEAR(p.zenith_deg, 50.11162, kSpaTolerance);
  EXPECT_NEAR(p.azimuth_deg, 194.34024, kSpaTolerance);

  // The standard atmosphere (1010 hPa, 10 C) refracts 1.2 times more than 820 hPa, 11 C: at 40 deg
  // elevation that is 0.2' more lift, well inside the tolerance.
  const SunPosition standard = solar_position(t, golden, true);
  EXPECT_NEAR(standard.zenith_deg, 50.11162, kSpaTolerance);
  EXPECT_LT(standard.zenith_deg, p.zenith_deg);
  EXPECT_NEAR(standard.azimuth_deg, p.azimuth_deg, 1e-9);
}

// Reference positions without refraction from astropy 5.2.1 (ERFA: get_sun(t).transform_to(AltAz(...,
// pressure=0))), which agrees with SPA to about 0.001 deg: both hemispheres, the tropics, the midnight
// sun and the polar night, 1955-2048.
TEST(SolarPosition, MatchesReferencePositionsAroundTheWorld) {
  struct Case {
    const char* name;
    const char* date;
    const char* clock;
    double utc_offset;
    Place place;
    double zenith, azimuth;
  };
  const Case cases[] = {
      {"Sydney, summer", "2021-12-21", "12:00", 11, {-33.8688, 151.2093, 58}, 15.6103, 51.5225},
      {"Quito, equinox", "2013-03-21", "08:00", -5, {-0.1807, -78.4678, 2850}, 65.2470, 89.4462},
      {"Cape Town, winter", "2019-06-21", "16:00", 2, {-33.9249, 18.4241, 0}, 73.2866, 314.6239},
      {"Singapore", "1965-09-10", "10:00", 7.5, {1.3521, 103.8198, 15}, 38.0761, 83.5038},
      {"Longyearbyen, midnight sun", "2024-06-21", "00:00", 2, {78.2232, 15.6267, 0}, 77.9762, 346.1146},
      {"Longyearbyen, polar night", "2024-12-21", "12:00", 1, {78.2232, 15.6267, 0}, 101.6659, 180.9922},
      {"Reykjavik, winter", "1955-01-15", "13:00", 0, {64.1466, -21.9426, 0}, 85.6608, 171.3388},
      {"Ushuaia, summer", "2048-12-21", "18:00", -3, {-54.8019, -68.3030, 0}, 57.9287, 274.2596},
      {"Honolulu, sun near the zenith", "1999-05-27", "12:20", -10, {21.3069, -157.8583, 0}, 1.9936, 88.6994},
  };
  for (const Case& c : cases) {
    const SunPosition p = solar_position(utc(c.date, c.clock, c.utc_offset), c.place, false);
    EXPECT_NEAR(p.zenith_deg, c.zenith, kSpaTolerance) << c.name;
    EXPECT_NEAR(azimuth_arc(p.azimuth_deg, c.azimuth, c.zenith), 0.0, kSpaTolerance) << c.name;
  }
}

// At a solstice the declination is the obliquity (23.44 deg), so at solar noon the zenith angle is
// |latitude - 23.44| in June, and the sun is due south north of the subsolar latitude, due north south of it.
TEST(SolarPosition, NoonZenithAtTheJuneSolsticeIsLatitudeMinusObliquity) {
  const double declination = 23.4372;  // obliquity of 2024, plus the 0.001 deg the sun lacks half a day from the solstice
  for (double latitude : {-60.0, -33.87, -10.0, 0.0, 10.0, 23.0, 40.0, 60.0}) {
    const Place place{latitude, 0.0, 0.0};
    const LocalDate date = parse_date("2024-06-21");
    const SunriseSunset day = sunrise_sunset(date, TimeZone::fixed(0.0), place);
    const SunPosition noon = solar_position(TimeZone::fixed(0.0).utc_seconds(date, day.solar_noon_minutes), place, false);
    EXPECT_NEAR(noon.zenith_deg, std::abs(latitude - declination), 0.01) << "latitude " << latitude;
    const double due = latitude > declination ? 180.0 : 0.0;
    EXPECT_NEAR(azimuth_arc(noon.azimuth_deg, due, noon.zenith_deg), 0.0, 0.01) << "latitude " << latitude;
  }
}

TEST(SolarPosition, MidnightSunAndPolarNightAt78North) {
  const Place longyearbyen{78.2232, 15.6267, 0.0};
  const TimeZone cet = TimeZone::fixed(1.0);
  for (double minutes = 0.0; minutes < 1440.0; minutes += 30.0) {
    // The sun circles above the horizon all day in June, at 11.4 to 35.2 deg elevation...
    const SunPosition june = solar_position(cet.utc_seconds(parse_date("2024-06-21"), minutes), longyearbyen);
    EXPECT_GT(90.0 - june.zenith_deg, 11.0) << minutes;
    EXPECT_LT(90.0 - june.zenith_deg, 35.5) << minutes;
    // ...and below it all day in December.
    const SunPosition december = solar_position(cet.utc_seconds(parse_date("2024-12-21"), minutes), longyearbyen);
    EXPECT_GT(december.zenith_deg, 101.0) << minutes;
  }
}

TEST(SolarPosition, RefractionLiftsTheSunOnlyNearTheHorizon) {
  const Place athens{37.98, 23.73, 70.0};
  const double noon = utc("2024-07-15", "13:00", 3.0);
  const double airless = solar_position(noon, athens, false).zenith_deg;
  EXPECT_NEAR(solar_position(noon, athens, true).zenith_deg, airless, 0.01);

  // Half an hour before sunrise the sun is geometrically well under the horizon: SPA applies no refraction.
  const double before_dawn = utc("2024-07-15", "05:40", 3.0);
  const SunPosition dark = solar_position(before_dawn, athens, false);
  ASSERT_GT(dark.zenith_deg, 93.0);
  EXPECT_DOUBLE_EQ(solar_position(before_dawn, athens, true).zenith_deg, dark.zenith_deg);

  // At the horizon standard refraction is about 0.5 deg.
  const SunriseSunset day = sunrise_sunset(parse_date("2024-07-15"), TimeZone::fixed(3.0), athens);
  const double sunrise = TimeZone::fixed(3.0).utc_seconds(parse_date("2024-07-15"), day.sunrise_minutes + 4.0);
  const double lift = solar_position(sunrise, athens, false).zenith_deg - solar_position(sunrise, athens, true).zenith_deg;
  EXPECT_GT(lift, 0.35);
  EXPECT_LT(lift, 0.65);
}

TEST(SolarPosition, SunDirectionFollowsTheSceneAxes) {
  const auto expect_direction = [](double zenith, double azimuth, const Vec3& expected) {
    const Vec3 d = sun_direction(SunPosition{zenith, azimuth});
    EXPECT_NEAR((d - expected).norm(), 0.0f, 1e-6f) << zenith << " " << azimuth;
    EXPECT_NEAR(d.norm(), 1.0f, 1e-6f);
  };
  expect_direction(0.0, 123.0, Vec3(0, 0, 1));
  expect_direction(90.0, 0.0, Vec3(0, 1, 0));    // north: +Y
  expect_direction(90.0, 90.0, Vec3(1, 0, 0));   // east: +X
  expect_direction(90.0, 180.0, Vec3(0, -1, 0));
  expect_direction(90.0, 270.0, Vec3(-1, 0, 0));
  const float s = std::sqrt(0.5f);
  expect_direction(45.0, 180.0, Vec3(0, -s, s));  // noon sun in the south, 45 deg up

  // Morning sun is in the east.
  const Place denver{39.74, -104.99, 1609.0};
  const Vec3 morning = sun_direction(solar_position(utc("2024-03-20", "08:00", -6.0), denver));
  EXPECT_GT(morning.x(), 0.8f);
  EXPECT_GT(morning.z(), 0.0f);
}

TEST(SolarPosition, DeltaTFollowsObservedValues) {
  // Observed TT - UT1 (IERS): 29.2 s in 1950, 40.2 s in 1970, 63.8 s in 2000, 69.4 s in 2020 (the
  // polynomial, fitted in 2006, extrapolates 71.6 s there; one second moves the sun by 0.04").
  EXPECT_NEAR(delta_t_seconds(1950.0), 29.2, 0.5);
  EXPECT_NEAR(delta_t_seconds(1970.0), 40.2, 0.5);
  EXPECT_NEAR(delta_t_seconds(2000.0), 63.8, 0.5);
  EXPECT_NEAR(delta_t_seconds(2020.0), 69.4, 3.0);
  EXPECT_GT(delta_t_seconds(2050.0), delta_t_seconds(2020.0));
}

TEST(SolarPosition, RejectsImpossiblePlacesAndInstants) {
  EXPECT_THROW(solar_position(0.0, Place{91.0, 0.0, 0.0}), std::invalid_argument);
  EXPECT_THROW(solar_position(0.0, Place{0.0, NAN, 0.0}), std::invalid_argument);
  EXPECT_THROW(solar_position(NAN, Place{}), std::invalid_argument);
  EXPECT_THROW(solar_position(0.0, Place{}, Atmosphere{-1.0, 10.0}), std::invalid_argument);
}

// ---- Sunrise and sunset ----

// U.S. Naval Observatory, "Sun and Moon Data for One Day", Atlanta (33.8 N, 84.4 W), Sunday 6 September
// 2009, Eastern Daylight Time: sunrise 7:15 a.m., sunset 7:56 p.m. (reproduced in the PyEphem manual,
// rhodesmill.org/pyephem/rise-set.html). USNO rounds to the minute.
TEST(SolarSunriseSunset, MatchesTheNavalObservatoryForAtlanta) {
  const Place atlanta{33.8, -84.4, 0.0};
  for (const TimeZone& zone : {TimeZone::named("America/New_York"), TimeZone::fixed(-4.0)}) {
    const SunriseSunset day = sunrise_sunset(parse_date("2009-09-06"), zone, atlanta);
    EXPECT_EQ(day.kind, SunriseSunset::Normal) << zone.name();
    EXPECT_NEAR(day.sunrise_minutes, 7 * 60 + 15, 1.5) << day.to_string();
    EXPECT_NEAR(day.sunset_minutes, 19 * 60 + 56, 1.5) << day.to_string();
    EXPECT_NEAR(day.solar_noon_minutes, 13 * 60 + 36, 1.5) << day.to_string();  // USNO: sun transit 1:36 p.m.
  }
}

TEST(SolarSunriseSunset, TheSunIsOnTheHorizonAtSunriseAndSunset) {
  const Place place{-33.87, 151.21, 0.0};
  const LocalDate date = parse_date("2024-01-10");
  const TimeZone sydney = TimeZone::named("Australia/Sydney");
  const SunriseSunset day = sunrise_sunset(date, sydney, place);
  ASSERT_EQ(day.kind, SunriseSunset::Normal);
  for (double minutes : {day.sunrise_minutes, day.sunset_minutes})
    EXPECT_NEAR(solar_position(sydney.utc_seconds(date, minutes), place, false).zenith_deg, 90.833, 0.002);
  // A minute later the sun is higher after sunrise and lower after sunset.
  EXPECT_LT(solar_position(sydney.utc_seconds(date, day.sunrise_minutes + 1), place, false).zenith_deg, 90.833);
  EXPECT_GT(solar_position(sydney.utc_seconds(date, day.sunset_minutes + 1), place, false).zenith_deg, 90.833);
}

// A place far west of its clock's meridian (60 N, 30 W on UTC+2): solar noon falls at 16:00 and in
// June the sun sets after local midnight, reported past 1440 minutes.
TEST(SolarSunriseSunset, SunsetAfterMidnightIsPast1440Minutes) {
  const Place place{60.0, -30.0, 0.0};
  const TimeZone zone = TimeZone::fixed(2.0);
  const SunriseSunset day = sunrise_sunset(parse_date("2024-06-21"), zone, place);
  ASSERT_EQ(day.kind, SunriseSunset::Normal);
  EXPECT_NEAR(day.solar_noon_minutes, 16 * 60 + 2, 3.0) << day.to_string();
  EXPECT_GT(day.sunset_minutes, 1440.0) << day.to_string();
  // The arc is symmetric about noon within a minute (the declination barely moves at the solstice).
  EXPECT_NEAR(day.sunset_minutes - day.solar_noon_minutes, day.solar_noon_minutes - day.sunrise_minutes, 1.0);
  // The hour angle H of the rise/set zenith z0 at declination d: cos H = (cos z0 - sin lat sin d) / (cos lat cos d).
  const double lat = 60.0 * kDeg, dec = 23.437 * kDeg, z0 = 90.833 * kDeg;
  const double hour_angle = std::acos((std::cos(z0) - std::sin(lat) * std::sin(dec)) / (std::cos(lat) * std::cos(dec)));
  EXPECT_NEAR(day.sunset_minutes - day.sunrise_minutes, 2.0 * hour_angle / kDeg * 4.0, 2.0);  // 4 minutes per degree
}

// Longyearbyen (78.2 N): polar night until mid-February, midnight sun from late April to late August,
// polar night again from late October (Norwegian Polar Institute: midnight sun 20 April - 23 August,
// polar night 26 October - 15 February).
TEST(SolarSunriseSunset, PolarSeasonsInLongyearbyen) {
  const Place longyearbyen{78.2232, 15.6267, 0.0};
  const TimeZone zone = TimeZone::named("Arctic/Longyearbyen");
  const auto kind = [&](const char* date) { return sunrise_sunset(parse_date(date), zone, longyearbyen).kind; };
  EXPECT_EQ(kind("2024-01-15"), SunriseSunset::PolarNight);
  EXPECT_EQ(kind("2024-02-10"), SunriseSunset::PolarNight);
  EXPECT_EQ(kind("2024-02-25"), SunriseSunset::Normal);
  EXPECT_EQ(kind("2024-03-20"), SunriseSunset::Normal);
  EXPECT_EQ(kind("2024-04-25"), SunriseSunset::PolarDay);
  EXPECT_EQ(kind("2024-06-21"), SunriseSunset::PolarDay);
  EXPECT_EQ(kind("2024-08-20"), SunriseSunset::PolarDay);
  EXPECT_EQ(kind("2024-09-01"), SunriseSunset::Normal);
  EXPECT_EQ(kind("2024-11-15"), SunriseSunset::PolarNight);
  EXPECT_EQ(kind("2024-12-21"), SunriseSunset::PolarNight);

  // Count the days of each season over the year; the transitions come within two days of the published dates.
  int polar_day = 0, polar_night = 0;
  for (LocalDate d = parse_date("2024-01-01"); d.year == 2024; d = add_days(d, 1)) {
    const SunriseSunset s = sunrise_sunset(d, zone, longyearbyen);
    polar_day += s.kind == SunriseSunset::PolarDay;
    polar_night += s.kind == SunriseSunset::PolarNight;
    if (s.kind != SunriseSunset::Normal) {
      EXPECT_TRUE(std::isnan(s.sunrise_minutes) && std::isnan(s.sunset_minutes)) << to_string(d);
    } else {
      EXPECT_FALSE(std::isnan(s.sunrise_minutes) && std::isnan(s.sunset_minutes)) << to_string(d);
    }
  }
  const int published_day = days_between(parse_date("2024-04-20"), parse_date("2024-08-23")) + 1;
  const int published_night = days_between(parse_date("2024-10-26"), parse_date("2024-12-31")) + 1 +
                              days_between(parse_date("2024-01-01"), parse_date("2024-02-15")) + 1;
  EXPECT_NEAR(polar_day, published_day, 3);
  EXPECT_NEAR(polar_night, published_night, 3);
}

TEST(SolarSunriseSunset, PolarNightAtTheSouthPoleInJune) {
  const SunriseSunset s = sunrise_sunset(parse_date("2024-06-21"), TimeZone::fixed(12.0), Place{-90.0, 0.0, 2835.0});
  EXPECT_EQ(s.kind, SunriseSunset::PolarNight);
  EXPECT_EQ(sunrise_sunset(parse_date("2024-12-21"), TimeZone::fixed(12.0), Place{-90.0, 0.0, 2835.0}).kind,
            SunriseSunset::PolarDay);
}

// ---- Local time ----

TEST(LocalTime, ParsesDates) {
  const LocalDate leap = parse_date("2024-02-29");
  EXPECT_EQ(leap.year, 2024);
  EXPECT_EQ(leap.month, 2);
  EXPECT_EQ(leap.day, 29);
  EXPECT_EQ(to_string(parse_date("1950-12-31")), "1950-12-31");
}

TEST(LocalTime, RejectsDatesThatDoNotExist) {
  for (const char* text : {"2026-02-30", "2023-02-29", "2024-04-31", "2024-13-01", "2024-00-10", "2024-01-00",
                           "2024-1-5", "2024/01/05", "20240105", "2024-01-05x", " 2024-01-05", "garbage", ""})
    expect_rejected(parse_date, text);
}

TEST(LocalTime, ParsesClockTimes) {
  EXPECT_DOUBLE_EQ(parse_clock_minutes("00:00"), 0.0);
  EXPECT_DOUBLE_EQ(parse_clock_minutes("7:05"), 425.0);
  EXPECT_DOUBLE_EQ(parse_clock_minutes("12:30:30"), 750.5);
  EXPECT_DOUBLE_EQ(parse_clock_minutes("23:59:59"), 1440.0 - 1.0 / 60.0);
  EXPECT_DOUBLE_EQ(parse_clock_minutes("24:00"), 1440.0);
  EXPECT_DOUBLE_EQ(parse_clock_minutes("24:00:00"), 1440.0);
}

TEST(LocalTime, RejectsImpossibleClockTimes) {
  for (const char* text : {"24:01", "24:00:01", "25:00", "12:60", "12:00:60", "12:3", "1230", "-1:00", "12:30:",
                           "12:30:5", "noon", ""})
    expect_rejected(parse_clock_minutes, text);
}

TEST(LocalTime, CountsDaysAcrossMonthsAndLeapYears) {
  EXPECT_EQ(to_string(add_days(parse_date("2024-02-28"), 1)), "2024-02-29");
  EXPECT_EQ(to_string(add_days(parse_date("2023-02-28"), 1)), "2023-03-01");
  EXPECT_EQ(to_string(add_days(parse_date("2023-12-31"), 1)), "2024-01-01");
  EXPECT_EQ(to_string(add_days(parse_date("2024-03-01"), -1)), "2024-02-29");
  EXPECT_EQ(days_between(parse_date("2024-01-01"), parse_date("2025-01-01")), 366);
  EXPECT_EQ(days_between(parse_date("2025-01-01"), parse_date("2024-01-01")), -366);
  EXPECT_EQ(days_between(parse_date("1970-01-01"), parse_date("2000-01-01")), 10957);
}

TEST(LocalTime, FixedOffsets) {
  // 2000-01-01 00:00 UTC is POSIX 946684800.
  EXPECT_DOUBLE_EQ(TimeZone::fixed(0.0).utc_seconds(parse_date("2000-01-01"), 0.0), 946684800.0);
  EXPECT_DOUBLE_EQ(TimeZone::fixed(-7.0).utc_seconds(parse_date("2000-01-01"), 0.0), 946684800.0 + 7 * 3600);
  EXPECT_EQ(TimeZone::fixed(-7.0).name(), "UTC-07:00");
  EXPECT_EQ(TimeZone::fixed(5.5).name(), "UTC+05:30");
  EXPECT_NO_THROW(TimeZone::fixed(14.0));
  EXPECT_NO_THROW(TimeZone::fixed(-12.0));
  EXPECT_THROW(TimeZone::fixed(14.5), std::invalid_argument);
  EXPECT_THROW(TimeZone::fixed(-15.0), std::invalid_argument);
  EXPECT_THROW(TimeZone::fixed(NAN), std::invalid_argument);
}

TEST(LocalTime, MinutesPastMidnightRunIntoTheNextDay) {
  for (const TimeZone& zone : {TimeZone::fixed(-7.0), TimeZone::named("Europe/Athens")}) {
    const LocalDate d = parse_date("2024-07-31");
    EXPECT_DOUBLE_EQ(zone.utc_seconds(d, 1500.0), zone.utc_seconds(parse_date("2024-08-01"), 60.0)) << zone.name();
    EXPECT_DOUBLE_EQ(zone.utc_seconds(d, -60.0), zone.utc_seconds(parse_date("2024-07-30"), 1380.0)) << zone.name();
    EXPECT_DOUBLE_EQ(zone.utc_seconds(d, 1440.0) - zone.utc_seconds(d, 0.0), 86400.0) << zone.name();
    // local_minutes is the inverse, past 1440 too.
    EXPECT_NEAR(zone.local_minutes(d, zone.utc_seconds(d, 1500.25)), 1500.25, 1e-6) << zone.name();
  }
}

TEST(LocalTime, NamedZonesFollowDaylightSavingTime) {
  const TimeZone athens = TimeZone::named("Europe/Athens");
  EXPECT_EQ(athens.name(), "Europe/Athens");
  const LocalDate july = parse_date("2024-07-15"), january = parse_date("2024-01-15");
  EXPECT_DOUBLE_EQ(athens.utc_seconds(july, 720.0), TimeZone::fixed(3.0).utc_seconds(july, 720.0));  // EEST
  EXPECT_DOUBLE_EQ(athens.utc_seconds(january, 720.0), TimeZone::fixed(2.0).utc_seconds(january, 720.0));  // EET
  EXPECT_DOUBLE_EQ(athens.utc_offset_hours(athens.utc_seconds(july, 720.0)), 3.0);

  const TimeZone denver = TimeZone::named("America/Denver");
  EXPECT_DOUBLE_EQ(denver.utc_seconds(parse_date("2003-10-17"), 750.5), utc("2003-10-17", "12:30:30", -6.0));  // MDT
  EXPECT_DOUBLE_EQ(denver.utc_seconds(parse_date("2003-12-17"), 750.5), utc("2003-12-17", "12:30:30", -7.0));  // MST

  // A day with a clock change is 23 or 25 hours long.
  const LocalDate spring = parse_date("2024-03-31"), autumn = parse_date("2024-10-27");
  EXPECT_DOUBLE_EQ(athens.utc_seconds(spring, 1440.0) - athens.utc_seconds(spring, 0.0), 23 * 3600.0);
  EXPECT_DOUBLE_EQ(athens.utc_seconds(autumn, 1440.0) - athens.utc_seconds(autumn, 0.0), 25 * 3600.0);
}

// Athens springs forward from 03:00 to 04:00 on 2024-03-31 and falls back from 04:00 to 03:00 on
// 2024-10-27: a skipped or repeated wall time reads with the offset in force before the change.
TEST(LocalTime, SkippedAndRepeatedClockTimesUseTheOffsetBeforeTheChange) {
  const TimeZone athens = TimeZone::named("Europe/Athens");
  EXPECT_DOUBLE_EQ(athens.utc_seconds(parse_date("2024-03-31"), 3 * 60 + 30), utc("2024-03-31", "01:30", 0.0));
  EXPECT_DOUBLE_EQ(athens.utc_seconds(parse_date("2024-10-27"), 3 * 60 + 30), utc("2024-10-27", "00:30", 0.0));
}

TEST(LocalTime, UnknownZonesAreNamedInTheError) {
  try {
    TimeZone::named("Mars/Olympus_Mons");
    ADD_FAILURE() << "accepted an unknown zone";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("Mars/Olympus_Mons"), std::string::npos) << e.what();
  }
  EXPECT_THROW(TimeZone::named(""), std::invalid_argument);
}
