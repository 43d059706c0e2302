#include "scene/constraint_input.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "scene/scene.h"
#include "util/quoted_text.h"

namespace fenestra {

using namespace scene_json;  // the path-aware readers

namespace {

// One list of catalogue sizes: [[width, height], ...] or [{"width": w, "height": h}, ...], meters.
std::vector<CatalogueSize> parse_catalogue_sizes(const ScenePath& sp, const json& j, const std::string& key) {
  constexpr size_t kMaxSizes = 1000;
  constexpr double kMaxSide = 100.0;  // meters
  if (!j.is_array()) sp.fail(key, "expected a list of [width, height] sizes in meters");
  if (j.empty()) sp.fail(key, "is empty: give at least one [width, height] size, or leave the catalogue out");
  if (j.size() > kMaxSizes) sp.fail(key, "has " + std::to_string(j.size()) + " sizes, more than 1000");
  std::vector<CatalogueSize> sizes;
  for (size_t i = 0; i < j.size(); ++i) {
    const std::string at = key + "[" + std::to_string(i) + "]";
    const json& e = j[i];
    CatalogueSize size;
    if (e.is_array() && e.size() == 2) {
      size.width = number(sp, e[0], at + "[0]");
      size.height = number(sp, e[1], at + "[1]");
    } else if (e.is_object()) {
      check_known_keys(sp, e, at, {"width", "height"});
      if (!e.contains("width") || !e.contains("height")) sp.fail(at, "expected {\"width\": w, \"height\": h}");
      size.width = number(sp, e.at("width"), at + ".width");
      size.height = number(sp, e.at("height"), at + ".height");
    } else {
      sp.fail(at, "expected [width, height] in meters");
    }
    for (double side : {size.width, size.height})
      if (!(side > 0.0) || !(side <= kMaxSide))
        sp.fail(at, "sides must be positive lengths up to 100 m, got " + quoted_json(e));
    sizes.push_back(size);
  }
  return sizes;
}

// "catalogue": a built-in's name, a list of sizes (walls and roofs), or {"walls": [...], "roofs": [...]}.
WindowCatalogue parse_catalogue(const ScenePath& sp, const json& j, const std::string& key) {
  if (j.is_string()) {
    try {
      return builtin_catalogue(j.get<std::string>());
    } catch (const std::invalid_argument& e) {
      sp.fail(key, e.what());
    }
  }
  WindowCatalogue c;
  c.name = "custom";
  if (j.is_array()) {
    c.walls = parse_catalogue_sizes(sp, j, key);
    c.roofs = c.walls;
    return c;
  }
  if (!j.is_object()) sp.fail(key, "expected a catalogue's name, a list of [width, height] sizes, or {\"walls\", \"roofs\"}");
  check_known_keys(sp, j, key, {"walls", "roofs"});
  if (j.empty()) sp.fail(key, "is empty: give \"walls\" or \"roofs\" sizes, or leave the catalogue out");
  if (j.contains("walls")) c.walls = parse_catalogue_sizes(sp, j.at("walls"), key + ".walls");
  if (j.contains("roofs")) c.roofs = parse_catalogue_sizes(sp, j.at("roofs"), key + ".roofs");
  return c;
}

}  // namespace

OpeningConstraints parse_constraints(const ScenePath& sp, const json& j, double element_size, const std::string& key,
                                     bool climate) {
  if (!j.is_object()) sp.fail(key, "expected an object");
  check_known_keys(sp, j, key,
                   {"min_area", "max_area", "min_aspect", "max_aspect", "min_width", "max_width", "min_height",
                    "max_height", "max_openings", "min_gap", "margin", "sill_min", "sill_max", "head_min",
                    "head_max", "module", "head_clearance", "max_openings_per_panel", "panel_width_per_opening",
                    "automatic", "full_height", "catalogue", "align_sills", "align_heads", "equal_widths",
                    "same_type_in_row", "symmetric", "equal_spacing", "sill_heights"});
  OpeningConstraints c;
  const std::pair<const char*, double*> values[] = {
      {"min_area", &c.min_area},     {"max_area", &c.max_area},     {"min_aspect", &c.min_aspect},
      {"max_aspect", &c.max_aspect}, {"min_width", &c.min_width},   {"max_width", &c.max_width},
      {"min_height", &c.min_height}, {"max_height", &c.max_height}, {"min_gap", &c.min_gap},
      {"margin", &c.margin},         {"sill_min", &c.sill_min},     {"sill_max", &c.sill_max},
      {"head_min", &c.head_min},     {"head_max", &c.head_max},     {"module", &c.module},
      {"head_clearance", &c.head_clearance}, {"panel_width_per_opening", &c.panel_width_per_opening}};
  for (const auto& [name, value] : values) {
    *value = number_or(sp, j, name, key, *value);
    if (*value < 0.0) sp.fail(key + "." + name, "must not be negative");
  }
  auto whole = [&](const char* name, int* out) {
    if (!j.contains(name)) return;
    const double v = number(sp, j.at(name), key + "." + name);
    if (v != std::floor(v) || v < 0 || v > 1e6) sp.fail(key + "." + name, "expected a whole number from 0 to 10^6");
    *out = static_cast<int>(v);
  };
  whole("max_openings", &c.max_openings);
  whole("max_openings_per_panel", &c.max_openings_per_panel);
  auto flag = [&](const char* name, bool fallback) {
    if (!j.contains(name)) return fallback;
    if (!j.at(name).is_boolean()) sp.fail(key + "." + name, "expected true or false");
    return j.at(name).get<bool>();
  };
  const bool automatic = flag("automatic", true), full_height = flag("full_height", false);
  if (j.contains("catalogue")) c.catalogue = parse_catalogue(sp, j.at("catalogue"), key + ".catalogue");
  c.align_sills = flag("align_sills", false);
  c.align_heads = flag("align_heads", false);
  c.equal_widths = flag("equal_widths", false);
  c.same_type_in_row = flag("same_type_in_row", false);
  c.symmetric = flag("symmetric", false);
  c.equal_spacing = flag("equal_spacing", false);
  if (j.contains("sill_heights")) {
    const json& list = j.at("sill_heights");
    const std::string at = key + ".sill_heights";
    if (!list.is_array() || list.empty()) sp.fail(at, "expected a non-empty list of heights in meters");
    if (list.size() > 100) sp.fail(at, "has more than 100 heights");
    for (size_t i = 0; i < list.size(); ++i) {
      const double h = number(sp, list[i], at + "[" + std::to_string(i) + "]");
      if (!(h >= 0.0) || !(h <= 100.0)) sp.fail(at + "[" + std::to_string(i) + "]", "expected a height from 0 to 100 m");
      c.sill_heights.push_back(h);
    }
  }
  auto feasible = [&](const OpeningConstraints& set) {
    try {
      check_feasible(set, element_size);
      return true;
    } catch (const std::invalid_argument&) {
      return false;
    }
  };
  if (automatic) {
    std::vector<AutomaticConstraint> taken;
    for (const AutomaticConstraint& a : automatic_constraints(full_height, climate)) {
      const bool a_size = std::string(a.key) == "min_width" || std::string(a.key) == "min_height";
      if (!j.contains(a.key) && !(a_size && !c.catalogue.empty())) taken.push_back(a);  // a catalogue sets sizes
    }
    auto with = [&](const std::vector<AutomaticConstraint>& list) {
      OpeningConstraints set = c;
      for (const AutomaticConstraint& a : list) set_constraint(&set, a.key, a.value), set.automatic_keys.push_back(a.key);
      return set;
    };
    // Yield: drop the first automatic value whose absence makes the set feasible, else the last.
    while (!taken.empty() && !feasible(with(taken))) {
      size_t drop = taken.size() - 1;
      for (size_t i = 0; i < taken.size(); ++i) {
        std::vector<AutomaticConstraint> rest = taken;
        rest.erase(rest.begin() + static_cast<std::ptrdiff_t>(i));
        if (feasible(with(rest))) {
          drop = i;
          break;
        }
      }
      taken.erase(taken.begin() + static_cast<std::ptrdiff_t>(drop));
    }
    c = with(taken);
    // Facades whose sills and heads line up, where that costs little light (composition.h).
    if (!full_height && !j.contains("align_sills") && !j.contains("align_heads") && !j.contains("sill_heights"))
      c.align_sills = c.align_heads = c.automatic_alignment = true;
  }
  try {
    check_feasible(c, element_size);
  } catch (const std::invalid_argument& e) {
    sp.fail(key, e.what());
  }
  return c;
}

void apply_panel_constraints(const ScenePath& sp, const json& solver, Scene* scene) {
  if (!solver.is_object() || !solver.contains("panel_constraints")) return;
  const json& list = solver.at("panel_constraints");
  if (!list.is_array()) sp.fail("solver.panel_constraints", "expected a list of {\"materials\", \"groups\", \"constraints\"}");
  const json global = solver.value("constraints", json::object());
  const auto materials = scene->material_names();
  const auto& panels = scene->domain.panels();
  std::vector<OpeningConstraints> per_panel(panels.size(), scene->solver.constraints);
  for (size_t e = 0; e < list.size(); ++e) {
    const std::string key = "solver.panel_constraints[" + std::to_string(e) + "]";
    const json& entry = list[e];
    if (!entry.is_object()) sp.fail(key, "expected an object");
    check_known_keys(sp, entry, key, {"materials", "groups", "constraints"});
    const auto want_materials = names(sp, entry, "materials", key), want_groups = names(sp, entry, "groups", key);
    json merged = global;
    if (entry.contains("constraints")) {
      if (!entry.at("constraints").is_object()) sp.fail(key + ".constraints", "expected an object");
      merged.update(entry.at("constraints"));
    }
    const OpeningConstraints set = parse_constraints(sp, merged, scene->domain.element_size(), key + ".constraints",
                                                     !scene->sensors.climate_goals.empty());
    int matched = 0;
    for (size_t p = 0; p < panels.size(); ++p) {
      bool match = panels[p].material >= 0 &&
                   std::count(want_materials.begin(), want_materials.end(), materials[panels[p].material]) > 0;
      for (uint32_t t : panels[p].triangles) {
        const int g = scene->mesh.triangle_group[t];
        if (g >= 0 && std::count(want_groups.begin(), want_groups.end(), scene->mesh.group_names[g]) > 0) match = true;
      }
      if (match) per_panel[p] = set, ++matched;
    }
    if (matched == 0) sp.fail(key, "matches no panel of the opening domain");
  }
  for (OpeningConstraints& set : per_panel) set.max_openings = scene->solver.constraints.max_openings;
  scene->solver.constraints.per_panel = std::move(per_panel);
}

}  // namespace fenestra
