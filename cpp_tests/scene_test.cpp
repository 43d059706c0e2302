// Scene files: the opening domain's dicing, and bad input that must give a clear error.
#include <gtest/gtest.h>

#include <cmath>

#include "annual/annual_contributions.h"
#include "format/image_writer.h"
#include "io/results.h"
#include "io/sky_output.h"
#include "scene/environment_map.h"
#include "solve/solver.h"
#include "test_scenes.h"
#include "trace/contributions.h"
#include "trace/contributions_origin.h"
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
    EXPECT_EQ(scene.domain.element_at(0, scene.domain.panel_point(0, scene.domain.elements()[k].center)), static_cast<int>(k));
  EXPECT_EQ(scene.domain.element_at(0, scene.domain.panel_point(0, Vec3(2, 0, 0.02f))), -1);
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
  EXPECT_THROW(read_openings(dir.file("openings.json"), SiteFrame{}), std::invalid_argument);
}

// ---- Every number validated after its conversion ----

// Expects load_scene on `json` (with room_obj()) to fail naming scene.json and every fragment.
void expect_scene_error(const std::string& json, const std::vector<std::string>& fragments) {
  TempDir dir;
  dir.write("scene.obj", room_obj());
  dir.write("scene.json", json);
  std::vector<std::string> all = {"scene.json"};
  all.insert(all.end(), fragments.begin(), fragments.end());
  expect_error(dir, all);
}

const char* kDomain = R"({"materials": ["facade"]})";

TEST(Validation, SensorCoordinatesOutsideTheRangeAreRefused) {
  // 1e39 is infinite as a float; 2e18 reached Embree and aborted.
  for (const char* p : {"[1e39, 1, 1]", "[1, 2e18, 1]", "[1, 1, -10000001]"})
    expect_scene_error(scene_text(kDomain, std::string(R"({"points": [[2, 1.5, 0.8], )") + p + "]}"),
                       {"sensors.points[1]", "1e+07 m"});
  // Within the site's range but farther from the model than a float keeps centimetres.
  expect_scene_error(scene_text(kDomain, R"({"points": [[2, 1.5, 0.8], [1, 1, -1000001]]})"),
                     {"sensors.points[1]", "1e+06 m from the model's local origin"});
  TempDir dir;
  dir.write("scene.obj", room_obj());
  dir.write("scene.json", scene_text(kDomain, R"({"points": [[2, 1.5, 0.8], [1000000, 1, 1]]})"));
  EXPECT_NO_THROW(load_scene(dir.file("scene.json")));  // the limit itself is accepted
}

TEST(Validation, NormalsAreNormalizedInDoublePrecisionAndNeverZero) {
  // 1e30 squared overflows a float: normalized in float it became [0, 0, 0].
  expect_scene_error(scene_text(kDomain, R"({"points": [[2, 1.5, 0.8]], "normals": [1e30, 0, 0]})"),
                     {"sensors.normals[0]"});
  expect_scene_error(scene_text(kDomain, R"({"points": [[2, 1.5, 0.8]], "normals": [1e-30, 0, 0]})"),
                     {"sensors.normals[0]", "zero"});
  TempDir dir;
  dir.write("scene.obj", room_obj());
  dir.write("scene.json", scene_text(kDomain, R"({"points": [[2, 1.5, 0.8]], "normals": [0, 1e-5, 5e5]})"));
  const Scene s = load_scene(dir.file("scene.json"));
  EXPECT_NEAR(s.sensors.normals[0].norm(), 1.0f, 1e-6f);
  EXPECT_NEAR(s.sensors.normals[0].z(), 1.0f, 1e-6f);
}

TEST(Validation, IntegersAreCheckedBeforeTheyAreConverted) {
  // Read as an int, 4294967297 was 1 and 4294967424 was 128.
  std::string text = scene_text();
  expect_scene_error(R"({"fenestra": 4294967297)" + text.substr(text.find(',')), {"fenestra", "4294967297"});
  expect_scene_error(scene_text(kDomain, R"({"points": [[2, 1.5, 0.8]]})",
                                R"({"type": "cie_overcast", "resolution": [4294967424, 64]})"),
                     {"sky.resolution[0]", "16384"});
  expect_scene_error(scene_text(kDomain, R"({"points": [[2, 1.5, 0.8]]})",
                                R"({"type": "cie_overcast", "resolution": [64, -2]})"),
                     {"sky.resolution[1]"});
  text.pop_back();
  expect_scene_error(text + R"(, "render": {"paths_per_sensor": 4294967296}})", {"render.paths_per_sensor", "1073741824"});
  expect_scene_error(text + R"(, "render": {"threads": 2147483648}})", {"render.threads", "4096"});
  expect_scene_error(text + R"(, "render": {"paths": 10}})", {"render.paths", "unknown key"});
}

TEST(Validation, SamplerAndGroundRadianceAreReadOrRefusedByName) {
  std::string text = scene_text();
  text.pop_back();
  TempDir dir;
  dir.write("scene.obj", room_obj());
  dir.write("scene.json", text + R"(, "render": {"sampler": "independent"}})");
  EXPECT_EQ(load_scene(dir.file("scene.json")).render.sampler, RenderSettings::Sampler::kIndependent);
  dir.write("scene.json", text + "}");
  EXPECT_EQ(load_scene(dir.file("scene.json")).render.sampler, RenderSettings::Sampler::kSobol);
  expect_scene_error(text + R"(, "render": {"sampler": "halton"}})", {"render.sampler", "\"halton\"", "sobol"});
  expect_scene_error(text + R"(, "render": {"sampler": 1}})", {"render.sampler", "independent"});
  const std::string points = R"({"points": [[2, 1.5, 0.8]]})";
  dir.write("scene.json", scene_text(kDomain, points, R"({"type": "uniform", "radiance": 300, "ground_radiance": 60})"));
  const Scene s = load_scene(dir.file("scene.json"));
  EXPECT_FLOAT_EQ(s.sky->radiance(Vec3(0, 0, 1))[0], 300.0f);
  EXPECT_FLOAT_EQ(s.sky->radiance(Vec3(0, 0.6f, -0.8f))[1], 60.0f);
  expect_scene_error(scene_text(kDomain, points, R"({"type": "uniform", "ground_radiance": -1})"),
                     {"sky.ground_radiance", "negative"});
  expect_scene_error(scene_text(kDomain, points, R"({"type": "uniform", "ground_radiance": 1e13})"),
                     {"sky.ground_radiance", "cd/m^2"});
}

TEST(Validation, ObjIndicesAndCoordinatesAreCheckedWithTheirLine) {
  TempDir dir;
  dir.write("scene.json", scene_text());
  const std::string room = room_obj();
  const auto lines = std::count(room.begin(), room.end(), '\n');
  // tinyobjloader wraps an index past 2^64 around to another vertex.
  dir.write("scene.obj", room + "usemtl wall\nf 1 2 18446744073709551619\n");
  expect_error(dir, {"scene.obj", "line " + std::to_string(lines + 2), "18446744073709551619"});
  dir.write("scene.obj", room + "usemtl wall\nf 1 2 999\n");
  expect_error(dir, {"scene.obj", "line " + std::to_string(lines + 2), "past the last vertex"});
  dir.write("scene.obj", room + "usemtl wall\nf 1 2 -9999\n");
  expect_error(dir, {"scene.obj", "line " + std::to_string(lines + 2), "-9999"});
  dir.write("scene.obj", room + "usemtl wall\nf 1 2 3x\n");
  expect_error(dir, {"scene.obj", "not an integer"});
  dir.write("scene.obj", "usemtl facade\nv 0 0 0\nv 2e7 0 0\nv 0 0 1\nf 1 2 3\n");
  expect_error(dir, {"scene.obj", "line 3", "out of range", "1e+07 m"});
  // Within the site's range, but wider than a float keeps centimetres across.
  dir.write("scene.obj", "usemtl facade\nv 0 0 0\nv 3e6 0 0\nv 0 0 1\nf 1 2 3\n");
  expect_error(dir, {"scene.obj", "vertex 1", "1e+06 m from the model's local origin"});
}

TEST(Validation, RadianceScaleAndAnglesMustStayFiniteAsFloats) {
  const std::string points = R"({"points": [[2, 1.5, 0.8]]})";
  // 1e39 cd/m^2 is infinite as a float: every value came out 0.
  expect_scene_error(scene_text(kDomain, points, R"({"type": "uniform", "radiance": 1e39})"), {"sky.radiance"});
  expect_scene_error(scene_text(kDomain, points, R"({"type": "uniform", "radiance": [1, 1, 2e12]})"),
                     {"sky.radiance", "1e+12"});
  expect_scene_error(scene_text(kDomain, points, R"({"radiance": 100})"), {"sky.type", "missing"});
  expect_scene_error(scene_text(kDomain, points, R"({"type": "uniform", "radiance": 100, "scale": 2})"),
                     {"sky.scale", "unknown key"});
  expect_scene_error(scene_text(kDomain, points, R"({"type": "cie_overcast", "horizontal_illuminance": 1e300})"),
                     {"sky.horizontal_illuminance"});

  TempDir dir;
  dir.write("scene.obj", room_obj());
  write_image(dir.file("sky.exr"), 8, 4, 3, std::vector<float>(8 * 4 * 3, 1000.0f));
  auto envmap = [&](const std::string& extra) {
    dir.write("scene.json", scene_text(kDomain, points, R"({"type": "envmap", "file": "sky.exr")" + extra + "}"));
  };
  envmap(R"(, "scale": 1e300)");
  expect_error(dir, {"scene.json", "sky.scale"});
  envmap(R"(, "scale": 1e10)");  // finite, but 1000 x 1e10 cd/m^2
  expect_error(dir, {"scene.json", "sky.file", "brightest pixel"});
  envmap(R"(, "rotation_deg": 1e300)");
  expect_error(dir, {"scene.json", "sky.rotation_deg", "360"});
  envmap(R"(, "scale": 2, "rotation_deg": -90)");
  EXPECT_NO_THROW(load_scene(dir.file("scene.json")));
}

TEST(Validation, JsonErrorsNameTheFileLineAndKeyInWords) {
  TempDir dir;
  dir.write("scene.obj", room_obj());
  dir.write("scene.json", scene_text(kDomain, "{\n\"points\": [[2, 1.5, 1e400]]}"));
  try {
    load_scene(dir.file("scene.json"));
    FAIL() << "1e400 accepted";
  } catch (const std::invalid_argument& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("scene.json"), std::string::npos) << m;
    EXPECT_NE(m.find("line 2"), std::string::npos) << m;
    EXPECT_NE(m.find("sensors.points[0][2]"), std::string::npos) << m;
    EXPECT_EQ(m.find("json.exception"), std::string::npos) << m;
  }
  dir.write("scene.json", scene_text(kDomain, R"({"points": [[2, 1.5, 0.8]]})", R"({"type": 3})"));
  expect_error(dir, {"scene.json", "sky.type", "expected a string"});
  dir.write("scene.json", scene_text(kDomain, R"({"points": [[2, 1.5, 0.8]]})", R"({"type": "uniform"})",
                                     R"({"wall": {"type": 3}, "facade": {}})"));
  expect_error(dir, {"scene.json", "materials.wall.type", "expected a string"});
  dir.write("openings.json", "{\"openings\": [\n{\"corners\": [[1, 0, 1], [2, 0, 1], [2, 0, 2], [1e400, 0, 2]]}]}");
  try {
    read_openings(dir.file("openings.json"), SiteFrame{});
    FAIL() << "1e400 accepted";
  } catch (const std::invalid_argument& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("openings.json"), std::string::npos) << m;
    EXPECT_NE(m.find("line 2"), std::string::npos) << m;
    EXPECT_NE(m.find("openings[0].corners[3][0]"), std::string::npos) << m;
  }
  dir.write("openings.json", R"({"openings": [{"corners": [[1, 0, 1], [2, 0, 1], [2, 0, 2], [1e39, 0, 2]]}]})");
  try {
    read_openings(dir.file("openings.json"), SiteFrame{});
    FAIL() << "1e39 accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("opening 0: corner 3"), std::string::npos) << e.what();
  }
}

TEST(Validation, InputsThatAreNotRegularFilesAreRefused) {
  TempDir dir;
  dir.write("scene.json", scene_text());
  std::filesystem::create_directory(dir.file("scene.obj"));
  expect_error(dir, {"scene.obj", "not a regular file"});
  dir.write("scene.json", R"({"fenestra": 1, "geometry": "/dev/zero", "materials": {"a": {}}})");
  expect_error(dir, {"/dev/zero", "not a regular file"});  // read forever before
  EXPECT_THROW(load_scene("/dev/null"), std::invalid_argument);
  EXPECT_THROW(read_openings("/dev/zero", SiteFrame{}), std::invalid_argument);
}

TEST(Validation, ContributionsOfAnotherSceneAreRefused) {
  TempDir dir;
  dir.write("scene.obj", room_obj());
  auto scene = [&](const std::string& sensors) {
    dir.write("scene.json", scene_text(kDomain, sensors));
    Scene s = load_scene(dir.file("scene.json"));
    s.render.paths_per_sensor = 32;
    return s;
  };
  const Scene a = scene(R"({"points": [[2, 1.5, 0.8]], "goals": [0.5]})");
  Contributions c = compute_contributions(a);
  // Counts are always checked, even without the origin.
  const Scene two = scene(R"({"points": [[2, 1.5, 0.8], [1, 1, 1]], "goals": [0.5, 0.5]})");
  try {
    solve_openings(two, c);
    FAIL() << "solved 2 sensors with the contributions of 1";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("1 sensors x 160 elements"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("2 sensors x 160 elements"), std::string::npos) << e.what();
  }
  c.origin = contributions_origin(a);
  const Scene moved = scene(R"({"points": [[2, 1.0, 0.8]], "goals": [0.5]})");
  EXPECT_THROW(solve_openings(moved, c), std::invalid_argument);
  EXPECT_THROW(write_contributions(moved, c, dir.file("c.npz")), std::invalid_argument);
  EXPECT_FALSE(std::filesystem::exists(dir.file("c.npz")));
  EXPECT_FALSE(std::filesystem::exists(dir.file("c.json")));
  const Scene same = scene(R"({"points": [[2, 1.5, 0.8]], "goals": [0.5]})");
  EXPECT_NO_THROW(check_contributions_match(same, c, "solve"));
  Scene other_sky = same;
  dir.write("scene.json", scene_text(kDomain, R"({"points": [[2, 1.5, 0.8]]})", R"({"type": "uniform", "radiance": 50})"));
  other_sky = load_scene(dir.file("scene.json"));
  EXPECT_THROW(check_contributions_match(other_sky, c, "solve"), std::invalid_argument);
}

TEST(Validation, PolarNightIsRefusedBySolveAndWarnedOtherwise) {
  TempDir dir;
  dir.write("scene.obj", room_obj());
  dir.write("scene.json", scene_text(kDomain, R"({"points": [[2, 1.5, 0.8]], "goals": [0.5]})",
                                     R"({"type": "preetham", "latitude": 78, "longitude": 15, "utc_offset": 1,
                                         "date": "2026-12-21", "resolution": [64, 32]})"));
  Scene s = load_scene(dir.file("scene.json"));
  s.render.paths_per_sensor = 16;
  EXPECT_NE(dark_sky_warning(*s.sky, s.daylight.get()).find("below the horizon"), std::string::npos);
  try {
    solve_openings(s);
    FAIL() << "solved under a sky without light";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("2026-12-21"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("78, 15"), std::string::npos) << e.what();
  }
  EXPECT_NE(sky_summary(s).dump().find("warning"), std::string::npos);
  dir.write("scene.json", scene_text(kDomain, R"({"points": [[2, 1.5, 0.8]]})",
                                     R"({"type": "preetham", "latitude": 48, "longitude": 2, "utc_offset": 1,
                                         "date": "2026-06-21", "resolution": [64, 32]})"));
  const Scene lit = load_scene(dir.file("scene.json"));
  EXPECT_EQ(dark_sky_warning(*lit.sky, lit.daylight.get()), "");
}

}  // namespace
}  // namespace fenestra
