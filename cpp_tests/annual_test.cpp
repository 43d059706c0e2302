// Annual daylight coefficients against closed forms and against the single-sky pass on the same
// paths: a roof opening under a uniform-patch sky, the sun straight through it, the mean of the
// occupied hours, and the sun's light after a reflection against a path-traced reference.
#include <gtest/gtest.h>

#include <cmath>

#include "annual/annual_contributions.h"
#include "annual/annual_illuminance.h"
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

using Rectangle = std::array<Vec3, 4>;
const Rectangle kHole = {Vec3(0.5f, 0.5f, 2), Vec3(1.5f, 0.5f, 2), Vec3(1.5f, 1.5f, 2), Vec3(0.5f, 1.5f, 2)};

// A 2 x 2 x 2 m box whose roof is the opening domain, two sensors on the floor; `floor` its floor's
// reflectance (every other surface black).
Scene roof_box(const TempDir& dir, int paths, double floor_reflectance, double wall_reflectance = 0.0) {
  ObjBuilder obj;
  obj.box({0, 0, 0}, {2, 2, 2}, [](const std::string& f) {
    return f == "ceiling" ? "roof" : f == "floor" ? "floor" : "wall";
  });
  dir.write("scene.obj", obj.str());
  std::ostringstream s;
  s << R"({"fenestra": 1, "geometry": "scene.obj", "materials": {"roof": {"reflectance": 0}, "floor": {"reflectance": )"
    << floor_reflectance << R"(}, "wall": {"reflectance": )" << wall_reflectance
    << R"(}}, "opening_domain": {"materials": ["roof"], "element_size": 0.25},
       "sensors": {"points": [[1, 1, 0.01], [0.7, 1.3, 0.01]], "normals": [0, 0, 1]},
       "sky": {"type": "uniform", "radiance": 1}, "render": {"paths_per_sensor": )"
    << paths << R"(, "max_bounces": 8, "seed": 3}})";
  dir.write("scene.json", s.str());
  return load_scene(dir.file("scene.json"));
}

// A year of `hours` noon hours (all occupied), all dark; tests light some of them.
std::shared_ptr<SkyMatrix> dark_year(int hours) {
  auto sky = std::make_shared<SkyMatrix>();
  sky->patches = SkyPatches(1);
  for (int h = 0; h < hours; ++h) sky->hours.push_back({1, 1 + h, 12.5});
  sky->radiance.setZero(sky->patches.count(), hours);
  sky->sun_direction.assign(hours, Vec3(0, 0, -1));
  sky->sun_normal_illuminance.assign(hours, 0.0f);
  sky->diffuse_horizontal_lux.assign(hours, 0.0);
  sky->global_horizontal_lux.assign(hours, 0.0);
  return sky;
}

void attach(Scene* scene, std::shared_ptr<SkyMatrix> sky) {
  auto climate = std::make_shared<Climate>();
  climate->sky = std::move(sky);
  scene->climate = climate;
}

AnnualIlluminance annual_of(const Contributions& c, const std::vector<uint8_t>& mask) {
  const AnnualCoefficients k =
      annual_coefficients(c.records, *c.annual, [&](int32_t e, const CellPoint&) { return mask[e] != 0; });
  return annual_illuminance(k, *c.annual);
}

TEST(Annual, RoofOpeningUnderUniformPatchSkyIsViewFactorTimesLuminanceAndSunIsExact) {
  TempDir dir;
  Scene scene = roof_box(dir, 1 << 14, 0.0);
  constexpr float kLuminance = 3000.0f, kSun = 60000.0f;  // cd/m^2, lux
  auto sky = dark_year(3);
  sky->radiance.block(1, 1, sky->patches.sky_count(), 1).setConstant(kLuminance);  // hour 1: uniform sky
  const Vec3 sun = Vec3(0.1f, 0.05f, 1.0f).normalized();                          // hour 2: the sun alone
  sky->sun_direction[2] = sun;
  sky->sun_normal_illuminance[2] = kSun;
  attach(&scene, sky);
  const Contributions c = compute_contributions(scene);
  ASSERT_TRUE(c.annual);
  ASSERT_EQ(c.annual->sources.suns.size(), 1u);
  const auto mask = mask_of_elements_inside(scene, kHole);
  const AnnualIlluminance year = annual_of(c, mask);
  const SensorValues design = c.evaluate(mask);  // the mean of the three occupied hours
  ASSERT_EQ(year.total.cols(), 3);
  for (int i = 0; i < 2; ++i) {
    const Vec3 p = scene.sensors.points[i] + Vec3(0, 0, test::kSensorLift);
    const double expected = M_PI * kLuminance * test::polygon_view_factor(p, {0, 0, 1}, {kHole.begin(), kHole.end()});
    // The sky hour carries all of the design value's spread but for the exact sun.
    EXPECT_TRUE(within_sigma(year.total(i, 1), 3.0 * design.standard_error[i], expected, 0.0)) << "sensor " << i;
    EXPECT_EQ(year.total(i, 0), 0.0f);
    EXPECT_NEAR(year.direct(i, 2), kSun * sun.z(), 1e-4 * kSun) << "the sun passes the hole, cos " << sun.z();
    EXPECT_EQ(year.total(i, 2), year.direct(i, 2)) << "a black box: nothing reflects";
    EXPECT_EQ(year.direct(i, 1), 0.0f);
    // The design value is the mean of the occupied hours (the cluster holds that one sun exactly;
    // it is traced as a disk, the exact sun as a point: both miss the hole's edges here).
    EXPECT_NEAR(design.value[i], year.total.row(i).mean(), 1e-4 * design.value[i]) << "sensor " << i;
  }
  const AnnualIlluminance closed = annual_of(c, std::vector<uint8_t>(mask.size(), 0));
  EXPECT_EQ(closed.total.maxCoeff(), 0.0f);
}

TEST(Annual, SkyHourEqualsTheUniformSkyPassOnTheSamePaths) {
  // With no sun the annual pass traces exactly the paths of a unit uniform sky: an hour whose every
  // patch (ground included) has luminance L gives L times those values, to float rounding.
  TempDir dir;
  Scene uniform = roof_box(dir, 4096, 0.5, 0.5);
  Scene climate = uniform;
  auto sky = dark_year(2);
  constexpr float kLuminance = 2500.0f;
  sky->radiance.col(1).setConstant(kLuminance);
  attach(&climate, sky);
  const Contributions a = compute_contributions(climate);
  const Contributions u = compute_contributions(uniform);
  const auto mask = mask_of_elements_inside(uniform, kHole);
  const AnnualIlluminance year = annual_of(a, mask);
  const SensorValues v = u.evaluate(mask);
  for (int i = 0; i < 2; ++i) {
    EXPECT_GT(v.value[i], 0.0);
    EXPECT_NEAR(year.total(i, 1), kLuminance * v.value[i], 1e-5 * kLuminance * v.value[i]) << "sensor " << i;
  }
}

TEST(Annual, SunAfterReflectionMatchesPathTracedSun) {
  // A grey floor: the sun through the roof lights it and the floor lights the sensors' cosine-
  // weighted ... a sensor facing down sees only the floor, so the sun reaches it only after a
  // reflection (the cluster's coefficients), which a ground-truth trace with the same sun checks.
  TempDir dir;
  Scene scene = roof_box(dir, 1 << 13, 0.6, 0.3);
  scene.sensors.normals.assign(scene.sensors.size(), Vec3(0, 0, -1));
  for (auto& p : scene.sensors.points) p.z() = 1.0f;
  constexpr float kSun = 50000.0f;
  auto sky = dark_year(1);
  const Vec3 sun = Vec3(0.3f, -0.2f, 1.0f).normalized();
  sky->sun_direction[0] = sun;
  sky->sun_normal_illuminance[0] = kSun;
  Scene with_climate = scene;
  attach(&with_climate, sky);
  const Contributions c = compute_contributions(with_climate);
  const auto mask = mask_of_elements_inside(scene, kHole);
  const AnnualIlluminance year = annual_of(c, mask);
  const SensorValues design = c.evaluate(mask);  // one hour: its value and spread

  Scene truth = scene;
  truth.sky = std::make_shared<UniformSky>(Rgb::Zero());
  SunLight light;
  light.direction = sun;
  light.normal_illuminance = Rgb::Constant(kSun);
  truth.suns = SunLights({light});
  truth.render.paths_per_sensor = 1 << 14;
  const SensorValues v = evaluate_openings(truth, {kHole});
  for (int i = 0; i < 2; ++i) {
    EXPECT_EQ(year.direct(i, 0), 0.0f) << "facing down, no direct sun";
    EXPECT_GT(v.value[i], 0.0);
    EXPECT_TRUE(within_sigma(year.total(i, 0), design.standard_error[i], v.value[i], v.standard_error[i]))
        << "sensor " << i;
  }
}

TEST(Annual, SunClustersGroupHoursWithinTheirPatch) {
  auto sky = dark_year(4);
  const Vec3 a = Vec3(0.3f, 0.2f, 1.0f).normalized(), b = Vec3(0.301f, 0.2f, 1.0f).normalized();
  sky->sun_direction = {a, b, Vec3(-0.8f, 0.1f, 0.3f).normalized(), Vec3(0, 0, -1)};
  sky->sun_normal_illuminance = {1000.0f, 3000.0f, 500.0f, 0.0f};
  const SunClusters s = cluster_suns(*sky, 6);
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s.cluster_of_hour[0], s.cluster_of_hour[1]);
  EXPECT_NE(s.cluster_of_hour[0], s.cluster_of_hour[2]);
  EXPECT_EQ(s.cluster_of_hour[3], -1);
  EXPECT_DOUBLE_EQ(s.energy_lux_h[s.cluster_of_hour[0]], 4000.0);
  const double angle = std::acos(std::clamp<double>(a.dot(b), -1.0, 1.0)) * 180.0 / M_PI;
  EXPECT_LE(s.max_error_deg, angle + 1e-4);
  EXPECT_GT(s.max_error_deg, 0.5 * angle);  // the weighted mean lies between the two, nearer b
}

}  // namespace
}  // namespace fenestra
