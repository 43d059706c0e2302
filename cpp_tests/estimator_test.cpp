// The contribution estimator under both samplers (render.sampler): each unbiased against real
// cuts and against the other, the stratified one with less variance of E, and the reference room
// with its sky in closed form against Radiance's table.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "annual/annual_contributions.h"
#include "scene/scene.h"
#include "test_scenes.h"
#include "trace/contributions.h"
#include "trace/evaluate.h"

namespace fenestra {
namespace {

using test::ObjBuilder;
using test::TempDir;
using test::within_sigma;

// A room with its south wall and ceiling in the domain (two panels), a ground and a facing
// building outside, sensors near the wall and deep in the room.
// `black`: every surface black, so that E is the sky seen straight through each element.
Scene two_panel_room(const TempDir& dir, RenderSettings::Sampler sampler, int paths, bool skylights = true,
                     bool black = false) {
  ObjBuilder obj;
  obj.box({0, 0, 0}, {4, 3, 2.5f}, [&](const std::string& f) {
    return f == "south" || (skylights && f == "ceiling") ? "domain" : f == "floor" ? "floor" : "grey";
  });
  obj.quad("ground", "ground", {-30, -30, -0.01f}, {30, -30, -0.01f}, {30, 30, -0.01f}, {-30, 30, -0.01f});
  obj.quad("neighbour", "neighbour", {-5, -5, 0}, {-5, -5, 6}, {9, -5, 6}, {9, -5, 0});
  dir.write("scene.obj", obj.str());
  auto rho = [&](const char* value) { return std::string(black ? "0" : value); };
  dir.write("scene.json", R"({"fenestra": 1, "geometry": "scene.obj",
    "materials": {"grey": {"reflectance": )" + rho("0.7") + R"(}, "floor": {"reflectance": )" + rho("0.3") +
                              R"(}, "domain": {"reflectance": )" + rho("0.6") + R"(},
                  "ground": {"reflectance": )" + rho("0.2") + R"(}, "neighbour": {"reflectance": )" + rho("0.4") +
                              R"(}},
    "opening_domain": {"materials": ["domain"], "element_size": 0.5},
    "sensors": {"points": [[1, 0.4, 0.8], [3, 2.5, 0.8], [2, 1.5, 1.2]], "normals": [0, 0, 1]},
    "sky": {"type": "uniform", "radiance": 318.31},
    "render": {"paths_per_sensor": )" + std::to_string(paths) + R"(, "max_bounces": 8, "seed": 7}})");
  Scene scene = load_scene(dir.file("scene.json"));
  scene.render.sampler = sampler;
  return scene;
}

class Sampler : public ::testing::TestWithParam<RenderSettings::Sampler> {};

TEST_P(Sampler, RecordsEqualRealCutsForWindowsInTwoPanels) {
  TempDir dir;
  const Scene scene = two_panel_room(dir, GetParam(), 1 << 13);
  const Contributions c = compute_contributions(scene);
  const std::vector<Rectangle> openings = {
      {Vec3(0.5f, 0, 1), Vec3(2, 0, 1), Vec3(2, 0, 2), Vec3(0.5f, 0, 2)},
      {Vec3(2.5f, 1, 2.5f), Vec3(3.5f, 1, 2.5f), Vec3(3.5f, 2, 2.5f), Vec3(2.5f, 2, 2.5f)}};
  std::vector<uint8_t> mask(scene.domain.element_count(), 0);
  for (const auto& r : openings) {
    const auto m = test::mask_of_elements_inside(scene, r);
    for (size_t k = 0; k < m.size(); ++k) mask[k] |= m[k];
  }
  const SensorValues exact = c.evaluate(mask);
  const SensorValues truth = evaluate_openings(scene, {openings.begin(), openings.end()});
  for (size_t i = 0; i < scene.sensors.size(); ++i)
    EXPECT_TRUE(within_sigma(exact.value[i], exact.standard_error[i], truth.value[i], truth.standard_error[i]))
        << sampler_name(GetParam()) << ", sensor " << i;
}

INSTANTIATE_TEST_SUITE_P(Estimator, Sampler,
                         ::testing::Values(RenderSettings::Sampler::kSobol, RenderSettings::Sampler::kIndependent),
                         [](const auto& info) { return std::string(sampler_name(info.param)); });

TEST(Estimator, BothSamplersAgreeOnEveryEntryOfE) {
  // Two unbiased estimators of the same matrix: their entries differ by noise alone (a t bound per
  // entry, Bonferroni over the large entries at a family-wise 10^-3).
  TempDir dir;
  const Contributions a = compute_contributions(two_panel_room(dir, RenderSettings::Sampler::kSobol, 1 << 13));
  const Contributions b = compute_contributions(two_panel_room(dir, RenderSettings::Sampler::kIndependent, 1 << 13));
  const double largest = a.E.maxCoeff();
  int compared = 0;
  for (Eigen::Index i = 0; i < a.E.rows(); ++i)
    for (Eigen::Index k = 0; k < a.E.cols(); ++k) compared += a.E(i, k) > 0.01 * largest;
  // The normal sigma level whose two-sided tail is 10^-3 / compared.
  double level = 3.0;
  while (std::erfc(level / std::sqrt(2.0)) > 1e-3 / compared) level += 0.01;
  for (Eigen::Index i = 0; i < a.E.rows(); ++i)
    for (Eigen::Index k = 0; k < a.E.cols(); ++k)
      if (a.E(i, k) > 0.01 * largest)
        EXPECT_TRUE(within_sigma(a.E(i, k), a.E_stderr(i, k), b.E(i, k), b.E_stderr(i, k), level))
            << "sensor " << i << ", element " << k;
  for (Eigen::Index i = 0; i < a.E.rows(); ++i)
    EXPECT_TRUE(within_sigma(a.all_open.value[i], a.all_open.standard_error[i], b.all_open.value[i],
                             b.all_open.standard_error[i]))
        << "all open, sensor " << i;
}

// A black room with a 6 x 3 m south wall of 200 elements, sensors 0.3 m and 3 m from it at desk
// height, an open sky: E is the sky seen straight through each element, which the sensors'
// portal samples alone carry. Most elements are far from a sensor, or below its plane.
Scene black_side_lit_room(const TempDir& dir, RenderSettings::Sampler sampler) {
  ObjBuilder obj;
  obj.box({0, 0, 0}, {6, 6, 3}, [](const std::string& f) { return f == "south" ? "domain" : "black"; });
  dir.write("scene.obj", obj.str());
  dir.write("scene.json", R"({"fenestra": 1, "geometry": "scene.obj",
    "materials": {"black": {"reflectance": 0}, "domain": {"reflectance": 0}},
    "opening_domain": {"materials": ["domain"], "element_size": 0.3},
    "sensors": {"points": [[3, 0.3, 0.8], [1, 0.3, 0.8], [3, 3, 0.8]], "normals": [0, 0, 1]},
    "sky": {"type": "uniform", "radiance": 318.31},
    "render": {"paths_per_sensor": 2048, "max_bounces": 8, "seed": 5}})");
  Scene scene = load_scene(dir.file("scene.json"));
  scene.render.sampler = sampler;
  return scene;
}

TEST(Estimator, SensorPortalSamplesFollowTheView) {
  // Aimed by the view, uniform in each element's solid angle and stratified, two portal samples
  // per path leave at most a third of the variance of E that four even, by-area ones leave.
  TempDir dir;
  const Contributions a = compute_contributions(black_side_lit_room(dir, RenderSettings::Sampler::kSobol));
  const Contributions b = compute_contributions(black_side_lit_room(dir, RenderSettings::Sampler::kIndependent));
  const double variance_a = a.E_stderr.array().square().sum(), variance_b = b.E_stderr.array().square().sum();
  EXPECT_GT(a.E.sum(), 0.0);
  EXPECT_LT(3.0 * variance_a, variance_b) << "stratified " << variance_a << ", independent " << variance_b;
  std::printf("[ estimator] black side-lit room: variance of E %.3g stratified, %.3g independent (%.1fx)\n", variance_a,
              variance_b, variance_b / variance_a);
  // Both estimate the same sky view: every sensor's all-open value agrees.
  for (Eigen::Index i = 0; i < a.E.rows(); ++i)
    EXPECT_TRUE(within_sigma(a.all_open.value[i], a.all_open.standard_error[i], b.all_open.value[i],
                             b.all_open.standard_error[i]))
        << "sensor " << i;
}

TEST(Estimator, ReferenceRoomWithItsSkyInClosedFormMatchesRadiance) {
  // The reference room's sky as a uniform sky over a uniform ground (no image): the same table.
  Scene scene = load_scene(std::string(FENESTRA_EXAMPLES) + "/reference_room/scene_uniform.json");
  scene.render.paths_per_sensor = 1 << 15;
  const Rectangle window = {Vec3(1, 0, 0.9f), Vec3(3, 0, 0.9f), Vec3(3, 0, 2.1f), Vec3(1, 0, 2.1f)};
  const SensorValues v = evaluate_openings(scene, {window});
  const double* table = test::kReferenceRoomTable;
  for (int i = 0; i < 16; ++i)
    EXPECT_TRUE(within_sigma(v.value[i], v.standard_error[i], table[i], 0.003 * table[i])) << "sensor " << i;
}

}  // namespace
}  // namespace fenestra
