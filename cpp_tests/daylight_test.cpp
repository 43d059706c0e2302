// Daylight for a place and an interval: time steps, the averaged map's energy bookkeeping, its
// sampling, the ground, and the sun as explicit sources in the tracer.
#include <gtest/gtest.h>

#include <cmath>

#include "annual/annual_contributions.h"
#include "chi2.h"
#include "daylight/daylight.h"
#include "daylight/sky_models.h"
#include "scene/environment_map.h"
#include "test_scenes.h"
#include "trace/contributions.h"
#include "trace/evaluate.h"

namespace fenestra {
namespace {

using test::ObjBuilder;
using test::TempDir;
using test::mask_of_elements_inside;
using test::within_sigma;

DaylightSettings athens_summer(int width = 512, int height = 256) {
  DaylightSettings s;
  s.place = {37.98, 23.73, 0.0};
  s.time_zone = TimeZone::fixed(3.0);
  s.date = s.date_end = parse_date("2026-06-21");
  s.start_minutes = 9 * 60;
  s.end_minutes = 17 * 60;
  s.step_minutes = 60;
  s.turbidity = 3.0;
  s.width = width;
  s.height = height;
  return s;
}

// Sky horizontal illuminance of an analytic radiance by a plain midpoint rule in (cos theta, phi),
// independent of the quadrature the map is normalised with.
double midpoint_horizontal_illuminance(const std::function<double(const Vec3&)>& luminance_of) {
  constexpr int kMu = 400, kPhi = 800;
  double sum = 0.0;
  for (int i = 0; i < kMu; ++i) {
    const double mu = (i + 0.5) / kMu, s = std::sqrt(1.0 - mu * mu);
    for (int j = 0; j < kPhi; ++j) {
      const double phi = 2.0 * M_PI * (j + 0.5) / kPhi;
      sum += mu * luminance_of(Vec3(float(s * std::cos(phi)), float(s * std::sin(phi)), float(mu)));
    }
  }
  return sum * (1.0 / kMu) * (2.0 * M_PI / kPhi);
}

// The map's upper hemisphere summed pixel by pixel (each pixel's solid angle times its mean cosine).
double pixel_sum_horizontal_illuminance(const Daylight& d) {
  double e = 0.0;
  for (int y = 0; y < d.height / 2; ++y) {
    const double t0 = M_PI * y / d.height, t1 = M_PI * (y + 1) / d.height;
    const double cos_solid_angle = (2.0 * M_PI / d.width) * 0.5 * (std::pow(std::sin(t1), 2) - std::pow(std::sin(t0), 2));
    for (int x = 0; x < d.width; ++x) e += cos_solid_angle * luminance(d.pixels[static_cast<size_t>(y) * d.width + x]);
  }
  return e;
}

TEST(DaylightSteps, MidpointsOfStepsWeightedByTheirLength) {
  DaylightSettings s = athens_summer();
  s.start_minutes = 9 * 60;
  s.end_minutes = 10 * 60 + 40;
  s.step_minutes = 30;
  const auto steps = time_steps(s);
  ASSERT_EQ(steps.size(), 4u);  // 9:00-9:30, 9:30-10:00, 10:00-10:30, 10:30-10:40
  const double t0 = s.time_zone.utc_seconds(s.date, 0.0);
  const double mids[] = {9 * 60 + 15, 9 * 60 + 45, 10 * 60 + 15, 10 * 60 + 35};
  const double weights[] = {0.3, 0.3, 0.3, 0.1};
  for (int k = 0; k < 4; ++k) {
    EXPECT_NEAR(steps[k].utc_seconds - t0, mids[k] * 60.0, 1e-6) << k;
    EXPECT_NEAR(steps[k].weight, weights[k], 1e-12) << k;
  }
}

TEST(DaylightSteps, IntervalCrossingMidnightAndDateRanges) {
  DaylightSettings s = athens_summer();
  s.start_minutes = 22 * 60;
  s.end_minutes = 2 * 60;
  s.step_minutes = 60;
  auto steps = time_steps(s);
  ASSERT_EQ(steps.size(), 4u);
  EXPECT_NEAR(steps.back().utc_seconds - steps.front().utc_seconds, 3 * 3600.0, 1e-6);
  EXPECT_NEAR(steps.back().utc_seconds - s.time_zone.utc_seconds(add_days(s.date, 1), 0.0), 90 * 60.0, 1e-6);

  s.date_end = add_days(s.date, 2);  // three nights
  steps = time_steps(s);
  ASSERT_EQ(steps.size(), 12u);
  EXPECT_NEAR(steps[4].utc_seconds - steps[0].utc_seconds, 86400.0, 1e-6);
  double total = 0.0;
  for (const auto& t : steps) total += t.weight;
  EXPECT_NEAR(total, 1.0, 1e-12);

  s.date_end = add_days(s.date, -1);
  EXPECT_THROW(time_steps(s), std::invalid_argument);
  s.date_end = s.date;
  s.start_minutes = s.end_minutes = 12 * 60;  // one instant
  steps = time_steps(s);
  ASSERT_EQ(steps.size(), 1u);
  EXPECT_NEAR(steps[0].utc_seconds, s.time_zone.utc_seconds(s.date, 12 * 60), 1e-6);
  s.step_minutes = 0.0;
  EXPECT_THROW(time_steps(s), std::invalid_argument);
}

TEST(Daylight, MapAndSunsCarryTheMeanOfThePerStepAnalyticIlluminances) {
  const DaylightSettings s = athens_summer();
  const Daylight d = make_daylight(s);
  ASSERT_EQ(d.steps, 8u);
  ASSERT_EQ(d.steps_with_sun, 8u);
  ASSERT_EQ(d.suns.size(), 8u);
  double sky = 0.0, sun = 0.0;
  for (const TimeStep& step : time_steps(s)) {
    const SunPosition p = solar_position(step.utc_seconds, s.place, true);
    const Vec3 dir = sun_direction(p);
    const PreethamSky model(s.turbidity, dir);
    sky += step.weight * midpoint_horizontal_illuminance([&](const Vec3& w) { return model.luminance(w); });
    sun += step.weight * luminance(preetham_sun(s.turbidity, p.zenith_deg * M_PI / 180.0).normal_illuminance()) * dir.z();
  }
  // The midpoint rule above is good to ~1e-4 (the circumsolar cusp); the pixels are summed here,
  // independently of the builder's own bookkeeping.
  EXPECT_NEAR(pixel_sum_horizontal_illuminance(d), sky, 1e-3 * sky);
  EXPECT_NEAR(luminance(d.sky_horizontal), sky, 1e-3 * sky);
  EXPECT_NEAR(luminance(d.analytic_sky_horizontal), luminance(d.sky_horizontal), 1e-4 * sky);
  EXPECT_NEAR(luminance(SunLights(d.suns).horizontal_illuminance()), sun, 1e-4 * sun);
  EXPECT_NEAR(luminance(d.sun_horizontal), sun, 1e-4 * sun);
  // A clear summer day: direct sun outweighs the sky several times over.
  EXPECT_GT(sun, 2.0 * sky);
  double weights = 0.0;
  for (const SunLight& l : d.suns) weights += l.weight;
  EXPECT_NEAR(weights, 1.0, 1e-9);
}

TEST(Daylight, GroundBelowTheHorizonIsReflectanceTimesHorizontalIlluminanceOverPi) {
  DaylightSettings s = athens_summer(128, 64);
  s.ground_reflectance = 0.3;
  const Daylight d = make_daylight(s);
  const Rgb expected = (d.sky_horizontal + d.sun_horizontal) * static_cast<float>(0.3 / M_PI);
  for (int y = d.height / 2; y < d.height; ++y)
    for (int x = 0; x < d.width; x += 7)
      EXPECT_TRUE(d.pixels[static_cast<size_t>(y) * d.width + x].isApprox(expected, 1e-6f)) << y << " " << x;
}

TEST(Daylight, PolarNightIsDarkAndPolarDayHasSunAtMidnight) {
  DaylightSettings s = athens_summer(64, 32);
  s.place = {80.0, 15.0, 0.0};
  s.time_zone = TimeZone::fixed(1.0);
  s.date = s.date_end = parse_date("2026-12-21");
  s.start_minutes = 0;
  s.end_minutes = 24 * 60;
  const Daylight night = make_daylight(s);
  EXPECT_EQ(night.steps, 24u);
  EXPECT_EQ(night.steps_with_sun, 0u);
  EXPECT_TRUE(night.suns.empty());
  for (const Rgb& p : night.pixels) ASSERT_TRUE((p == 0.0f).all());

  s.date = s.date_end = parse_date("2026-06-21");
  s.start_minutes = 23 * 60;
  s.end_minutes = 60;  // around midnight, across it
  const Daylight day = make_daylight(s);
  EXPECT_EQ(day.steps_with_sun, day.steps);
  EXPECT_GT(luminance(day.sun_horizontal), 0.0f);
  for (const SunLight& l : day.suns)
    EXPECT_GT(l.direction.y(), 3.0f * std::abs(l.direction.x())) << "the midnight sun lies to the north";
}

TEST(Daylight, NorthOffsetTurnsTheSunClockwise) {
  DaylightSettings s = athens_summer(64, 32);
  s.start_minutes = s.end_minutes = 12 * 60;
  const Daylight a = make_daylight(s);
  s.north_offset_deg = 90.0;
  const Daylight b = make_daylight(s);
  ASSERT_EQ(a.suns.size(), 1u);
  ASSERT_EQ(b.suns.size(), 1u);
  // (x, y) -> (y, -x): a quarter turn clockwise seen from above.
  EXPECT_NEAR(b.suns[0].direction.x(), a.suns[0].direction.y(), 1e-5);
  EXPECT_NEAR(b.suns[0].direction.y(), -a.suns[0].direction.x(), 1e-5);
  EXPECT_NEAR(b.suns[0].direction.z(), a.suns[0].direction.z(), 1e-6);
}

TEST(Daylight, CieOvercastHorizontalIlluminanceIsSevenPiOverNineZenithLuminance) {
  DaylightSettings s;
  s.model = DaylightSettings::Model::CieOvercast;
  s.horizontal_illuminance = 10000.0;
  s.width = 256;
  s.height = 128;
  const Daylight d = make_daylight(s);
  EXPECT_NEAR(pixel_sum_horizontal_illuminance(d), 10000.0, 1.0);
  EXPECT_TRUE(d.suns.empty());
  const double lz = 10000.0 * 9.0 / (7.0 * M_PI);
  // Top row: polar angle pi / 256 / 2, so (1 + 2 cos) / 3 differs from 1 by ~1e-5.
  EXPECT_NEAR(luminance(d.pixels[0]), lz, 1e-3 * lz);
  // The horizon row is a third of the zenith.
  EXPECT_NEAR(luminance(d.pixels[static_cast<size_t>(d.height / 2 - 1) * d.width]), lz / 3.0, 0.01 * lz);
}

TEST(Daylight, RejectsSettingsOutsideTheModel) {
  DaylightSettings s = athens_summer(64, 32);
  s.turbidity = 12.0;
  EXPECT_THROW(make_daylight(s), std::invalid_argument);
  s = athens_summer(64, 31);
  EXPECT_THROW(make_daylight(s), std::invalid_argument);
  s = athens_summer(64, 32);
  s.ground_reflectance = 1.5;
  EXPECT_THROW(make_daylight(s), std::invalid_argument);
  s = athens_summer(64, 32);
  s.place.latitude_deg = 95.0;
  EXPECT_THROW(make_daylight(s), std::invalid_argument);
}

TEST(Daylight, MapSamplingFollowsItsPdfChi2) {
  DaylightSettings s = athens_summer(64, 32);
  s.start_minutes = s.end_minutes = 10 * 60;  // one instant: a strong circumsolar peak
  const Daylight d = make_daylight(s);
  const EnvironmentMap map(d.width, d.height, d.pixels, 1.0f, 0.0f);
  fenestra_test::SphereGrid grid;  // cells of 2 x 2 pixels: the pdf is smooth within each
  grid.theta_res = 16;
  grid.phi_res = 32;
  grid.theta_max = M_PI;
  const auto r = fenestra_test::sphere_chi2(
      grid, 1000000, 71,
      [&](Rng& rng, Vec3* dir) {
        float pdf = 0.0f;
        *dir = map.sample(fenestra_test::next2(rng), &pdf);
        return pdf > 0.0f;
      },
      [&](const Vec3& dir) { return map.pdf(dir); }, fenestra_test::kSignificance);
  EXPECT_TRUE(r.passed) << r.message;
}

// ---------------------------------------------------------------------------------------------
// The sun in the tracer.

TEST(SunLights, PicksInProportionToIlluminanceAndStaysUnbiased) {
  const std::vector<SunLight> suns = {{Vec3(0, 0, 1), Rgb::Constant(1000.0f), 0.2},
                                      {Vec3(1, 0, 0), Rgb::Constant(3000.0f), 0.5},
                                      {Vec3(0, 0.6f, 0.8f), Rgb::Constant(6000.0f), 0.3}};
  const SunLights lights(suns);
  constexpr int kDraws = 100000;  // stratified picks
  int picked[3] = {0, 0, 0};
  double mean = 0.0;
  const float cos_half = std::cos(0.5 * SunLights::kAngularDiameterDeg * M_PI / 180.0);
  for (int i = 0; i < kDraws; ++i) {
    const SunLights::Sample s = lights.sample((i + 0.5f) / kDraws, Vec2(0.37f, 0.81f));
    mean += luminance(s.illuminance) / kDraws;
    for (int k = 0; k < 3; ++k) {
      if (s.direction.dot(suns[k].direction) >= cos_half - 1e-6f) {
        ++picked[k];
        EXPECT_NEAR(luminance(s.illuminance), 10000.0f, 1.0f) << k;  // E_k / (E_k / sum E)
      }
    }
  }
  EXPECT_EQ(picked[0] + picked[1] + picked[2], kDraws);
  EXPECT_NEAR(picked[0], 0.1 * kDraws, 2);
  EXPECT_NEAR(picked[1], 0.3 * kDraws, 2);
  EXPECT_NEAR(mean, 10000.0, 0.1);
  EXPECT_NEAR(luminance(lights.horizontal_illuminance()), 1000.0f + 0.0f + 6000.0f * 0.8f, 1e-2f);
}

std::string box_scene_json(const std::string& domain_material, const std::string& sensors, int paths,
                           const std::string& sky) {
  return R"({"fenestra": 1, "geometry": "scene.obj",
    "materials": {"grey": {"reflectance": 0.6}, "domain": {"reflectance": 0.5}, "black": {"reflectance": 0},
                  "ground": {"reflectance": 0.2}},
    "opening_domain": {"materials": [")" + domain_material + R"("], "element_size": 0.5},
    "sensors": )" + sensors + R"(, "sky": )" + sky + R"(,
    "render": {"paths_per_sensor": )" + std::to_string(paths) + R"(, "seed": 3}})";
}

TEST(Sun, ThroughARoofOpeningItLightsItsPatchAndNothingElse) {
  TempDir dir;
  ObjBuilder obj;  // a black 2 m cube whose roof hosts openings
  obj.box({0, 0, 0}, {2, 2, 2}, [](const std::string& f) { return f == "ceiling" ? "domain" : "black"; });
  dir.write("scene.obj", obj.str());
  dir.write("scene.json", box_scene_json("domain", R"({"points": [[1, 1.2, 0], [1.6, 1, 0], [0.5, 0.5, 0]], "normals": [0, 0, 1]})",
                                         1024, R"({"type": "uniform", "radiance": 0})"));
  Scene scene = load_scene(dir.file("scene.json"));
  // A sun 20 degrees from the zenith toward +X, 100 klx at normal incidence; the sky is black.
  // Looking at it, a floor point sees the roof 2 tan(20) = 0.728 m further along +X.
  const float t = 20.0f * kPi / 180.0f;
  const Vec3 sun_dir(std::sin(t), 0.0f, std::cos(t));
  const float en = 100000.0f, direct = en * std::cos(t);
  scene.suns = SunLights({{sun_dir, Rgb::Constant(en), 1.0, 0.0, 20.0, 90.0}});
  const Rectangle hole = {Vec3(1.5f, 0.5f, 2), Vec3(2, 0.5f, 2), Vec3(2, 1.5f, 2), Vec3(1.5f, 1.5f, 2)};
  const SensorValues v = evaluate_openings(scene, {hole});
  EXPECT_NEAR(v.value[0], direct, 1e-3 * direct);  // looks through (1.728, 1.2): the hole
  EXPECT_EQ(v.value[1], 0.0);                      // the east wall hides the sun
  EXPECT_EQ(v.value[2], 0.0);                      // looks through (1.228, 0.5): roof
  // The one-pass records agree: the sun reaches sensor 0 through exactly one element.
  const Contributions c = compute_contributions(scene);
  EXPECT_NEAR(c.E.row(0).sum(), direct, 1e-3 * direct);
  EXPECT_NEAR(c.E.row(0).maxCoeff(), direct, 1e-3 * direct);
  EXPECT_NEAR(c.evaluate(mask_of_elements_inside(scene, hole)).value[0], direct, 1e-3 * direct);
  EXPECT_NEAR(c.all_open.value[0], direct, 1e-3 * direct);
  EXPECT_EQ(c.all_open.value[1], 0.0);
  EXPECT_NEAR(c.all_open.value[2], direct, 1e-3 * direct);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(c.closed.value[i], 0.0) << i;
}

TEST(Sun, ExactRecordsEqualEvaluateUnderAPreethamSky) {
  // A room with a south window under a Preetham sky and a low winter sun from the south; light
  // also reaches it from the sunlit ground.
  TempDir dir;
  ObjBuilder obj;
  obj.box({0, 0, 0}, {3, 3, 2.5f}, [](const std::string& f) { return f == "south" ? "domain" : "grey"; });
  obj.quad("ground", "ground", {-30, -30, -0.01f}, {30, -30, -0.01f}, {30, 30, -0.01f}, {-30, 30, -0.01f});
  dir.write("scene.obj", obj.str());
  dir.write("scene.json",
            box_scene_json("domain", R"({"points": [[1.5, 0.8, 0.8], [0.5, 2.5, 0.8], [2.5, 2.0, 1.5]], "normals": [0, 0, 1]})",
                           1 << 13,
                           R"({"type": "preetham", "latitude": 37.98, "longitude": 23.73, "utc_offset": 2,
                               "date": "2026-12-21", "start": "11:00", "end": "14:00", "step_minutes": 30,
                               "turbidity": 3.0, "resolution": [256, 128]})"));
  const Scene scene = load_scene(dir.file("scene.json"));
  ASSERT_EQ(scene.suns.suns().size(), 6u);
  const Contributions c = compute_contributions(scene);
  const Rectangle window = {Vec3(0.5f, 0, 0.5f), Vec3(2.5f, 0, 0.5f), Vec3(2.5f, 0, 2), Vec3(0.5f, 0, 2)};
  const SensorValues truth = evaluate_openings(scene, {window});
  const auto mask = mask_of_elements_inside(scene, window);
  ASSERT_EQ(std::count(mask.begin(), mask.end(), 1), 12);
  const SensorValues exact = c.evaluate(mask);
  for (int i = 0; i < 3; ++i) {
    EXPECT_TRUE(within_sigma(exact.value[i], exact.standard_error[i], truth.value[i], truth.standard_error[i]))
        << "sensor " << i;
    EXPECT_GT(truth.value[i], 0.0);
  }
}

TEST(Sun, UnobstructedSensorReadsTheSkyAndSunHorizontalIlluminance) {
  TempDir dir;
  ObjBuilder obj;  // a domain square far below the sensors: they cannot see it
  obj.quad("slab", "domain", {-1, -1, -10}, {1, -1, -10}, {1, 1, -10}, {-1, 1, -10});
  dir.write("scene.obj", obj.str());
  dir.write("scene.json",
            box_scene_json("domain", R"({"points": [[0, 0, 0]], "normals": [0, 0, 1]})", 1 << 14,
                           R"({"type": "preetham", "latitude": 51.48, "longitude": 0.0, "timezone": "Europe/London",
                               "date": "2026-04-15", "start": "08:00", "end": "18:00", "turbidity": 4.0,
                               "resolution": [512, 256]})"));
  const Scene scene = load_scene(dir.file("scene.json"));
  const double expected = luminance(scene.daylight->sky_horizontal + scene.daylight->sun_horizontal);
  const SensorValues v = evaluate_openings(scene, {});
  EXPECT_TRUE(within_sigma(v.value[0], v.standard_error[0], expected, 0.0));
  EXPECT_LT(v.standard_error[0], 0.01 * expected);
}

TEST(DaylightScene, BadSkySettingsNameTheKey) {
  TempDir dir;
  ObjBuilder obj;
  obj.quad("slab", "domain", {-1, -1, -10}, {1, -1, -10}, {1, 1, -10}, {-1, 1, -10});
  dir.write("scene.obj", obj.str());
  const std::string base = R"("type": "preetham", "latitude": 37.98, "longitude": 23.73, "date": "2026-06-21")";
  const std::pair<std::string, std::string> cases[] = {
      {base + R"(, "utc_offset": 2, "turbidity": 20)", "sky.turbidity"},
      {base + R"(, "utc_offset": 2, "turbidty": 3)", "sky.turbidty"},
      {base, "sky.utc_offset"},
      {base + R"(, "timezone": "Mars/Olympus_Mons")", "Mars/Olympus_Mons"},
      {base + R"(, "utc_offset": 2, "start": "25:00")", "25:00"},
      {R"("type": "preetham", "latitude": 37.98, "longitude": 23.73, "utc_offset": 2, "date": "2026-02-30")",
       "2026-02-30"},
      {R"("type": "preetham", "longitude": 23.73, "utc_offset": 2, "date": "2026-06-21")", "sky.latitude"},
      {R"("type": "cie_overcast", "horizontal_illuminance": -5)", "sky.horizontal_illuminance"},
      {R"("type": "daylight")", "sky.type"},
  };
  for (const auto& [sky, needle] : cases) {
    dir.write("scene.json", box_scene_json("domain", R"({"points": [[0, 0, 0]], "normals": [0, 0, 1]})", 16,
                                           "{" + sky + "}"));
    try {
      load_scene(dir.file("scene.json"));
      ADD_FAILURE() << "accepted " << sky;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("scene.json"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace fenestra
