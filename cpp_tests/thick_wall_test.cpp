// Thick walls: the exact evaluation from path records (elements as tubes through the wall, reveals
// where a closed neighbour lines an open one) against `evaluate` with the openings really cut.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <sstream>

#include "test_scenes.h"
#include "trace/contributions.h"
#include "trace/evaluate.h"

namespace fenestra {
namespace {

using test::ObjBuilder;
using test::TempDir;
using test::within_sigma;

struct Wall {
  float thickness;     // meters
  float element_size;  // meters
  bool modelled;       // outer face and edge strips in the OBJ (else: thickness given, wall added)
  bool sun;            // Preetham sky with the sun at about 50 degrees to the wall's normal; else overcast
};

std::string describe(const Wall& w) {
  std::ostringstream s;
  s << w.thickness << " m wall, " << w.element_size << " m elements, " << (w.modelled ? "modelled solid" : "given")
    << ", " << (w.sun ? "sun" : "overcast");
  return s.str();
}

// A 3 m x 3 m x 2.5 m room; its south wall (y = 0) is the domain, the wall's body lies at y < 0.
Scene room(const TempDir& dir, const Wall& w, int paths) {
  ObjBuilder obj;
  obj.box({0, 0, 0}, {3, 3, 2.5f}, [](const std::string& f) { return f == "south" ? "facade" : "plaster"; });
  obj.quad("ground", "ground", {-20, -20, -0.01f}, {20, -20, -0.01f}, {20, 20, -0.01f}, {-20, 20, -0.01f});
  if (w.modelled) {
    const float t = -w.thickness;
    obj.quad("outer", "outside", {0, t, 0}, {0, t, 2.5f}, {3, t, 2.5f}, {3, t, 0});
    obj.quad("edge_bottom", "outside", {0, t, 0}, {3, t, 0}, {3, 0, 0}, {0, 0, 0});
    obj.quad("edge_top", "outside", {0, t, 2.5f}, {0, 0, 2.5f}, {3, 0, 2.5f}, {3, t, 2.5f});
    obj.quad("edge_west", "outside", {0, t, 0}, {0, 0, 0}, {0, 0, 2.5f}, {0, t, 2.5f});
    obj.quad("edge_east", "outside", {3, t, 0}, {3, t, 2.5f}, {3, 0, 2.5f}, {3, 0, 0});
  }
  dir.write("scene.obj", obj.str());
  std::ostringstream s;
  s << R"({"fenestra": 1, "geometry": "scene.obj",
      "materials": {"plaster": {"reflectance": 0.6}, "facade": {"reflectance": 0.5},
                    "outside": {"reflectance": 0.5}, "ground": {"reflectance": 0.2}},
      "opening_domain": {"materials": ["facade"], "element_size": )"
    << w.element_size;
  if (!w.modelled) s << R"(, "thickness": )" << w.thickness;
  s << R"(},
      "sensors": {"points": [[1.5, 1, 0.8], [0.6, 2.4, 0.8], [2.4, 0.6, 0.8], [1.5, 2.5, 1.6]], "normals": [0, 0, 1]},
      "sky": )"
    << (w.sun ? R"({"type": "preetham", "latitude": 48.85, "longitude": 2.35, "utc_offset": 1, "date": "2026-03-21",
                  "time": "10:00", "resolution": [128, 64]})"
              : R"({"type": "cie_overcast", "resolution": [128, 64]})")
    << R"(, "render": {"paths_per_sensor": )" << paths << R"(, "max_bounces": 6, "seed": 3}})";
  dir.write("scene.json", s.str());
  return load_scene(dir.file("scene.json"));
}

// Element k's square as an opening rectangle.
Rectangle square(const Scene& scene, int k) { return scene.domain.elements()[k].corners; }

// Elements whose centre lies in the box [x0, x1] x [z0, z1] of the wall.
std::vector<int> elements_in(const Scene& scene, float x0, float x1, float z0, float z1) {
  std::vector<int> out;
  for (size_t k = 0; k < scene.domain.element_count(); ++k) {
    const Vec3 c = scene.domain.elements()[k].center;
    if (c.x() > x0 && c.x() < x1 && c.z() > z0 && c.z() < z1) out.push_back(static_cast<int>(k));
  }
  return out;
}

class ThickWall : public ::testing::TestWithParam<Wall> {};

TEST_P(ThickWall, ExactRecordsEqualEvaluateWithRealCuts) {
  const Wall w = GetParam();
  TempDir dir;
  const Scene scene = room(dir, w, 1 << 13);
  for (const Panel& p : scene.domain.panels()) ASSERT_NEAR(p.thickness, w.thickness, 1e-5) << describe(w);
  const Contributions c = compute_contributions(scene);
  const size_t n = scene.domain.element_count();

  // Open sets as the solver makes them: a window, a ragged cluster of single elements (neighbours
  // open and closed on every side), the whole wall. Each element is cut as its own rectangle:
  // adjacent cuts share no reveal.
  const std::vector<std::vector<int>> sets = {
      elements_in(scene, 0.9f, 2.1f, 0.9f, 2.1f),
      [&] {
        std::vector<int> ragged;
        for (int k : elements_in(scene, 0.3f, 2.7f, 0.3f, 2.3f))
          if ((k * 7) % 3 != 0) ragged.push_back(k);
        return ragged;
      }(),
      elements_in(scene, -1, 4, -1, 3)};
  double max_z = 0.0;
  for (size_t set = 0; set < sets.size(); ++set) {
    std::vector<uint8_t> mask(n, 0);
    std::vector<OpeningInput> cuts;
    for (int k : sets[set]) mask[k] = 1, cuts.push_back(square(scene, k));
    ASSERT_GT(cuts.size(), 3u);
    const SensorValues exact = c.evaluate(mask);
    const SensorValues truth = evaluate_openings(scene, cuts);
    // The same set as rectangles on the panel (what the solver's edge search evaluates): equal to
    // the mask's evaluation, although tube crossings lie on the grid lines between cells.
    std::vector<PanelRectangle> squares;
    for (int k : sets[set]) squares.push_back(to_panel_rectangle(scene.domain, square(scene, k)));
    const SensorValues as_region = c.evaluate(OpenRegion(scene.domain, squares));
    for (size_t i = 0; i < scene.sensors.size(); ++i)
      EXPECT_NEAR(as_region.value[i], exact.value[i], 1e-9 * (1.0 + exact.value[i])) << describe(w) << ", set " << set;
    for (size_t i = 0; i < scene.sensors.size(); ++i) {
      EXPECT_GT(truth.value[i], 0.0);
      max_z = std::max(max_z, std::abs(exact.value[i] - truth.value[i]) /
                                  std::hypot(exact.standard_error[i], truth.standard_error[i]));
      EXPECT_TRUE(within_sigma(exact.value[i], exact.standard_error[i], truth.value[i], truth.standard_error[i]))
          << describe(w) << ", set " << set << ", sensor " << i;
    }
  }
  std::printf("[ thick    ] %s: records against real cuts, max |z| %.2f over %zu values\n", describe(w).c_str(), max_z,
              sets.size() * scene.sensors.size());
}

INSTANTIATE_TEST_SUITE_P(Walls, ThickWall,
                         ::testing::Values(Wall{0.3f, 0.25f, true, false}, Wall{0.3f, 0.25f, false, true},
                                           Wall{0.5f, 0.2f, true, true}, Wall{0.1f, 0.5f, false, false},
                                           Wall{0.2f, 0.25f, true, true}));

TEST(ThickWall, RevealsTakeLightTheThinWallLets) {
  // The test above can tell: the same window in a 0.5 m wall and in a zero-thickness one differ
  // by many standard errors.
  TempDir thin_dir, thick_dir;
  const Scene thin = room(thin_dir, {0.0f, 0.25f, false, false}, 1 << 13);
  const Scene thick = room(thick_dir, {0.5f, 0.25f, false, false}, 1 << 13);
  const Rectangle window = {Vec3(1, 0, 1), Vec3(2, 0, 1), Vec3(2, 0, 2), Vec3(1, 0, 2)};
  const SensorValues a = evaluate_openings(thin, {window}), b = evaluate_openings(thick, {window});
  for (size_t i = 0; i < a.value.size(); ++i)
    EXPECT_GT(a.value[i] - b.value[i], 8.0 * std::hypot(a.standard_error[i], b.standard_error[i])) << "sensor " << i;
}

TEST(ThickWall, MeasuredFromTheModelUnlessGiven) {
  TempDir dir;
  const Scene measured = room(dir, {0.3f, 0.25f, true, false}, 16);
  EXPECT_NEAR(measured.domain.panels()[0].thickness, 0.3f, 1e-5);
  EXPECT_TRUE(measured.domain.panels()[0].solid_modelled);
  // A thickness that disagrees with the model is refused, naming both.
  std::string json;
  {
    std::ifstream in(dir.file("scene.json"));
    json.assign(std::istreambuf_iterator<char>(in), {});
  }
  const std::string key = R"("element_size": 0.25)";
  json.replace(json.find(key), key.size(), key + R"(, "thickness": 0.2)");
  dir.write("scene.json", json);
  try {
    load_scene(dir.file("scene.json"));
    FAIL() << "a thickness of 0.2 m on a 0.3 m solid was accepted";
  } catch (const std::invalid_argument& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("0.2 m"), std::string::npos) << m;
    EXPECT_NE(m.find("0.3 m"), std::string::npos) << m;
    EXPECT_NE(m.find("facade"), std::string::npos) << m;
  }
}

}  // namespace
}  // namespace fenestra
