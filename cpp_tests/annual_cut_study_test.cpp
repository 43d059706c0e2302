// The annual study traced with the openings really cut (annual/annual_cut_study.h) against the
// study from the contribution records: two independent estimates of the same year. A side-lit
// room under the Chicago year (means, direct sun, DA), a roof opening under a uniform-patch sky
// (a closed form), one seed for any thread count, and bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "annual/annual_contributions.h"
#include "annual/annual_cut_study.h"
#include "annual/annual_study.h"
#include "solve/edge_refinement.h"
#include "solve/thick_wall_edges.h"
#include "test_scenes.h"
#include "trace/contributions.h"
#include "trace/replicates.h"

namespace fenestra {
namespace {

using test::ObjBuilder;
using test::TempDir;

using test::kChicago;
// On the 0.5 m element grid of the south wall (y = 0): x 0.5..2.5 m, z 1..2 m.
const Rectangle kWindow = {Vec3(0.5f, 0, 1), Vec3(2.5f, 0, 1), Vec3(2.5f, 0, 2), Vec3(0.5f, 0, 2)};

// A grey 3 x 3 x 2.5 m room whose south wall is the opening domain (`thickness` m thick, given),
// under the Chicago year.
Scene side_lit_room(const TempDir& dir, int paths, int threads = 0, float thickness = 0.0f, int seed = 3,
                    float element_size = 0.5f) {
  ObjBuilder obj;
  obj.box({0, 0, 0}, {3, 3, 2.5f}, [](const std::string& f) { return f == "south" ? "facade" : "grey"; });
  dir.write("room.obj", obj.str());
  std::ostringstream s;
  s << R"({"fenestra": 1, "geometry": "room.obj",
           "materials": {"grey": {"reflectance": 0.6}, "facade": {"reflectance": 0.5}},
           "opening_domain": {"materials": ["facade"], "element_size": )"
    << element_size << R"(, "thickness": )" << thickness << R"(},
           "sensors": {"points": [[1.5, 1.0, 0.8], [0.5, 2.5, 0.8], [2.5, 0.5, 1.2]], "normals": [0, 0, 1]},
           "sky": {"type": "climate", "weather": ")"
    << kChicago << R"(", "resolution": [64, 32]},
           "render": {"paths_per_sensor": )"
    << paths << R"(, "max_bounces": 8, "seed": )" << seed << R"(, "threads": )" << threads << "}}";
  dir.write("scene.json", s.str());
  return load_scene(dir.file("scene.json"));
}

// The standard error of the records' occupied-hours mean without the sun a sensor's own sample
// finds straight away (the year replaces it by the exact sun, which has no spread): replicate
// groups, as Contributions::evaluate.
std::vector<double> records_stderr_without_direct(const Contributions& c, const OpenRegion& region) {
  std::vector<double> out;
  for (const SensorRecord& r : c.records) {
    ReplicateSums sums;
    for (size_t p = 0; p < r.path_count(); ++p) {
      double v = 0.0;
      for_each_counting_event_in_region(r, p, [&](int32_t k, const CellPoint& at) { return region.is_open(k, at); },
                                        [&](uint32_t e) {
                                          if (!(r.event_sources[e] & AnnualSources::kDirect)) v += r.events[e].value();
                                        });
      sums.add(p, v);
    }
    double mean = 0.0, se = 0.0;
    sums.estimate(r.path_count(), &mean, &se);
    out.push_back(se);
  }
  return out;
}

// Where the ray from p toward the sun meets the wall plane y = 0, if it does going south.
bool through_window_interior(const Vec3& p, const Vec3& sun, float margin) {
  if (!(sun.y() < -1e-6f)) return false;
  const Vec3 hit = p + (-p.y() / sun.y()) * sun;
  return hit.x() > 0.5f + margin && hit.x() < 2.5f - margin && hit.z() > 1.0f + margin && hit.z() < 2.0f - margin;
}
bool clear_of_window(const Vec3& p, const Vec3& sun, float margin) {
  if (!(sun.y() < -1e-6f)) return true;
  const Vec3 hit = p + (-p.y() / sun.y()) * sun;
  return hit.x() < 0.5f - margin || hit.x() > 2.5f + margin || hit.z() < 1.0f - margin || hit.z() > 2.0f + margin;
}

TEST(AnnualCutStudy, SideLitRoomAgreesWithTheRecordsStudy) {
  TempDir dir;
  const Scene scene = side_lit_room(dir, 16384);
  const Contributions c = compute_contributions(scene, nullptr, /*transport=*/false);
  const OpenRegion region = region_of_openings(scene, {kWindow});
  const AnnualStudy records = annual_study(scene, c, region);
  const AnnualStudy cut = annual_study_with_cutters(scene, {kWindow}, nullptr, 65536);
  ASSERT_TRUE(cut.cutters);
  ASSERT_EQ(cut.paths_per_sensor, 65536);
  ASSERT_EQ(cut.illuminance.total.rows(), 3);
  ASSERT_EQ(cut.illuminance.total.cols(), records.illuminance.total.cols());
  const std::vector<double> records_se = records_stderr_without_direct(c, region);
  const SkyMatrix& sky = *scene.climate->sky;
  const int occupied = cut.metrics.occupied_hours;
  ASSERT_EQ(occupied, 3650);

  for (Eigen::Index i = 0; i < 3; ++i) {
    const double year = cut.metrics.mean_illuminance_lux[i], truth = records.metrics.mean_illuminance_lux[i];
    const double se = cut.occupied_mean.standard_error[i];
    // The cut study's mean of the occupied hours is its year's, with the paths' spread.
    EXPECT_NEAR(cut.occupied_mean.value[i], year, 1e-4 * year) << "sensor " << i;
    EXPECT_GT(se, 0.0);
    EXPECT_LT(se, 0.05 * year) << "sensor " << i << ": too few paths for a test that can fail";
    // Both estimate the same year (the same patches, clusters and exact suns): no model allowance.
    // (Over 24 seeds the two means agree within 0.4 %, and no seed differs by 4 standard errors.)
    EXPECT_TRUE(test::within_sigma(year, se, truth, records_se[i])) << "sensor " << i;
    std::printf("sensor %ld: annual mean %.1f lux with the openings cut (se %.1f), %.1f from the records (se %.1f), "
                "%+.2f %%\n", static_cast<long>(i), year, se, truth, records_se[i], 100.0 * (year / truth - 1.0));

    // The sun straight to the sensor: the same cos x attenuation wherever its ray passes 1 cm
    // or more inside the window, none wherever it passes 1 cm or more outside.
    const Vec3 p = scene.sensors.points[i];
    int inside = 0, edge = 0;
    for (const int h : c.annual->sun_hours) {
      const Vec3& sun = sky.sun_direction[h];
      if (through_window_interior(p, sun, 0.01f)) {
        ++inside;
        EXPECT_GT(cut.illuminance.direct(i, h), 0.0f) << "sensor " << i << " hour " << h;
        EXPECT_EQ(cut.illuminance.direct(i, h), records.illuminance.direct(i, h)) << "sensor " << i << " hour " << h;
      } else if (clear_of_window(p, sun, 0.01f)) {
        EXPECT_EQ(cut.illuminance.direct(i, h), 0.0f) << "sensor " << i << " hour " << h;
      } else {
        ++edge;
      }
    }
    if (i == 0) EXPECT_GT(inside, 500) << "the sensor 1 m behind the window sees the sun often";

    // DA300: an hour changes sides only where the two estimates straddle 300 lux. The studies'
    // hourly values differ by their coefficients' errors, about the mean's relative standard
    // error r on each hour: hours within 4 r of 300 lux in the records' year may flip, and hours
    // whose sun ray grazes the window's edge (the direct sun differs there).
    const double r = std::hypot(se, records_se[i]) / truth;
    int near = 0;
    for (int h = 0; h < static_cast<int>(cut.hours.size()); ++h) {
      if (!cut.occupied[h]) continue;
      const double e = records.illuminance.total(i, h);
      near += std::abs(e - 300.0) <= 4.0 * r * e || (sky.sun_normal_illuminance[h] > 0.0f &&
                                                      !through_window_interior(p, sky.sun_direction[h], 0.01f) &&
                                                      !clear_of_window(p, sky.sun_direction[h], 0.01f));
    }
    const double tolerance = static_cast<double>(near) / occupied;
    EXPECT_NEAR(cut.metrics.daylight_autonomy[i], records.metrics.daylight_autonomy[i], tolerance) << "sensor " << i;
    std::printf("sensor %ld: DA300 %.4f cut, %.4f records (tolerance %.4f); %d sun hours inside the window, %d at "
                "its edge\n", static_cast<long>(i), cut.metrics.daylight_autonomy[i],
                records.metrics.daylight_autonomy[i], tolerance, inside, edge);
  }
}

// In thick walls the records' year and the year traced with the openings really cut are two
// estimates of the same year: per sensor the annual mean and DA300 agree within 3 combined
// standard errors, sDA and ASE within 2 points.
struct ThickYear {
  float thickness;
  int seed;
};

class ThickWallYear : public ::testing::TestWithParam<ThickYear> {};

TEST_P(ThickWallYear, RecordsAgreeWithTheOpeningsCut) {
  const ThickYear w = GetParam();
  TempDir dir;
  const Scene scene = side_lit_room(dir, 4096, 0, w.thickness, w.seed, 0.25f);
  ASSERT_NEAR(scene.domain.panels()[0].thickness, w.thickness, 1e-6);
  const PanelRectangle window = to_panel_rectangle(scene.domain, kWindow);
  const Contributions c = compute_contributions(scene, nullptr, /*transport=*/false);
  const OpenRegion region(scene.domain, {window});
  const AnnualStudy records = annual_study(scene, c, region);
  const AnnualStudy cut = annual_study_with_cutters(scene, {OpeningInput(window)}, nullptr, 16384);
  const std::vector<double> records_se = records_stderr_without_direct(c, region);
  const int occupied = cut.metrics.occupied_hours;
  for (Eigen::Index i = 0; i < 3; ++i) {
    const double year = cut.metrics.mean_illuminance_lux[i], truth = records.metrics.mean_illuminance_lux[i];
    const double se = cut.occupied_mean.standard_error[i];
    EXPECT_TRUE(test::within_sigma(truth, records_se[i], year, se, 3.0)) << "sensor " << i;
    // DA300 within 3 sigma: the hours whose value lies within 3 combined relative standard errors
    // r of 300 lux may change sides (the coefficients' errors move every hour by about r), and
    // one hour more.
    const double r = std::hypot(se, records_se[i]) / truth;
    int near = 0;
    for (int h = 0; h < static_cast<int>(cut.hours.size()); ++h) {
      if (!cut.occupied[h]) continue;
      const double e = records.illuminance.total(i, h);
      near += std::abs(e - 300.0) <= 3.0 * r * e;
    }
    const double da_tolerance = (near + 1.0) / occupied;
    EXPECT_NEAR(records.metrics.daylight_autonomy[i], cut.metrics.daylight_autonomy[i], da_tolerance) << "sensor " << i;
    std::printf("[ year     ] %.2f m wall, seed %d, sensor %ld: mean %.1f records (se %.1f), %.1f cut (se %.1f), "
                "%+.2f %%; DA300 %.4f records, %.4f cut (tolerance %.4f)\n",
                w.thickness, w.seed, static_cast<long>(i), truth, records_se[i], year, se,
                100.0 * (truth / year - 1.0), records.metrics.daylight_autonomy[i], cut.metrics.daylight_autonomy[i],
                da_tolerance);
  }
  EXPECT_NEAR(records.metrics.spatial_daylight_autonomy, cut.metrics.spatial_daylight_autonomy, 0.02);
  EXPECT_NEAR(records.metrics.annual_sunlight_exposure, cut.metrics.annual_sunlight_exposure, 0.02);
}

INSTANTIATE_TEST_SUITE_P(Walls, ThickWallYear,
                         ::testing::Values(ThickYear{0.2f, 3}, ThickYear{0.3f, 3}, ThickYear{0.5f, 3},
                                           ThickYear{0.3f, 4}));

// A 2 x 2 x 2 m black box whose roof is the opening domain, two sensors on the floor.
Scene roof_box(const TempDir& dir, int paths) {
  ObjBuilder obj;
  obj.box({0, 0, 0}, {2, 2, 2}, [](const std::string& f) { return f == "ceiling" ? "roof" : "black"; });
  dir.write("scene.obj", obj.str());
  std::ostringstream s;
  s << R"({"fenestra": 1, "geometry": "scene.obj", "materials": {"roof": {"reflectance": 0}, "black": {"reflectance": 0}},
       "opening_domain": {"materials": ["roof"], "element_size": 0.25},
       "sensors": {"points": [[1, 1, 0.01], [0.7, 1.3, 0.01]], "normals": [0, 0, 1]},
       "sky": {"type": "uniform", "radiance": 1}, "render": {"paths_per_sensor": )"
    << paths << R"(, "max_bounces": 8, "seed": 3}})";
  dir.write("scene.json", s.str());
  return load_scene(dir.file("scene.json"));
}

TEST(AnnualCutStudy, RoofOpeningUnderUniformPatchSkyIsViewFactorTimesLuminance) {
  TempDir dir;
  Scene scene = roof_box(dir, 1 << 14);
  constexpr float kLuminance = 3000.0f, kSun = 60000.0f;  // cd/m^2, lux
  // Three occupied noon hours: dark, a uniform sky of every patch at kLuminance, the sun alone.
  auto sky = std::make_shared<SkyMatrix>();
  sky->patches = SkyPatches(1);
  for (int h = 0; h < 3; ++h) sky->hours.push_back({1, 1 + h, 12.5});
  sky->radiance.setZero(sky->patches.count(), 3);
  sky->radiance.block(1, 1, sky->patches.sky_count(), 1).setConstant(kLuminance);
  const Vec3 sun = Vec3(0.1f, 0.05f, 1.0f).normalized();
  sky->sun_direction = {Vec3(0, 0, -1), Vec3(0, 0, -1), sun};
  sky->sun_normal_illuminance = {0.0f, 0.0f, kSun};
  sky->diffuse_horizontal_lux.assign(3, 0.0);
  sky->global_horizontal_lux.assign(3, 0.0);
  auto climate = std::make_shared<Climate>();
  climate->sky = sky;
  scene.climate = climate;
  const Rectangle hole = {Vec3(0.5f, 0.5f, 2), Vec3(1.5f, 0.5f, 2), Vec3(1.5f, 1.5f, 2), Vec3(0.5f, 1.5f, 2)};
  const AnnualStudy year = annual_study_with_cutters(scene, {hole});
  for (int i = 0; i < 2; ++i) {
    const Vec3 p = scene.sensors.points[i] + Vec3(0, 0, test::kSensorLift);
    const double expected = M_PI * kLuminance * test::polygon_view_factor(p, {0, 0, 1}, {hole.begin(), hole.end()});
    // The paths' design value is the sky hour's third (three occupied hours, nothing reflects).
    const double se = 3.0 * year.occupied_mean.standard_error[i];
    EXPECT_TRUE(test::within_sigma(year.illuminance.total(i, 1), se, expected, 0.0)) << "sensor " << i;
    EXPECT_EQ(year.illuminance.total(i, 0), 0.0f);
    EXPECT_NEAR(year.illuminance.direct(i, 2), kSun * sun.z(), 1e-4 * kSun) << "the sun passes the hole";
    EXPECT_EQ(year.illuminance.total(i, 2), year.illuminance.direct(i, 2)) << "a black box: nothing reflects";
    EXPECT_NEAR(year.occupied_mean.value[i], year.illuminance.total.row(i).mean(), 1e-4 * year.occupied_mean.value[i]);
  }
  // A hole the sun's ray misses: no direct sun.
  const Rectangle aside = {Vec3(0.0f, 0.0f, 2), Vec3(0.5f, 0.0f, 2), Vec3(0.5f, 0.5f, 2), Vec3(0.0f, 0.5f, 2)};
  const AnnualStudy shaded = annual_study_with_cutters(scene, {aside}, nullptr, 256);
  EXPECT_EQ(shaded.illuminance.direct.maxCoeff(), 0.0f);
}

TEST(AnnualCutStudy, SameYearForAnySeededThreadCount) {
  TempDir one_dir, two_dir;
  const AnnualStudy one = annual_study_with_cutters(side_lit_room(one_dir, 300, 1), {kWindow});
  const AnnualStudy two = annual_study_with_cutters(side_lit_room(two_dir, 300, 2), {kWindow});
  EXPECT_TRUE(one.illuminance.total == two.illuminance.total);
  EXPECT_TRUE(one.occupied_mean.standard_error == two.occupied_mean.standard_error);
}

TEST(AnnualCutStudy, RefusesOtherSkiesAndOpeningsOffTheirPanel) {
  TempDir dir;
  Scene scene = side_lit_room(dir, 64);
  const Rectangle off = {Vec3(0.5f, 5, 1), Vec3(2.5f, 5, 1), Vec3(2.5f, 5, 2), Vec3(0.5f, 5, 2)};
  try {
    annual_study_with_cutters(scene, {kWindow, off});
    FAIL() << "an opening off its panel was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("opening 1"), std::string::npos) << e.what();
  }
  scene.climate.reset();
  try {
    annual_study_with_cutters(scene, {kWindow});
    FAIL() << "a scene without a climate sky was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("climate"), std::string::npos) << e.what();
  }
}

TEST(AnnualCutStudy, StopsWhenCancelled) {
  TempDir dir;
  const Scene scene = side_lit_room(dir, 256);
  Progress progress;
  progress.cancel();
  EXPECT_THROW(annual_study_with_cutters(scene, {kWindow}, &progress), Cancelled);
}

}  // namespace
}  // namespace fenestra
