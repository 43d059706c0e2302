// The scene file read whole: each section by the reader beside its concept, in an order that
// refuses cheap mistakes before the costly sky is built.
#include <nlohmann/json.hpp>

#include <filesystem>
#include <stdexcept>

#include "format/json_input.h"
#include "scene/constraint_input.h"
#include "scene/input_limits.h"
#include "scene/material_input.h"
#include "scene/scene.h"
#include "scene/scene_json.h"
#include "scene/sensor_input.h"
#include "scene/settings_input.h"
#include "scene/sky_input.h"
#include "util/quoted_text.h"
#include "util/whole_file.h"

namespace fenestra {

using namespace scene_json;  // the path-aware readers
namespace fs = std::filesystem;

Scene parse_scene(const std::string& text, const std::string& base_dir, const std::string& source_name,
                  Progress* progress) {
  const ScenePath sp(source_name);
  const json j = parse_json_text(text, "scene", source_name);
  if (!j.is_object()) sp.fail("(top level)", "expected a JSON object");
  // Compared as a double: an integer such as 4294967297 must not wrap to 1.
  const bool version_1 = j.contains("fenestra") && j.at("fenestra").is_number_integer() &&
                         j.at("fenestra").get<double>() == 1.0;
  auto fail_version = [&] {
    sp.fail("fenestra", "expected the format version 1 (\"fenestra\": 1), got " +
                            (j.contains("fenestra") ? quoted_json(j.at("fenestra")) : std::string("nothing")));
  };
  if (j.contains("fenestra") && !version_1) fail_version();  // another version may have other keys
  check_known_keys(sp, j, "",
                   {"fenestra", "geometry", "materials", "opening_domain", "sensors", "goals", "sky", "render",
                    "solver"});
  if (!version_1) fail_version();

  Scene scene;
  scene.source = source_name;
  const fs::path base(base_dir);
  try {
    if (!j.contains("materials") || !j.at("materials").is_object() || j.at("materials").empty())
      sp.fail("materials", "the scene defines no materials");
    for (const auto& [name, m] : j.at("materials").items()) scene.materials.push_back(parse_material(sp, name, m));

    if (!j.contains("geometry") || !j.at("geometry").is_string()) sp.fail("geometry", "expected the OBJ file name");
    try {
      scene.mesh = load_obj((base / j.at("geometry").get<std::string>()).string(), scene.material_names(), &scene.site);
      scene.input_files.push_back((base / j.at("geometry").get<std::string>()).string());
    } catch (const std::invalid_argument& e) {
      sp.fail("geometry", e.what());
    }

    if (!j.contains("opening_domain") || !j.at("opening_domain").is_object())
      sp.fail("opening_domain", "expected an object naming the materials or groups that may host openings");
    const json& od = j.at("opening_domain");
    check_known_keys(sp, od, "opening_domain", {"materials", "groups", "element_size", "thickness"});
    OpeningDomainSelection sel;
    sel.materials = names(sp, od, "materials", "opening_domain");
    sel.groups = names(sp, od, "groups", "opening_domain");
    sel.element_size = static_cast<float>(number_or(sp, od, "element_size", "opening_domain", 0.25));
    // The solver's element size, when given, is the one the domain is diced with.
    if (j.contains("solver") && j.at("solver").is_object() && j.at("solver").contains("element_size"))
      sel.element_size = static_cast<float>(number(sp, j.at("solver").at("element_size"), "solver.element_size"));
    if (od.contains("thickness"))
      sel.thickness =
          static_cast<float>(number_in(sp, od, "thickness", "opening_domain", 0.0, 0.0, limits::kMaxThickness, " m"));
    sel.site = scene.site;
    try {
      scene.domain = OpeningDomain::build(scene.mesh, scene.material_names(), sel);
    } catch (const std::invalid_argument& e) {
      sp.fail("opening_domain", e.what());
    }

    if (!j.contains("sensors")) sp.fail("sensors", "the scene has no sensors");
    scene.sensors = parse_sensors(sp, j.at("sensors"), scene.site);
    scene.domain.orient(scene.sensors.points);
    try {
      scene.domain.build_walls(&scene.mesh);
    } catch (const std::invalid_argument& e) {
      sp.fail("opening_domain", e.what());
    }
    parse_goals(sp, j.value("goals", json()), &scene.sensors);
    check_goals(sp, scene.sensors);
    // No "sky" at all: the default uniform sky; a "sky" must name its type.
    // Before the sky: a climate sky takes seconds to build, a bad goal should not wait for it.
    scene.sensors.climate_goals = parse_climate_goals(j.value("goals", json()), j.at("sensors").value("groups", json()),
                                                      scene.sensors.size(), sp.source());
    parse_sky(sp, j.contains("sky") ? j.at("sky") : json{{"type", "uniform"}}, base, &scene, progress);
    if (!scene.sensors.climate_goals.empty() && !scene.climate)
      sp.fail("goals.climate", "climate goals need a sky of type \"climate\" (a weather file)");
    scene.render = parse_render(sp, j.value("render", json()));
    scene.solver = parse_solver(sp, j.value("solver", json()));
    const json solver = j.value("solver", json());
    const json given = solver.is_object() ? solver.value("constraints", json::object()) : json::object();
    scene.solver.constraints = parse_constraints(sp, given, scene.domain.element_size(), "solver.constraints",
                                                 !scene.sensors.climate_goals.empty());
    apply_panel_constraints(sp, j.value("solver", json()), &scene);
    const std::string no_fit = catalogue_fit_problem(scene.domain, scene.solver.constraints);
    if (!no_fit.empty()) sp.fail("solver.constraints.catalogue", no_fit);
    const std::string no_facade = composition_problem(scene.domain, scene.solver.constraints);
    if (!no_facade.empty()) sp.fail("solver.constraints", no_facade);
  } catch (const json::exception& e) {
    sp.fail("(structure)", "a value has the wrong type: " + json_error_text(e));
  }
  return scene;
}

Scene load_scene(const std::string& path, Progress* progress) {
  check_input_file(path, "scene file", limits::kMaxSceneFileBytes);
  const std::string text = read_whole_file(path, "scene file");
  const fs::path p(path);
  Scene scene = parse_scene(text, p.parent_path().string().empty() ? "." : p.parent_path().string(), path, progress);
  scene.input_files.insert(scene.input_files.begin(), path);
  return scene;
}

}  // namespace fenestra
