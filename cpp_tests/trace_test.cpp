// Light transport against closed-form answers and against itself (exact records vs ground truth).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "annual/annual_contributions.h"
#include "scene/bsdf.h"
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

constexpr double kRadiance = 1000.0 / M_PI;  // cd/m^2: an unobstructed horizontal sensor reads 1000 lux

std::string scene_json(const std::string& materials, const std::string& domain, const std::string& sensors,
                       int paths, int seed = 1, int threads = 0, const std::string& sky = "") {
  std::ostringstream s;
  s << R"({"fenestra": 1, "geometry": "scene.obj", "materials": )" << materials << R"(, "opening_domain": )" << domain
    << R"(, "sensors": )" << sensors << R"(, "sky": )"
    << (sky.empty() ? std::string(R"({"type": "uniform", "radiance": )") + std::to_string(kRadiance) + "}" : sky)
    << R"(, "render": {"paths_per_sensor": )" << paths << R"(, "max_bounces": 8, "seed": )" << seed
    << R"(, "threads": )" << threads << "}}";
  return s.str();
}

// Black 2 x 2 x 2 m box whose roof is the opening domain; one sensor on the floor centre.
Scene black_box(const TempDir& dir, int paths) {
  ObjBuilder obj;
  obj.box({0, 0, 0}, {2, 2, 2}, [](const std::string& f) { return f == "ceiling" ? "roof" : "black"; });
  dir.write("scene.obj", obj.str());
  dir.write("scene.json",
            scene_json(R"({"black": {"reflectance": 0}, "roof": {"reflectance": 0}})",
                       R"({"materials": ["roof"], "element_size": 0.25})",
                       R"({"points": [[1, 1, 0], [0.5, 1.5, 0]], "normals": [0, 0, 1]})", paths));
  return load_scene(dir.file("scene.json"));
}

TEST(Trace, UnobstructedUniformSkyGivesPiL) {
  TempDir dir;
  ObjBuilder obj;  // a domain square far below the sensor: it cannot see it
  obj.quad("slab", "slab", {-1, -1, -10}, {1, -1, -10}, {1, 1, -10}, {-1, 1, -10});
  dir.write("scene.obj", obj.str());
  dir.write("scene.json", scene_json(R"({"slab": {"reflectance": 0.5}})", R"({"materials": ["slab"]})",
                                     R"({"points": [[0, 0, 0], [3, 2, 1]], "normals": [[0, 0, 1], [0, 0, 1]]})", 2048));
  const Scene scene = load_scene(dir.file("scene.json"));
  const SensorValues v = evaluate_openings(scene, {});
  const Contributions c = compute_contributions(scene);
  for (int i = 0; i < 2; ++i) {
    // With cosine-weighted sky sampling the estimate is exact up to float rounding.
    const double rounding = test::kFloatRounding * M_PI * kRadiance;
    EXPECT_TRUE(within_sigma(v.value[i], v.standard_error[i], M_PI * kRadiance, rounding)) << "sensor " << i;
    EXPECT_TRUE(within_sigma(c.closed.value[i], c.closed.standard_error[i], M_PI * kRadiance, rounding)) << "sensor " << i;
    EXPECT_LT(v.standard_error[i], 0.01 * M_PI * kRadiance);
  }
}

TEST(Trace, BlackBoxRoofOpeningMatchesParallelRectangleViewFactor) {
  TempDir dir;
  const Scene scene = black_box(dir, 1 << 15);
  const Rectangle hole = {Vec3(0.5f, 0.5f, 2), Vec3(1.5f, 0.5f, 2), Vec3(1.5f, 1.5f, 2), Vec3(0.5f, 1.5f, 2)};
  // The corner formula (four 0.5 x 0.5 rectangles) and Lambert's polygon formula agree.
  const double f_corner = 4.0 * test::parallel_corner_view_factor(0.5, 0.5, 2.0);
  const double f_polygon = test::polygon_view_factor({1, 1, 0}, {0, 0, 1}, {hole.begin(), hole.end()});
  ASSERT_NEAR(f_corner, f_polygon, 1e-9);

  const SensorValues v = evaluate_openings(scene, {hole});
  const Contributions c = compute_contributions(scene);
  const SensorValues exact = c.evaluate(mask_of_elements_inside(scene, hole));
  for (int i = 0; i < 2; ++i) {
    const Vec3 p = scene.sensors.points[i] + Vec3(0, 0, test::kSensorLift);
    const double expected = M_PI * kRadiance * test::polygon_view_factor(p, {0, 0, 1}, {hole.begin(), hole.end()});
    EXPECT_TRUE(within_sigma(v.value[i], v.standard_error[i], expected, 0.0)) << "evaluate, sensor " << i;
    EXPECT_TRUE(within_sigma(exact.value[i], exact.standard_error[i], expected, 0.0)) << "exact records, sensor " << i;
    EXPECT_GT(v.standard_error[i], 0.0);
  }
}

TEST(Trace, VerticalWindowWithSillAtWorkPlaneMatchesClosedForm) {
  TempDir dir;
  ObjBuilder obj;
  obj.box({0, 0, 0}, {4, 4, 3}, [](const std::string& f) { return f == "south" ? "facade" : "black"; });
  dir.write("scene.obj", obj.str());
  dir.write("scene.json", scene_json(R"({"black": {"reflectance": 0}, "facade": {"reflectance": 0}})",
                                     R"({"materials": ["facade"], "element_size": 0.25})",
                                     R"({"points": [[2, 1, 0.75], [1.25, 2.5, 0.75]], "normals": [0, 0, 1]})", 1 << 15));
  const Scene scene = load_scene(dir.file("scene.json"));
  const Rectangle window = {Vec3(1, 0, 0.75f), Vec3(3, 0, 0.75f), Vec3(3, 0, 2), Vec3(1, 0, 2)};
  const SensorValues v = evaluate_openings(scene, {window});
  const Contributions c = compute_contributions(scene);
  const auto mask = mask_of_elements_inside(scene, window);
  ASSERT_EQ(std::count(mask.begin(), mask.end(), 1), 40);
  const SensorValues exact = c.evaluate(mask);
  for (int i = 0; i < 2; ++i) {
    const Vec3 p = scene.sensors.points[i] + Vec3(0, 0, test::kSensorLift);
    const double expected = M_PI * kRadiance * test::polygon_view_factor(p, {0, 0, 1}, {window.begin(), window.end()});
    EXPECT_TRUE(within_sigma(v.value[i], v.standard_error[i], expected, 0.0)) << "evaluate, sensor " << i;
    EXPECT_TRUE(within_sigma(exact.value[i], exact.standard_error[i], expected, 0.0)) << "exact records, sensor " << i;
  }
}

TEST(Trace, LambertFormulaReproducesReferenceDirectTable) {
  // ../shared/reference/radiance-scene-b.md, "Direct only": view factor x 1000 of the window.
  const std::vector<Vec3> window = {{1, 0, 0.9f}, {3, 0, 0.9f}, {3, 0, 2.1f}, {1, 0, 2.1f}};
  const double table[4][4] = {{51.69, 248.37, 248.37, 51.69},
                              {33.95, 68.03, 68.03, 33.95},
                              {15.79, 23.38, 23.38, 15.79},
                              {7.91, 10.10, 10.10, 7.91}};
  for (int r = 0; r < 4; ++r)
    for (int col = 0; col < 4; ++col) {
      const Vec3 p(0.5f + col, 0.5f + r, 0.8f);
      EXPECT_NEAR(1000.0 * test::polygon_view_factor(p, {0, 0, 1}, window), table[r][col], 0.006);
    }
}

// The reference room, interreflections included, against Radiance / radiosity.
TEST(Trace, ReferenceRoomMatchesRadiance) {
  Scene scene = load_scene(std::string(FENESTRA_EXAMPLES) + "/reference_room/scene.json");
  scene.render.paths_per_sensor = 1 << 15;
  const Rectangle window = {Vec3(1, 0, 0.9f), Vec3(3, 0, 0.9f), Vec3(3, 0, 2.1f), Vec3(1, 0, 2.1f)};
  const SensorValues v = evaluate_openings(scene, {window});
  const double* table = test::kReferenceRoomTable;
  for (int i = 0; i < 16; ++i) {
    // The reference is itself known to 0.3 % (Radiance and radiosity agree that closely).
    EXPECT_TRUE(within_sigma(v.value[i], v.standard_error[i], table[i], 0.003 * table[i])) << "sensor " << i;
  }
}

TEST(Trace, OneElementOpenEvaluateEqualsColumnOfE) {
  TempDir dir;
  ObjBuilder obj;
  obj.box({0, 0, 0}, {3, 3, 2.5f}, [](const std::string& f) {
    return f == "south" ? "facade" : f == "floor" ? "floor" : "grey";
  });
  dir.write("scene.obj", obj.str());
  dir.write("scene.json",
            scene_json(R"({"grey": {"reflectance": 0.6}, "floor": {"reflectance": [0.3, 0.25, 0.2]}, "facade": {"reflectance": 0.5}})",
                       R"({"materials": ["facade"], "element_size": 0.5})",
                       R"({"points": [[1.5, 1, 0.8], [0.5, 2.5, 0.8], [2.5, 0.5, 1.5]], "normals": [0, 0, 1]})", 1 << 14));
  const Scene scene = load_scene(dir.file("scene.json"));
  const Contributions c = compute_contributions(scene);
  for (int k : {3, 8, 14}) {
    const Element& e = scene.domain.elements()[k];
    const SensorValues v = evaluate_openings(scene, {e.corners});
    for (int i = 0; i < 3; ++i) {
      const double predicted = c.closed.value[i] + c.E(i, k);
      EXPECT_TRUE(within_sigma(predicted, c.E_stderr(i, k), v.value[i], v.standard_error[i])) << "element " << k << ", sensor " << i;
    }
    std::vector<uint8_t> only(scene.domain.element_count(), 0);
    only[k] = 1;
    const SensorValues exact = c.evaluate(only);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(exact.value[i], c.closed.value[i] + c.E(i, k), 1e-9 * (1 + exact.value[i]));
  }
}

TEST(Trace, ExactRecordsEqualEvaluateForASetOfOpenElements) {
  TempDir dir;
  ObjBuilder obj;
  obj.box({0, 0, 0}, {4, 3, 2.5f}, [](const std::string& f) {
    return f == "south" || f == "ceiling" ? "domain" : "grey";
  });
  dir.write("scene.obj", obj.str());
  dir.write("scene.json",
            scene_json(R"({"grey": {"reflectance": 0.7}, "domain": {"reflectance": 0.6}})",
                       R"({"materials": ["domain"], "element_size": 0.5})",
                       R"({"points": [[1, 1, 0.8], [3, 2, 0.8], [2, 2.5, 1.2], [0.5, 0.5, 2]], "normals": [0, 0, 1]})",
                       1 << 14));
  const Scene scene = load_scene(dir.file("scene.json"));
  const Contributions c = compute_contributions(scene);
  // Two windows and a skylight, element-aligned.
  const std::vector<Rectangle> openings = {
      {Vec3(0.5f, 0, 1), Vec3(1.5f, 0, 1), Vec3(1.5f, 0, 2), Vec3(0.5f, 0, 2)},
      {Vec3(2.5f, 0, 0.5f), Vec3(3.5f, 0, 0.5f), Vec3(3.5f, 0, 2), Vec3(2.5f, 0, 2)},
      {Vec3(1.5f, 1, 2.5f), Vec3(2.5f, 1, 2.5f), Vec3(2.5f, 2, 2.5f), Vec3(1.5f, 2, 2.5f)}};
  std::vector<uint8_t> mask(scene.domain.element_count(), 0);
  for (const auto& r : openings) {
    const auto m = mask_of_elements_inside(scene, r);
    for (size_t k = 0; k < m.size(); ++k) mask[k] |= m[k];
  }
  ASSERT_EQ(std::count(mask.begin(), mask.end(), 1), 4 + 6 + 4);
  const SensorValues exact = c.evaluate(mask);
  const SensorValues truth = evaluate_openings(scene, {openings.begin(), openings.end()});
  for (int i = 0; i < 4; ++i) {
    EXPECT_TRUE(within_sigma(exact.value[i], exact.standard_error[i], truth.value[i], truth.standard_error[i])) << "sensor " << i;
    EXPECT_GT(exact.value[i], 0.0);
  }
  // All open: the same from records and from the summary.
  const SensorValues all = c.evaluate(std::vector<uint8_t>(scene.domain.element_count(), 1));
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(all.value[i], c.all_open.value[i], 1e-9 * all.value[i]);
}

TEST(Trace, ExactRecordsEqualEvaluateWithGroundAndNeighbourOutside) {
  // Light reaches the room through the window from the sky, the ground and a facing building.
  TempDir dir;
  ObjBuilder obj;
  obj.box({0, 0, 0}, {3, 3, 2.5f}, [](const std::string& f) { return f == "south" ? "facade" : "grey"; });
  obj.quad("ground", "ground", {-30, -30, -0.01f}, {30, -30, -0.01f}, {30, 30, -0.01f}, {-30, 30, -0.01f});
  obj.quad("neighbour", "neighbour", {-5, -4, 0}, {-5, -4, 6}, {8, -4, 6}, {8, -4, 0});
  dir.write("scene.obj", obj.str());
  dir.write("scene.json",
            scene_json(R"({"grey": {"reflectance": 0.6}, "facade": {"reflectance": 0.5}, "ground": {"reflectance": 0.3},
                           "neighbour": {"reflectance": 0.5}})",
                       R"({"materials": ["facade"], "element_size": 0.5})",
                       R"({"points": [[1.5, 1, 0.8], [0.5, 2.5, 0.8], [2.5, 2.5, 1.5]], "normals": [0, 0, 1]})",
                       1 << 14));
  const Scene scene = load_scene(dir.file("scene.json"));
  const Contributions c = compute_contributions(scene);
  const Rectangle window = {Vec3(0.5f, 0, 0.5f), Vec3(2.5f, 0, 0.5f), Vec3(2.5f, 0, 2), Vec3(0.5f, 0, 2)};
  const auto mask = mask_of_elements_inside(scene, window);
  ASSERT_EQ(std::count(mask.begin(), mask.end(), 1), 12);
  const SensorValues exact = c.evaluate(mask);
  const SensorValues truth = evaluate_openings(scene, {window});
  for (int i = 0; i < 3; ++i)
    EXPECT_TRUE(within_sigma(exact.value[i], exact.standard_error[i], truth.value[i], truth.standard_error[i]))
        << "sensor " << i;
  // The whole wall open: light leaving through one element and coming back through others.
  const Rectangle wall = {Vec3(0, 0, 0), Vec3(3, 0, 0), Vec3(3, 0, 2.5f), Vec3(0, 0, 2.5f)};
  const SensorValues wall_truth = evaluate_openings(scene, {wall});
  for (int i = 0; i < 3; ++i)
    EXPECT_TRUE(within_sigma(c.all_open.value[i], c.all_open.standard_error[i], wall_truth.value[i],
                             wall_truth.standard_error[i]))
        << "sensor " << i << ", whole wall open";
}

TEST(Trace, SameSeedSameNumbersWhateverTheThreadCount) {
  TempDir dir;
  ObjBuilder obj;
  obj.box({0, 0, 0}, {3, 3, 2.5f}, [](const std::string& f) { return f == "south" ? "facade" : "grey"; });
  dir.write("scene.obj", obj.str());
  auto load = [&](int threads) {
    dir.write("scene.json", scene_json(R"({"grey": {"reflectance": 0.6}, "facade": {"reflectance": 0.5}})",
                                       R"({"materials": ["facade"], "element_size": 0.5})",
                                       R"({"points": [[1.5, 1, 0.8], [0.5, 2.5, 0.8]], "normals": [0, 0, 1]})", 1000,
                                       7, threads));
    return load_scene(dir.file("scene.json"));
  };
  const Scene one = load(1), two = load(2), all = load(0);
  const Contributions c1 = compute_contributions(one), c2 = compute_contributions(two), c0 = compute_contributions(all);
  EXPECT_TRUE(c1.E == c2.E && c1.E == c0.E);
  EXPECT_TRUE(c1.A == c2.A && c1.T == c2.T);
  EXPECT_TRUE(c1.all_open.value == c2.all_open.value);
  EXPECT_GT(c1.E.sum(), 0.0);
  const Rectangle hole = {Vec3(1, 0, 1), Vec3(2, 0, 1), Vec3(2, 0, 2), Vec3(1, 0, 2)};
  EXPECT_TRUE(evaluate_openings(one, {hole}).value == evaluate_openings(two, {hole}).value);
}

TEST(Trace, ThinGlassPaneAbsorbsWhatFresnelAndItsBodySay) {
  // A horizontal 20 x 20 m pane 1 m above an upward sensor, uniform sky in every direction: light
  // through the pane from above and light the pane reflects from below both reach the sensor, so
  // E = pi L - L * integral over the pane of absorptance(theta) cos(theta) d(omega).
  TempDir dir;
  ObjBuilder obj;
  obj.quad("pane", "pane", {-10, -10, 1}, {10, -10, 1}, {10, 10, 1}, {-10, 10, 1});
  obj.quad("slab", "slab", {-1, -1, -10}, {1, -1, -10}, {1, 1, -10}, {-1, 1, -10});
  dir.write("scene.obj", obj.str());
  dir.write("scene.json",
            scene_json(R"({"pane": {"type": "glass", "transmittance": 0.6, "ior": 1.5}, "slab": {"reflectance": 0.5}})",
                       R"({"materials": ["slab"]})", R"({"points": [[0, 0, 0]], "normals": [0, 0, 1]})", 1 << 15));
  const Scene scene = load_scene(dir.file("scene.json"));
  const Material& pane = scene.materials[0].name == "pane" ? scene.materials[0] : scene.materials[1];
  double absorbed = 0.0;  // integral of A(theta) cos(theta) d(omega) over directions meeting the pane
  const int n = 800;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double theta = (i + 0.5) / n * M_PI / 2, phi = (j + 0.5) / n * 2 * M_PI;
      const double t = std::tan(theta);
      if (std::abs(t * std::cos(phi)) > 10 || std::abs(t * std::sin(phi)) > 10) continue;
      const float c = static_cast<float>(std::cos(theta));
      const double a = 1.0 - luminance(thin_glass_transmittance(pane, c)) - luminance(thin_glass_reflectance(pane, c));
      absorbed += a * std::cos(theta) * std::sin(theta) * (M_PI / 2 / n) * (2 * M_PI / n);
    }
  ASSERT_GT(absorbed, 0.2);  // the pane absorbs a fair share: the test can tell
  const double expected = kRadiance * (M_PI - absorbed);
  const SensorValues v = evaluate_openings(scene, {});
  EXPECT_TRUE(within_sigma(v.value[0], v.standard_error[0], expected, 0.0));
  const Contributions c = compute_contributions(scene);
  EXPECT_TRUE(within_sigma(c.closed.value[0], c.closed.standard_error[0], expected, 0.0));
}

TEST(Trace, ThickWallCutHasReveals) {
  // A 0.3 m wall modelled as two faces; the cut through it is lined with reveal faces.
  TempDir dir;
  ObjBuilder obj;
  obj.box({0, 0, 0}, {3, 3, 2.5f}, [](const std::string& f) { return f == "south" ? "facade" : "black"; });
  obj.quad("outer", "black", {0, -0.3f, 0}, {3, -0.3f, 0}, {3, -0.3f, 2.5f}, {0, -0.3f, 2.5f});
  dir.write("scene.obj", obj.str());
  dir.write("scene.json", scene_json(R"({"black": {"reflectance": 0}, "facade": {"reflectance": 0}})",
                                     R"({"materials": ["facade"], "element_size": 0.25, "thickness": 0.3})",
                                     R"({"points": [[1.5, 1.5, 0.5]], "normals": [0, 0, 1]})", 1 << 14));
  const Scene scene = load_scene(dir.file("scene.json"));
  const Rectangle window = {Vec3(1, 0, 0.5f), Vec3(2, 0, 0.5f), Vec3(2, 0, 1.5f), Vec3(1, 0, 1.5f)};
  const SensorValues v = evaluate_openings(scene, {window});
  // Black reveals: only directions through both the inner and outer rectangle see the sky.
  // The sensor is at sill height, so this is the inner window's factor minus what the reveals hide;
  // bound it by the outer rectangle's factor (seen through the hole) from above and check it is lit.
  const std::vector<Vec3> inner = {window.begin(), window.end()};
  const std::vector<Vec3> outer = {{1, -0.3f, 0.5f}, {2, -0.3f, 0.5f}, {2, -0.3f, 1.5f}, {1, -0.3f, 1.5f}};
  const double f_inner = test::polygon_view_factor({1.5f, 1.5f, 0.5f}, {0, 0, 1}, inner);
  const double f_outer = test::polygon_view_factor({1.5f, 1.5f, 0.5f}, {0, 0, 1}, outer);
  EXPECT_LT(v.value[0], M_PI * kRadiance * f_inner);
  EXPECT_TRUE(within_sigma(v.value[0], v.standard_error[0], M_PI * kRadiance * f_outer, 0.0));
}

}  // namespace
}  // namespace fenestra
