// The weather-driven skies of the scene file: "perez" (one Perez all-weather sky, from constant
// irradiances or a weather file's rows) and "climate" (a year's sky matrix and the cumulative sky
// of its occupied hours). See docs/sky.md and docs/scene-format.md.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "daylight/daylight.h"
#include "daylight/perez_all_weather.h"
#include "daylight/sky_matrix.h"
#include "daylight/sky_figures.h"
#include "test_scenes.h"

namespace fenestra {
namespace {

using test::ObjBuilder;
using test::TempDir;

using test::kChicago;

// A domain square far below one sensor, under `sky` (JSON object text).
Scene load_with_sky(const TempDir& dir, const std::string& sky) {
  ObjBuilder obj;
  obj.quad("slab", "domain", {-1, -1, -10}, {1, -1, -10}, {1, 1, -10}, {-1, 1, -10});
  dir.write("scene.obj", obj.str());
  dir.write("scene.json", R"({"fenestra": 1, "geometry": "scene.obj", "materials": {"domain": {"reflectance": 0.5}},
    "opening_domain": {"materials": ["domain"], "element_size": 0.5},
    "sensors": {"points": [[0, 0, 0]], "normals": [0, 0, 1]}, "sky": )" + sky + "}");
  return load_scene(dir.file("scene.json"));
}

void expect_refused(const TempDir& dir, const std::string& sky, const std::vector<std::string>& needles) {
  try {
    load_with_sky(dir, sky);
    ADD_FAILURE() << "accepted " << sky;
  } catch (const std::invalid_argument& e) {
    for (const std::string& needle : needles)
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << "'" << needle << "' not in: " << e.what();
    EXPECT_NE(std::string(e.what()).find("scene.json"), std::string::npos) << e.what();
  }
}

double map_horizontal(const Daylight& d) { return luminance(map_horizontal_illuminance(d.width, d.height, d.pixels)); }

// The Perez sky of an instant at a place, as the scene's steps make it.
PerezAllWeatherSky perez_at(double utc, const Place& place, int day, double dni, double dhi, double dew) {
  PerezSkyInput in;
  in.sun = sun_direction(model_sun_position(utc, place, 0.0));
  in.day_of_year = day;
  in.direct_normal_w_m2 = dni;
  in.diffuse_horizontal_w_m2 = dhi;
  in.dew_point_c = dew;
  return PerezAllWeatherSky::create(in);
}

TEST(PerezScene, ConstantIrradianceGivesTheModelsDiffuseAndDirectIlluminance) {
  TempDir dir;
  const Scene scene = load_with_sky(dir, R"({"type": "perez", "latitude": 41.98, "longitude": -87.92,
      "utc_offset": -6, "date": "2026-06-21", "time": "12:30", "direct_normal": 700, "diffuse_horizontal": 120,
      "dew_point": 15, "ground_reflectance": 0.3, "resolution": [512, 256]})");
  ASSERT_TRUE(scene.daylight);
  EXPECT_FALSE(scene.climate);
  const Place place{41.98, -87.92, 0.0};
  const double utc = TimeZone::fixed(-6.0).utc_seconds(LocalDate{2026, 6, 21}, 12.5 * 60.0);
  const PerezAllWeatherSky sky = perez_at(utc, place, 172, 700.0, 120.0, 15.0);
  const double diffuse = 120.0 * sky.diffuse_efficacy(), direct = 700.0 * sky.direct_efficacy();
  EXPECT_GT(sky.diffuse_efficacy(), 100.0);
  // The map's own upper hemisphere carries DHI x diffuse efficacy, the sun DNI x direct efficacy.
  EXPECT_NEAR(map_horizontal(*scene.daylight), diffuse, 1e-4 * diffuse);
  EXPECT_NEAR(luminance(scene.daylight->sky_horizontal), diffuse, 1e-4 * diffuse);
  ASSERT_EQ(scene.suns.suns().size(), 1u);
  const SunLight& sun = scene.suns.suns()[0];
  EXPECT_NEAR(luminance(sun.normal_illuminance), direct, 1e-5 * direct);
  EXPECT_FLOAT_EQ(sun.normal_illuminance[0], sun.normal_illuminance[2]);  // white
  EXPECT_LT((sun.direction - sun_direction(model_sun_position(utc, place, 0.0))).norm(), 1e-6f);
  // Ground: reflectance x (diffuse + direct x cos zenith) / pi.
  const double global = diffuse + direct * sun.direction.z();
  const Rgb ground = scene.daylight->pixels.back();
  EXPECT_NEAR(luminance(ground), 0.3 * global / kPiD, 1e-4 * global);
  EXPECT_NE(scene.sky->to_string().find("Perez sky"), std::string::npos) << scene.sky->to_string();
}

TEST(PerezScene, AnIntervalAveragesTheStepsSkies) {
  TempDir dir;
  const Scene scene = load_with_sky(dir, R"({"type": "perez", "latitude": 41.98, "longitude": -87.92,
      "utc_offset": -6, "date": "2026-03-20", "start": "07:00", "end": "19:00", "step_minutes": 60,
      "direct_normal": 500, "diffuse_horizontal": 150, "resolution": [256, 128]})");
  const Place place{41.98, -87.92, 0.0};
  double diffuse = 0.0, direct_horizontal = 0.0;
  int up = 0;
  for (int k = 0; k < 12; ++k) {  // 12 steps, each at its middle, weight 1/12
    const double utc = TimeZone::fixed(-6.0).utc_seconds(LocalDate{2026, 3, 20}, (7.5 + k) * 60.0);
    const SunPosition p = model_sun_position(utc, place, 0.0);
    if (!(p.zenith_deg < 90.0)) continue;  // constant irradiances light the day only
    ++up;
    const PerezAllWeatherSky sky = perez_at(utc, place, 79, 500.0, 150.0, std::nan(""));
    diffuse += sky.diffuse_horizontal_illuminance() / 12.0;
    direct_horizontal += sky.direct_normal_illuminance() * std::cos(p.zenith_deg * kPiD / 180.0) / 12.0;
  }
  EXPECT_EQ(up, 11);  // the equinox sun is up from about 06:00 to 18:05 standard time: 18:30 is down
  EXPECT_EQ(scene.daylight->steps, 12u);
  EXPECT_EQ(scene.daylight->steps_with_sun, size_t(up));
  EXPECT_EQ(scene.suns.suns().size(), size_t(up));
  EXPECT_NEAR(map_horizontal(*scene.daylight), diffuse, 1e-4 * diffuse);
  EXPECT_NEAR(luminance(scene.suns.horizontal_illuminance()), direct_horizontal, 1e-4 * direct_horizontal);
}

TEST(PerezScene, AWeatherFileGivesEachStepTheRowOfItsHour) {
  TempDir dir;
  const WeatherData w = read_weather(kChicago);
  // 12:10 daylight saving time (UTC-5) is 11:10 standard time: the row of 11:00-12:00, hour 12.
  const Scene scene = load_with_sky(dir, R"({"type": "perez", "weather": ")" + kChicago +
                                             R"(", "date": "2026-06-21", "time": "12:10", "utc_offset": -5})");
  const size_t row = (31 + 28 + 31 + 30 + 31 + 20) * 24 + 11;
  ASSERT_EQ(w.hours[row].hour_ending, 12);
  ASSERT_GT(w.hours[row].direct_normal_w_m2, 0.0);
  const Place station{w.location.latitude_deg, w.location.longitude_deg, w.location.elevation_m};
  const double utc = TimeZone::fixed(-5.0).utc_seconds(LocalDate{2026, 6, 21}, 12.0 * 60.0 + 10.0);
  const WeatherHour& h = w.hours[row];
  const PerezAllWeatherSky sky = perez_at(utc, station, 172, h.direct_normal_w_m2, h.diffuse_horizontal_w_m2, h.dew_point_c);
  ASSERT_EQ(scene.suns.suns().size(), 1u);
  EXPECT_NEAR(luminance(scene.suns.suns()[0].normal_illuminance), sky.direct_normal_illuminance(),
              1e-5 * sky.direct_normal_illuminance());
  EXPECT_NEAR(map_horizontal(*scene.daylight), sky.diffuse_horizontal_illuminance(),
              1e-4 * sky.diffuse_horizontal_illuminance());
  // Without a clock the file's standard time applies: 11:10 is the same instant.
  const Scene same = load_with_sky(dir, R"({"type": "perez", "weather": ")" + kChicago +
                                            R"(", "date": "2026-06-21", "time": "11:10"})");
  EXPECT_EQ(luminance(same.suns.suns()[0].normal_illuminance), luminance(scene.suns.suns()[0].normal_illuminance));
  EXPECT_NE(std::find(same.input_files.begin(), same.input_files.end(), kChicago), same.input_files.end());
  EXPECT_TRUE(sky_warnings(same.daylight.get()).empty());
}

TEST(PerezScene, BadInputIsRefusedNamingTheKeyAndValue) {
  TempDir dir;
  const std::string place = R"("type": "perez", "latitude": 41.98, "longitude": -87.92, "utc_offset": -6,
      "date": "2026-06-21")";
  expect_refused(dir, "{" + place + R"(, "direct_normal": -5, "diffuse_horizontal": 100})", {"sky.direct_normal", "-5"});
  expect_refused(dir, "{" + place + R"(, "direct_normal": 1400, "diffuse_horizontal": 100})",
                 {"sky.direct_normal", "1400", "extraterrestrial", "2026-06-21"});
  expect_refused(dir, "{" + place + R"(, "direct_normal": 500, "diffuse_horizontal": "x"})", {"sky.diffuse_horizontal", "\"x\""});
  expect_refused(dir, "{" + place + R"(, "direct_normal": 500})", {"sky.diffuse_horizontal"});
  expect_refused(dir, "{" + place + R"(, "direct_normal": 500, "diffuse_horizontal": 100, "dew_point": 75})",
                 {"sky.dew_point", "75"});
  expect_refused(dir, "{" + place + R"(, "direct_normal": 500, "diffuse_horizontal": 100, "turbidity": 3})",
                 {"sky.turbidity", "unknown key"});
  expect_refused(dir, "{" + place + R"(, "weather": ")" + kChicago + R"(", "direct_normal": 500})",
                 {"sky.direct_normal", "either weather or"});
  expect_refused(dir, R"({"type": "perez", "weather": "nowhere.epw", "date": "2026-06-21"})",
                 {"sky.weather", "nowhere.epw"});
  expect_refused(dir, R"({"type": "perez", "weather": ")" + kChicago + R"(", "latitude": 40, "date": "2026-06-21"})",
                 {"sky.longitude"});
  expect_refused(dir, R"({"type": "perez", "weather": ")" + kChicago + R"(", "date": "2024-02-29", "time": "12:00"})",
                 {"no row for 2/29"});
  expect_refused(dir, R"({"type": "perez", "weather": ")" + kChicago + R"(", "time": "12:00"})", {"sky.date"});
}

TEST(ClimateScene, TheChicagoYearGivesAMatrixAndTheCumulativeSkyOfItsOccupiedHours) {
  TempDir dir;
  const Scene scene = load_with_sky(dir, R"({"type": "climate", "weather": ")" + kChicago + R"("})");
  ASSERT_TRUE(scene.climate);
  const Climate& c = *scene.climate;
  ASSERT_TRUE(c.sky && c.weather);
  EXPECT_EQ(c.settings.subdivision, 1);
  EXPECT_EQ(c.settings.weather_path, kChicago);
  EXPECT_DOUBLE_EQ(c.settings.place.latitude_deg, 41.98);
  EXPECT_DOUBLE_EQ(c.settings.time_zone_hours, -6.0);
  EXPECT_EQ(c.sky->radiance.rows(), 146);
  EXPECT_EQ(c.sky->radiance.cols(), 8760);
  EXPECT_NE(std::find(scene.input_files.begin(), scene.input_files.end(), kChicago), scene.input_files.end());
  EXPECT_NE(scene.sky->to_string().find("climate of"), std::string::npos);
  // The cumulative sky: every occupied hour weighs 1 / 3650; its map holds the mean diffuse
  // illuminance of the matrix's hours and its suns their mean direct illuminance.
  const SkyMatrix& m = *c.sky;
  const std::vector<size_t> occupied = occupied_hours(m.hours, c.settings);
  ASSERT_EQ(occupied.size(), 3650u);
  double diffuse = 0.0, direct = 0.0;
  size_t sunny = 0;
  for (size_t i : occupied) {
    diffuse += m.diffuse_horizontal_lux[i] / 3650.0;
    direct += m.sun_normal_illuminance[i] * std::max(0.0f, m.sun_direction[i].z()) / 3650.0;
    sunny += m.sun_normal_illuminance[i] > 0.0f;
  }
  ASSERT_EQ(scene.suns.suns().size(), sunny);
  for (const SunLight& s : scene.suns.suns()) EXPECT_DOUBLE_EQ(s.weight, 1.0 / 3650.0);
  EXPECT_NEAR(map_horizontal(*scene.daylight), diffuse, 1e-4 * diffuse);
  EXPECT_NEAR(luminance(scene.suns.horizontal_illuminance()), direct, 1e-4 * direct);
  EXPECT_EQ(scene.daylight->width, 256);
  EXPECT_TRUE(sky_warnings(scene.daylight.get()).empty());
}

TEST(ClimateScene, SettingsAreReadAndAFarPlaceIsWarned) {
  TempDir dir;
  const Scene scene = load_with_sky(dir, R"({"type": "climate", "weather": ")" + kChicago + R"(", "patches": 2,
      "occupied": ["09:00", "17:00"], "north_offset_deg": 20, "ground_reflectance": 0.1,
      "latitude": 37.98, "longitude": 23.73, "elevation": 100, "resolution": [64, 32]})");
  const ClimateSettings& s = scene.climate->settings;
  EXPECT_EQ(s.subdivision, 2);
  EXPECT_EQ(scene.climate->sky->radiance.rows(), 578);
  EXPECT_DOUBLE_EQ(s.occupied_start_hour, 9.0);
  EXPECT_DOUBLE_EQ(s.occupied_end_hour, 17.0);
  EXPECT_DOUBLE_EQ(s.north_offset_deg, 20.0);
  EXPECT_DOUBLE_EQ(s.ground_reflectance, 0.1);
  EXPECT_DOUBLE_EQ(s.place.latitude_deg, 37.98);
  EXPECT_DOUBLE_EQ(s.place.elevation_m, 100.0);
  EXPECT_EQ(occupied_hours(scene.climate->sky->hours, s).size(), 2920u);
  EXPECT_EQ(scene.daylight->steps, 2920u);
  EXPECT_EQ(scene.daylight->width, 64);
  const std::vector<std::string> warnings = sky_warnings(scene.daylight.get());
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("37.98"), std::string::npos) << warnings[0];
  EXPECT_NE(warnings[0].find("Chicago"), std::string::npos) << warnings[0];
  EXPECT_EQ(scene.climate->sky->warnings, warnings);
}

TEST(ClimateScene, BadInputIsRefusedNamingTheKeyAndValue) {
  TempDir dir;
  const std::string weather = R"("type": "climate", "weather": ")" + kChicago + R"(")";
  expect_refused(dir, R"({"type": "climate", "weather": "missing.epw"})",
                 {"sky.weather", "cannot open weather file", "missing.epw"});
  expect_refused(dir, R"({"type": "climate"})", {"sky.weather"});
  expect_refused(dir, R"({"type": "climate", "weather": "scene.obj"})", {"sky.weather", ".obj"});
  expect_refused(dir, "{" + weather + R"(, "patches": 3})", {"sky.patches", "3"});
  expect_refused(dir, "{" + weather + R"(, "patches": "2"})", {"sky.patches", "\"2\""});
  expect_refused(dir, "{" + weather + R"(, "patches": 0})", {"sky.patches"});
  expect_refused(dir, "{" + weather + R"(, "turbidity": 3})", {"sky.turbidity", "unknown key"});
  expect_refused(dir, "{" + weather + R"(, "direct_normal": 300})", {"sky.direct_normal", "unknown key"});
  expect_refused(dir, "{" + weather + R"(, "occupied": ["18:00", "08:00"]})", {"sky.occupied", "18:00"});
  expect_refused(dir, "{" + weather + R"(, "occupied": ["8am", "6pm"]})", {"sky.occupied", "8am"});
  expect_refused(dir, "{" + weather + R"(, "occupied": "08:00-18:00"})", {"sky.occupied"});
  expect_refused(dir, "{" + weather + R"(, "latitude": 40})", {"sky.longitude"});
  expect_refused(dir, "{" + weather + R"(, "ground_reflectance": 2})", {"sky.ground_reflectance", "2"});
  expect_refused(dir, "{" + weather + R"(, "north_offset_deg": 400})", {"sky.north_offset_deg", "400"});
}

}  // namespace
}  // namespace fenestra
