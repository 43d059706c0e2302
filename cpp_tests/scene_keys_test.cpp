// Typos and malformed input in the scene, OBJ and openings files: refused, naming the file, the
// key (or line) and, for a key, the closest known one; never read with the defaults.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "io/results.h"
#include "io/solve_result.h"
#include "scene/climate_goals.h"
#include "solve/solver.h"
#include "test_scenes.h"

namespace fenestra {
namespace {

using nlohmann::json;
using test::ObjBuilder;
using test::TempDir;

std::string room_obj() {
  ObjBuilder obj;
  obj.box({0, 0, 0}, {4, 3, 2.6f}, [](const std::string& f) { return f == "south" ? "facade" : "wall"; });
  return obj.str();
}

// A scene with every section and most nested objects.
json full_scene() {
  return json::parse(R"({
    "fenestra": 1, "geometry": "scene.obj",
    "materials": {"wall": {"type": "diffuse", "reflectance": 0.5}, "facade": {"reflectance": 0.5},
                  "pane": {"type": "glass", "transmittance": 0.8, "ior": 1.5, "kind": "thin"},
                  "steel": {"type": "glossy", "reflectance": 0.5, "roughness": 0.3, "metallic": 0.5}},
    "opening_domain": {"materials": ["facade"], "element_size": 0.5, "thickness": 0},
    "sensors": {"points": [[2, 1.5, 0.8]], "normals": [0, 0, 1], "goals": [0.3], "goal_units": "normalized",
                "weights": [1]},
    "goals": {"uniform": [{"sensors": "all", "level": 0.3, "min": 0, "max": 1}]},
    "sky": {"type": "uniform", "radiance": 100, "ground_radiance": 50},
    "render": {"paths_per_sensor": 16, "max_bounces": 2, "seed": 1, "threads": 1, "sampler": "sobol"},
    "solver": {"paths": 16, "population": 8, "generations": 2,
               "shape_weights": {"isolated": 1, "boundary": 1, "regions": 1},
               "constraints": {"min_width": 0.5, "catalogue": {"walls": [[1, 1], {"width": 1, "height": 1.5}]}},
               "panel_constraints": [{"materials": ["facade"], "constraints": {"max_openings": 2}}]}
  })");
}

// The message of loading `scene` (scene.json beside room_obj()), or "" when it loads.
std::string load_error(const json& scene, const std::string& obj = room_obj()) {
  TempDir dir;
  dir.write("scene.obj", obj);
  dir.write("scene.json", scene.dump());
  try {
    load_scene(dir.file("scene.json"));
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

// `scene` with the key at `pointer` renamed to `typo`.
json with_typo(json scene, const std::string& pointer, const std::string& typo) {
  const json::json_pointer at(pointer);
  json& parent = scene.at(at.parent_pointer());
  const json value = parent.at(at.back());
  parent.erase(at.back());
  parent[typo] = value;
  return scene;
}

TEST(SceneKeys, TheFullSceneLoads) { EXPECT_EQ(load_error(full_scene()), ""); }

TEST(SceneKeys, ATypoAtAnyLevelIsRefusedWithTheClosestKey) {
  struct Case {
    const char* pointer;
    const char* typo;
    const char* path;  // in the message
    const char* known;
  };
  const Case cases[] = {
      {"/render", "rendr", "rendr", "render"},
      {"/opening_domain/element_size", "element_sise", "opening_domain.element_sise", "element_size"},
      {"/opening_domain/thickness", "thicknes", "opening_domain.thicknes", "thickness"},
      {"/materials/wall/reflectance", "reflectence", "materials.wall.reflectence", "reflectance"},
      {"/materials/facade/reflectance", "Reflectance", "materials.facade.Reflectance", "reflectance"},
      {"/materials/pane/transmittance", "transmitance", "materials.pane.transmitance", "transmittance"},
      {"/materials/steel/roughness", "roughnes", "materials.steel.roughnes", "roughness"},
      {"/sensors/normals", "normal", "sensors.normal", "normals"},
      {"/sensors/goal_units", "goal_unit", "sensors.goal_unit", "goal_units"},
      {"/goals/uniform/0/level", "levle", "goals.uniform[0].levle", "level"},
      {"/sky/ground_radiance", "ground_radience", "sky.ground_radience", "ground_radiance"},
      {"/render/max_bounces", "max_bounce", "render.max_bounce", "max_bounces"},
      {"/solver/population", "populaton", "solver.populaton", "population"},
      {"/solver/shape_weights/regions", "region", "solver.shape_weights.region", "regions"},
      {"/solver/constraints/min_width", "min_widht", "solver.constraints.min_widht", "min_width"},
      {"/solver/constraints/catalogue/walls", "wals", "solver.constraints.catalogue.wals", "walls"},
      {"/solver/constraints/catalogue/walls/1/height", "heigth", "solver.constraints.catalogue.walls[1].heigth",
       "height"},
      {"/solver/panel_constraints/0/materials", "material", "solver.panel_constraints[0].material", "materials"},
      {"/solver/panel_constraints/0/constraints/max_openings", "max_opening",
       "solver.panel_constraints[0].constraints.max_opening", "max_openings"},
  };
  for (const Case& c : cases) {
    const std::string m = load_error(with_typo(full_scene(), c.pointer, c.typo));
    EXPECT_NE(m.find("scene '"), std::string::npos) << c.pointer << ": " << m;
    EXPECT_NE(m.find(std::string(c.path) + ": unknown key; did you mean `" + c.known + "`? (known: "),
              std::string::npos)
        << c.pointer << ": " << m;
  }
}

TEST(SceneKeys, KeysOfAnotherTypeOrNoneAtAllAreRefused) {
  json scene = full_scene();
  scene["materials"]["pane"]["reflectance"] = 0.1;  // read by glossy and diffuse, not by glass
  EXPECT_NE(load_error(scene).find("materials.pane.reflectance: unknown key"), std::string::npos) << load_error(scene);
  scene = full_scene();
  scene["comment"] = "mine";
  EXPECT_NE(load_error(scene).find("comment: unknown key; (known: fenestra, geometry"), std::string::npos)
      << load_error(scene);
  scene = full_scene();
  scene["sky"] = json::parse(R"({"type": "cie_overcast", "horizontal_iluminance": 1000, "resolution": [16, 8]})");
  EXPECT_NE(load_error(scene).find("sky.horizontal_iluminance: unknown key; did you mean `horizontal_illuminance`?"),
            std::string::npos)
      << load_error(scene);
  scene["sky"] = json::parse(R"({"type": "preethem"})");
  EXPECT_NE(load_error(scene).find("sky.type: unknown sky type 'preethem' (did you mean `preetham`?)"),
            std::string::npos)
      << load_error(scene);
  scene = full_scene();
  scene["materials"]["wall"]["type"] = "difuse";
  EXPECT_NE(load_error(scene).find("(did you mean `diffuse`?)"), std::string::npos) << load_error(scene);
  // A typo'd key echoes at most about 80 characters of itself.
  scene = full_scene();
  scene["render"][std::string(100000, 'k')] = 1;
  EXPECT_LT(load_error(scene).size(), 1000u);
}

TEST(SceneKeys, ClimateGoalKeysAndMetricsSuggestTheClosest) {
  auto error = [](const std::string& goals) {
    try {
      parse_climate_goals(json::parse(goals), json::parse(R"({"back": [0]})"), 2, "x.json");
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(error(R"({"climate": [{"metric": "sda", "illuminance": 300}]})")
                .find("goals.climate[0].illuminance: unknown key; did you mean `illuminance_lux`?"),
            std::string::npos);
  EXPECT_NE(error(R"({"climate": [{"metric": "sdaa"}]})").find("did you mean `sda`?"), std::string::npos);
  EXPECT_NE(error(R"({"climate": [{"metric": "sda", "sensors": "bakc"}]})").find("did you mean `back`?"),
            std::string::npos);
}

TEST(SceneKeys, DuplicateKeysAreRefusedWithTheirLine) {
  TempDir dir;
  dir.write("scene.obj", room_obj());
  std::string text = full_scene().dump(1);
  const std::size_t at = text.find("\"radiance\": 100");
  ASSERT_NE(at, std::string::npos);
  text.insert(at, "\"radiance\": 5,\n");
  dir.write("scene.json", text);
  const auto line_of = [&](std::size_t offset) { return 1 + std::count(text.begin(), text.begin() + offset, '\n'); };
  try {
    load_scene(dir.file("scene.json"));
    FAIL() << "a duplicate key accepted (the last one won)";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("scene.json', line " + std::to_string(line_of(at) + 1) +
                                         ": sky.radiance: the key is given twice (first on line " +
                                         std::to_string(line_of(at)) + ")"),
              std::string::npos)
        << e.what();
  }
}

TEST(SceneKeys, PathsWithANulByteAreRefused) {
  json scene = full_scene();
  scene["geometry"] = std::string("scene.obj\0x", 11);  // loaded scene.obj
  EXPECT_NE(load_error(scene).find("geometry: geometry file"), std::string::npos) << load_error(scene);
  EXPECT_NE(load_error(scene).find("scene.obj\\u0000x': the file name holds a NUL byte"), std::string::npos);
  scene = full_scene();
  scene["sky"] = {{"type", "envmap"}, {"file", std::string("sky.exr\0", 8)}};
  EXPECT_NE(load_error(scene).find("sky.file: environment map"), std::string::npos) << load_error(scene);
  EXPECT_NE(load_error(scene).find("NUL byte"), std::string::npos) << load_error(scene);
  EXPECT_THROW(load_scene(std::string("scene.json\0x", 12)), std::invalid_argument);
  EXPECT_THROW(read_openings(std::string("o.json\0x", 8), SiteFrame{}), std::invalid_argument);
}

TEST(ObjLines, FacesNeedThreeCornersAndNumbersTheDecimalForm) {
  const std::string room = room_obj();
  const auto next = std::to_string(std::count(room.begin(), room.end(), '\n') + 2);  // after "usemtl wall"
  const std::pair<const char*, const char*> cases[] = {
      {"f\n", "a face needs at least 3 corners, got 0"},
      {"f 1\n", "a face needs at least 3 corners, got 1"},
      {"f 1 2\n", "a face needs at least 3 corners, got 2"},
      {"v 0x10 0 0\n", "vertex coordinate '0x10' is not a finite decimal number"},
      {"v inf 0 0\n", "'inf' is not a finite decimal number"},
      {"v 1e 0 0\n", "'1e' is not a finite decimal number"},
      {"v 1 2\n", "a `v` line needs 3 numbers, got 2"},
      {"vt 0x1 0\n", "texture coordinate (vt) '0x1'"},
      {"vn nan 0 1\n", "normal (vn) component 'nan'"},
      {"f 1/2/3/4 2 3\n", "face corner '1/2/3/4' is not v, v/vt, v//vn or v/vt/vn"},
  };
  for (const auto& [line, words] : cases) {
    const std::string m = load_error(full_scene(), room + "usemtl wall\n" + line);
    EXPECT_NE(m.find("scene.obj', line " + next + ": "), std::string::npos) << line << m;
    EXPECT_NE(m.find(words), std::string::npos) << line << m;
  }
  // Lines and points light nothing: read past (tinyobjloader refused "l 0 1" with its own words).
  EXPECT_EQ(load_error(full_scene(), room + "l 0 1\np 1\nl 1 2\n"), "");
}

void expect_openings_error(const std::string& text, const std::string& words) {
  TempDir dir;
  dir.write("o.json", text);
  try {
    read_openings(dir.file("o.json"), SiteFrame{});
    ADD_FAILURE() << "accepted: " << text;
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("o.json"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
  }
}

TEST(OpeningsKeys, UnknownAndDuplicateKeysAreRefused) {
  const std::string corners = "[[1, 0, 1], [2, 0, 1], [2, 0, 2], [1, 0, 2]]";
  expect_openings_error(R"({"openings": [{"corner": )" + corners + "}]}",
                        "opening 0: corner: unknown key; did you mean `corners`?");
  expect_openings_error(R"({"opening": [{"corners": )" + corners + "}]}",
                        "opening: unknown key; did you mean `openings`?");
  expect_openings_error(R"({"openings": [{"panel": 0, "parameter_rectangle": {"u0": 0, "u1": 1, "v0": 0, "v_1": 1}}]})",
                        "opening 0: parameter_rectangle.v_1: unknown key; did you mean `v1`?");
  expect_openings_error(R"({"openings": [{"corners": )" + corners + R"(, "paramter_rectangle": {}}]})",
                        "did you mean `parameter_rectangle`?");
  expect_openings_error("{\"openings\": [],\n\"openings\": []}", "line 2: openings: the key is given twice");
}

TEST(OpeningsKeys, ASolveResultIsAnOpeningsFile) {
  TempDir dir;
  dir.write("scene.obj", room_obj());
  dir.write("scene.json", full_scene().dump());
  const Scene scene = load_scene(dir.file("scene.json"));
  SolveResult r;
  OpeningRectangle o;
  o.corners = {Vec3(1, 0, 1), Vec3(2, 0, 1), Vec3(2, 0, 2), Vec3(1, 0, 2)};
  o.curved = true;  // with its surface grid
  o.grid_rows = o.grid_columns = 1;
  o.grid_points = o.grid_normals = {Vec3(1, 0, 1)};
  r.openings = {o};
  json result = solve_result_json(scene, r);
  result["climate"] = json::object();  // written with climate goals
  EXPECT_EQ(parse_openings(result, "result.json", SiteFrame{}).size(), 1u);
}

}  // namespace
}  // namespace fenestra
