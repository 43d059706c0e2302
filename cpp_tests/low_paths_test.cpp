// Contributions are unbiased at any path count: with far fewer paths than elements, the mean over
// independent seeds matches the closed form, and the reported standard errors describe the spread.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "annual/annual_contributions.h"
#include "test_scenes.h"
#include "trace/contributions.h"
#include "trace/evaluate.h"

namespace fenestra {
namespace {

using test::ObjBuilder;
using test::TempDir;

constexpr double kRadiance = 1000.0 / M_PI;  // cd/m^2

// Black 3 x 3 x 2.5 m room whose south wall (y = 0) is the opening domain. Sensor 0 faces the wall
// from 1 m away; sensor 1 looks up from a desk, so it sees the wall above its own height only.
Scene black_room(const TempDir& dir, double element_size, int paths, int seed) {
  ObjBuilder obj;
  obj.box({0, 0, 0}, {3, 3, 2.5f}, [](const std::string& f) { return f == "south" ? "facade" : "black"; });
  dir.write("scene.obj", obj.str());
  std::ostringstream s;
  s << R"({"fenestra": 1, "geometry": "scene.obj",
           "materials": {"black": {"reflectance": 0}, "facade": {"reflectance": 0}},
           "opening_domain": {"materials": ["facade"], "element_size": )"
    << element_size << R"(},
           "sensors": {"points": [[1.5, 1.0, 1.25], [1.0, 1.5, 0.8]], "normals": [[0, -1, 0], [0, 0, 1]]},
           "sky": {"type": "uniform", "radiance": )"
    << kRadiance << R"(},
           "render": {"paths_per_sensor": )"
    << paths << R"(, "max_bounces": 4, "seed": )" << seed << "}}";
  dir.write("scene.json", s.str());
  return load_scene(dir.file("scene.json"));
}

// The sensors of black_room, as its scene file places them.
struct SensorPlacement {
  Vec3 point, normal;
};
const SensorPlacement kSensors[2] = {{Vec3(1.5f, 1.0f, 1.25f), Vec3(0, -1, 0)}, {Vec3(1.0f, 1.5f, 0.8f), Vec3(0, 0, 1)}};

// pi L times the view factor from sensor i of the wall rectangle x in [x0, x1], z in [z0, z1]
// (y = 0), cut at an upward sensor's horizon: the light through that opening.
double closed_form(size_t i, float x0, float x1, float z0, float z1) {
  const Vec3 p = kSensors[i].point + test::kSensorLift * kSensors[i].normal;
  if (kSensors[i].normal.z() > 0.0f) z0 = std::max(z0, p.z());
  return M_PI * kRadiance *
         test::polygon_view_factor(p, kSensors[i].normal, {Vec3(x0, 0, z0), Vec3(x1, 0, z0), Vec3(x1, 0, z1), Vec3(x0, 0, z1)});
}

double expected_all_open(size_t sensor) { return closed_form(sensor, 0, 3, 0, 2.5f); }

struct SeedStatistics {
  double mean = 0.0;            // of the per-seed estimates
  double sample_variance = 0.0;  // spread of the per-seed estimates
  double reported_variance = 0.0;  // mean of the reported squared standard errors
  int seeds = 0;
  double standard_error_of_mean() const { return std::sqrt(reported_variance / seeds); }
};

// Runs `seeds` independent contribution passes; `value(c, sensor, &v, &se)` picks the statistic.
template <typename Statistic>
std::vector<SeedStatistics> over_seeds(double element_size, int paths, int seeds, Statistic value) {
  std::vector<SeedStatistics> out(2);
  std::vector<std::vector<double>> samples(2);
  TempDir dir;
  for (int seed = 1; seed <= seeds; ++seed) {
    const Scene scene = black_room(dir, element_size, paths, seed);
    const Contributions c = compute_contributions(scene);
    for (size_t i = 0; i < 2; ++i) {
      double v = 0.0, se = 0.0;
      value(scene, c, i, &v, &se);
      samples[i].push_back(v);
      out[i].reported_variance += se * se / seeds;
    }
  }
  for (size_t i = 0; i < 2; ++i) {
    SeedStatistics& s = out[i];
    s.seeds = seeds;
    for (double v : samples[i]) s.mean += v / seeds;
    for (double v : samples[i]) s.sample_variance += (v - s.mean) * (v - s.mean) / (seeds - 1);
  }
  return out;
}

void all_open_of(const Scene&, const Contributions& c, size_t i, double* v, double* se) {
  *v = c.all_open.value[i];
  *se = c.all_open.standard_error[i];
}

// The 1 x 1 m block of elements x in [1, 2], z in [1, 2], from the exact path records.
void window_of(const Scene& scene, const Contributions& c, size_t i, double* v, double* se) {
  const Rectangle window = {Vec3(1, 0, 1), Vec3(2, 0, 1), Vec3(2, 0, 2), Vec3(1, 0, 2)};
  const SensorValues values = c.evaluate(test::mask_of_elements_inside(scene, window));
  *v = values.value[i];
  *se = values.standard_error[i];
}

double expected_window(size_t sensor) { return closed_form(sensor, 1, 2, 1, 2); }

// The mean over seeds is within 3 standard errors of the closed form, and the spread of the
// per-seed estimates matches the reported standard errors (the ratio of variances of 40 seeds
// has a relative spread of about 0.25: [0.4, 2.5] fails only for a real mismatch).
void expect_unbiased_and_covered(const std::vector<SeedStatistics>& stats, double (*expected)(size_t),
                                 const std::string& what) {
  for (size_t i = 0; i < stats.size(); ++i) {
    const SeedStatistics& s = stats[i];
    const double truth = expected(i);
    EXPECT_NEAR(s.mean, truth, 3.0 * s.standard_error_of_mean())
        << what << ", sensor " << i << ": mean over " << s.seeds << " seeds vs closed form";
    const double ratio = s.sample_variance / s.reported_variance;
    EXPECT_GT(ratio, 0.4) << what << ", sensor " << i << ": reported errors overstate the spread";
    EXPECT_LT(ratio, 2.5) << what << ", sensor " << i << ": reported errors understate the spread";
  }
}

TEST(LowPaths, AllOpenIsUnbiasedWithFarFewerPathsThanElements) {
  // 0.1 m elements: 750 on the wall; 32 paths per sensor send 128 portal samples in all, 8 per
  // replicate group, so each group visits about 1 % of the elements.
  const auto stats = over_seeds(0.1, 32, 40, all_open_of);
  expect_unbiased_and_covered(stats, expected_all_open, "all open, 750 elements, 32 paths");
}

TEST(LowPaths, ExactEvaluationOfAWindowIsUnbiasedWithFewPaths) {
  const auto stats = over_seeds(0.1, 64, 40, window_of);
  expect_unbiased_and_covered(stats, expected_window, "1 x 1 m window, 750 elements, 64 paths");
}

TEST(LowPaths, RowOfEEqualsAllOpenInABlackRoom) {
  // Without interreflection each element's light is its own: E's rows sum to the all-open value.
  TempDir dir;
  const Scene scene = black_room(dir, 0.1, 48, 7);
  const Contributions c = compute_contributions(scene);
  for (size_t i = 0; i < 2; ++i)
    EXPECT_NEAR(c.E.row(i).sum(), c.all_open.value[i], 1e-4 * expected_all_open(i)) << "sensor " << i;
}

TEST(LowPaths, UnbiasedWhereSomeGroupsCoverEveryElementAndOthersDoNot) {
  // 0.25 m elements: 120. 472 paths = 16 x 29 + 8: groups of 30 paths send 120 samples (every
  // element visited), groups of 29 send 116 (some elements left out).
  const auto stats = over_seeds(0.25, 472, 40, all_open_of);
  expect_unbiased_and_covered(stats, expected_all_open, "all open, 120 elements, 472 paths");
}

TEST(LowPaths, OnePathGivesAnUnknownStandardError) {
  TempDir dir;
  const Scene scene = black_room(dir, 0.25, 1, 3);
  const Contributions c = compute_contributions(scene);
  for (size_t i = 0; i < 2; ++i) {
    EXPECT_TRUE(std::isfinite(c.all_open.value[i]));
    EXPECT_TRUE(std::isinf(c.all_open.standard_error[i])) << "one path cannot tell its own spread";
  }
}

}  // namespace
}  // namespace fenestra
