#include "scene/material_input.h"

#include <nlohmann/json.hpp>

#include <stdexcept>

#include "format/json_keys.h"
#include "scene/bsdf.h"
#include "util/quoted_text.h"

namespace fenestra {

using namespace scene_json;  // the path-aware readers

Material parse_material(const ScenePath& sp, const std::string& name, const json& j) {
  const std::string key = "materials." + quoted_text(name);
  if (!j.is_object()) sp.fail(key, "expected an object");
  Material m;
  m.name = name;
  check_misspelt(sp, j, key, "type");
  const std::string type = text_or(sp, j, "type", key, "diffuse");
  if (type == "diffuse") check_known_keys(sp, j, key, {"type", "reflectance"});
  if (type == "glossy") check_known_keys(sp, j, key, {"type", "reflectance", "roughness", "metallic"});
  if (type == "glass") check_known_keys(sp, j, key, {"type", "transmittance", "ior", "kind"});
  if (j.contains("reflectance")) m.reflectance = colour(sp, j.at("reflectance"), key + ".reflectance");
  if (type == "diffuse") {
    m.type = MaterialType::Diffuse;
    check_range(sp, m.reflectance, 0.0f, 1.0f, key + ".reflectance");
  } else if (type == "glossy") {
    m.type = MaterialType::Glossy;
    check_range(sp, m.reflectance, 0.0f, 1.0f, key + ".reflectance");
    m.roughness = static_cast<float>(number_or(sp, j, "roughness", key, 0.5));
    m.metallic = static_cast<float>(number_or(sp, j, "metallic", key, 0.0));
    if (m.roughness < 0 || m.roughness > 1) sp.fail(key + ".roughness", "must lie in [0, 1]");
    if (m.metallic < 0 || m.metallic > 1) sp.fail(key + ".metallic", "must lie in [0, 1]");
  } else if (type == "glass") {
    m.type = MaterialType::Glass;
    if (j.contains("transmittance")) m.transmittance = colour(sp, j.at("transmittance"), key + ".transmittance");
    check_range(sp, m.transmittance, 0.0f, 1.0f, key + ".transmittance");
    m.ior = static_cast<float>(number_or(sp, j, "ior", key, 1.52));
    if (!(m.ior >= 1.0f && m.ior <= 4.0f)) sp.fail(key + ".ior", "must lie in [1, 4]");
    const std::string kind = text_or(sp, j, "kind", key, "thin");
    if (kind != "thin" && kind != "solid") sp.fail(key + ".kind", "must be \"thin\" or \"solid\"");
    m.thin = kind == "thin";
    if (m.thin) {
      try {
        m.internal_transmittance = thin_glass_internal_transmittance(m.transmittance, m.ior, name);
      } catch (const std::invalid_argument& e) {
        sp.fail(key + ".transmittance", e.what());
      }
    }
  } else {
    sp.fail(key + ".type", "unknown material type '" + quoted_text(type) + "'" +
                               did_you_mean(type, {"diffuse", "glass", "glossy"}) + " (diffuse, glass or glossy)");
  }
  return m;
}

}  // namespace fenestra
