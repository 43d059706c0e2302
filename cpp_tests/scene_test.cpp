// Scene files: the opening domain's dicing, and bad input that must give a clear error.
#include <gtest/gtest.h>

#include <cmath>

#include "io/results.h"
#include "test_scenes.h"
#include "trace/contributions.h"
#include "trace/evaluate.h"

namespace fenestra {
namespace {

using test::ObjBuilder;
using test::TempDir;

const char* kMaterials = R"({"wall": {"reflectance": 0.5}, "facade": {"reflectance": 0.5}})";

std::string room_obj() {
  ObjBuilder obj;
  obj.box({0, 0, 0}, {4, 3, 2.6f}, [](const std::string& f) { return f == "south" ? "facade" : "wall"; });
  return obj.str();
}

std::string scene_text(const std::string& domain = R"({"materials": ["facade"]})",
                       const std::string& sensors = R"({"points": [[2, 1.5, 0.8]]})",
                       const std::string& sky = R"({"type": "uniform", "radiance": 100})",
                       const std::string& materials = kMaterials) {
  return std::string(R"({"fenestra": 1, "geometry": "scene.obj", "materials": )") + materials +
         R"(, "opening_domain": )" + domain + R"(, "sensors": )" + sensors + R"(, "sky": )" + sky + "}";
}

// Loads the scene and expects std::invalid_argument whose message contains every fragment.
void expect_error(const TempDir& dir, const std::vector<std::string>& fragments) {
  try {
    const Scene s = load_scene(dir.file("scene.json"));
    compute_contributions(s);
    FAIL() << "no error; expected one mentioning " << fragments.front();
  } catch (const std::invalid_argument& e) {
    for (const auto& f : fragments) EXPECT_NE(std::string(e.what()).find(f), std::string::npos) << e.what();
  }
}

TEST(Scene, DomainIsDicedIntoCentredSquareElementsWithRowsHorizontal) {
  TempDir dir;
  dir.write("scene.obj", room_obj());
  dir.write("scene.json", scene_text(R"({"materials": ["facade"], "element_size": 0.25})"));
  const Scene scene = load_scene(dir.file("scene.json"));
  ASSERT_EQ(scene.domain.panels().size(), 1u);
  const Panel& p = scene.domain.panels()[0];
  EXPECT_EQ(p.cols, 16);
  EXPECT_EQ(p.rows, 10);  // 2.6 m: ten rows, 0.05 m margins top and bottom
  EXPECT_EQ(scene.domain.element_count(), 160u);
  EXPECT_NEAR(std::abs(p.u_axis.z()), 0.0f, 1e-6f);  // rows horizontal
  EXPECT_NEAR(p.v_axis.z(), 1.0f, 1e-6f);
  EXPECT_NEAR(p.outward.y(), -1.0f, 1e-6f);  // away from the sensor, out of the room
  float zmin = 1e9f, zmax = -1e9f;
  for (const auto& e : scene.domain.elements())
    for (const auto& c : e.corners) zmin = std::min(zmin, c.z()), zmax = std::max(zmax, c.z());
  EXPECT_NEAR(zmin, 0.05f, 1e-5f);
  EXPECT_NEAR(zmax, 2.55f, 1e-5f);
  // Every element is found at its own centre, and nothing in the margin.
  for (size_t k = 0; k < scene.domain.element_count(); ++k)
    EXPECT_EQ(scene.domain.element_at(0, scene.domain.elements()[k].center), static_cast<int>(k));
  EXPECT_EQ(scene.domain.element_at(0, Vec3(2, 0, 0.02f)), -1);
}

TEST(Scene, NonRectangularPanelKeepsOnlyElementsInside) {
  TempDir dir;
  ObjBuilder obj;
  obj.box({0, 0, 0}, {4, 3, 3}, [](const std::string&) { return "wall"; });
  // An L-shaped domain panel made of two coplanar quads in the plane y = 1.
  obj.quad("l1", "facade", {0, 1, 0}, {2, 1, 0}, {2, 1, 1}, {0, 1, 1});
  obj.quad("l2", "facade", {0, 1, 1}, {1, 1, 1}, {1, 1, 2}, {0, 1, 2});
  dir.write("scene.obj", obj.str());
  dir.write("scene.json", scene_text(R"({"materials": ["facade"], "element_size": 0.5})", R"({"points": [[2, 2, 0.8]]})"));
  const Scene scene = load_scene(dir.file("scene.json"));
  ASSERT_EQ(scene.domain.panels().size(), 1u);
  EXPECT_EQ(scene.domain.element_count(), 8u + 4u);  // 4 x 2 below, 2 x 2 above
}

TEST(Scene, SeparatePlanesAreSeparatePanels) {
  TempDir dir;
  dir.write("scene.obj", room_obj());
  dir.write("scene.json", scene_text(R"({"groups": ["south", "ceiling"], "element_size": 0.5})"));
  const Scene scene = load_scene(dir.file("scene.json"));
  EXPECT_EQ(scene.domain.panels().size(), 2u);
}

TEST(SceneErrors, MissingAndMalformedFiles) {
  TempDir dir;
  EXPECT_THROW(load_scene(dir.file("nope.json")), std::invalid_argument);
  dir.write("scene.json", "{\"fenestra\": 1, ");
  expect_error(dir, {"scene.json", "not valid JSON"});
  dir.write("scene.json", scene_text());
  expect_error(dir, {"scene.obj"});  // geometry file missing
  dir.write("scene.obj", "v 0 0 0\nv 1 0 0\nf 1 2 3\n");
  expect_error(dir, {"scene.obj"});
}

TEST(SceneErrors, NonFiniteCoordinatesAndDegenerateFaces) {
  TempDir dir;
  dir.write("scene.json", scene_text());
  dir.write("scene.obj", "usemtl facade\nv 0 0 0\nv nan 0 0\nv 0 0 1\nf 1 2 3\n");
  expect_error(dir, {"scene.obj", "line 3", "finite"});
  dir.write("scene.obj", "usemtl facade\nv 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n");
  expect_error(dir, {"scene.obj", "degenerate"});
}

TEST(SceneErrors, EmptyDomainNoSensorsUnknownMaterial) {
  TempDir dir;
  dir.write("scene.obj", room_obj());
  dir.write("scene.json", scene_text(R"({"materials": []})"));
  expect_error(dir, {"opening domain is empty"});
  dir.write("scene.json", scene_text(R"({"materials": ["glass"]})"));
  expect_error(dir, {"glass"});
  dir.write("scene.json", scene_text(R"({"materials": ["facade"]})", R"({"points": []})"));
  expect_error(dir, {"no sensors"});
  dir.write("scene.json", scene_text(R"({"materials": ["facade"]})", R"({"points": [[1, 1, "a"]]})"));
  expect_error(dir, {"sensors.points[0]"});
  dir.write("scene.json", scene_text(R"({"materials": ["facade"]})", R"({"points": [[1, 1, 1]]})",
                                     R"({"type": "uniform", "radiance": 100})", R"({"facade": {"reflectance": 0.5}})"));
  expect_error(dir, {"'wall'"});  // used in the OBJ, not defined
}

TEST(SceneErrors, ElementLargerThanPanel) {
  TempDir dir;
  dir.write("scene.obj", room_obj());
  dir.write("scene.json", scene_text(R"({"materials": ["facade"], "element_size": 3.0})"));
  expect_error(dir, {"element_size", "larger than"});
}

TEST(SceneErrors, SensorInsideGeometry) {
  TempDir dir;
  ObjBuilder obj;
  obj.box({0, 0, 0}, {4, 3, 2.6f}, [](const std::string& f) { return f == "south" ? "facade" : "wall"; });
  // A closed solid (outward normals) with the sensor inside it.
  obj.quad("b1", "wall", {1, 1, 0.1f}, {1, 2, 0.1f}, {2, 2, 0.1f}, {2, 1, 0.1f});
  obj.quad("b2", "wall", {1, 1, 1}, {2, 1, 1}, {2, 2, 1}, {1, 2, 1});
  obj.quad("b3", "wall", {1, 1, 0.1f}, {2, 1, 0.1f}, {2, 1, 1}, {1, 1, 1});
  obj.quad("b4", "wall", {1, 2, 0.1f}, {1, 2, 1}, {2, 2, 1}, {2, 2, 0.1f});
  obj.quad("b5", "wall", {1, 1, 0.1f}, {1, 1, 1}, {1, 2, 1}, {1, 2, 0.1f});
  obj.quad("b6", "wall", {2, 1, 0.1f}, {2, 2, 0.1f}, {2, 2, 1}, {2, 1, 1});
  dir.write("scene.obj", obj.str());
  dir.write("scene.json", scene_text(R"({"materials": ["facade"]})", R"({"points": [[3, 2.5, 0.8], [1.5, 1.5, 0.5]]})"));
  expect_error(dir, {"sensor 1", "inside geometry"});
}

TEST(SceneErrors, UnreadableEnvironmentMap) {
  TempDir dir;
  dir.write("scene.obj", room_obj());
  dir.write("sky.exr", "not an image");
  dir.write("scene.json", scene_text(R"({"materials": ["facade"]})", R"({"points": [[2, 1.5, 0.8]]})",
                                     R"({"type": "envmap", "file": "sky.exr"})"));
  expect_error(dir, {"sky.exr"});
}

TEST(SceneErrors, BadValues) {
  TempDir dir;
  dir.write("scene.obj", room_obj());
  dir.write("scene.json", scene_text(R"({"materials": ["facade"], "element_size": -1})"));
  expect_error(dir, {"element_size"});
  dir.write("scene.json", scene_text(R"({"materials": ["facade"]})", R"({"points": [[2, 1.5, 0.8]], "normals": [0, 0, 0]})"));
  expect_error(dir, {"normal"});
  dir.write("scene.json", scene_text(R"({"materials": ["facade"]})", R"({"points": [[2, 1.5, 0.8]]})",
                                     R"({"type": "uniform", "radiance": 100})",
                                     R"({"wall": {"reflectance": 1.5}, "facade": {"reflectance": 0.5}})"));
  expect_error(dir, {"materials.wall.reflectance"});
  dir.write("scene.json", scene_text(R"({"materials": ["facade"]})", R"({"points": [[2, 1.5, 0.8]]})",
                                     R"({"type": "sunny"})"));
  expect_error(dir, {"sky.type"});
}

TEST(SceneErrors, OpeningsOffTheDomainOrNotRectangles) {
  TempDir dir;
  dir.write("scene.obj", room_obj());
  dir.write("scene.json", scene_text());
  const Scene scene = load_scene(dir.file("scene.json"));
  const Rectangle off = {Vec3(1, 3, 1), Vec3(2, 3, 1), Vec3(2, 3, 2), Vec3(1, 3, 2)};  // north wall
  EXPECT_THROW(evaluate_openings(scene, {off}), std::invalid_argument);
  const Rectangle skew = {Vec3(1, 0, 1), Vec3(2, 0, 1), Vec3(2.5f, 0, 2), Vec3(1, 0, 2)};
  EXPECT_THROW(evaluate_openings(scene, {skew}), std::invalid_argument);
  dir.write("openings.json", R"({"openings": [{"corners": [[1, 0, 1], [2, 0, 1]]}]})");
  EXPECT_THROW(read_openings(dir.file("openings.json")), std::invalid_argument);
}

}  // namespace
}  // namespace fenestra
