#pragma once
// Materials Fenestra traces: what Blender's Principled BSDF maps onto.
#include <string>

#include "math/vec.h"

namespace fenestra {

enum class MaterialType { Diffuse, Glass, Glossy };

struct Material {
  std::string name;
  MaterialType type = MaterialType::Diffuse;
  Rgb reflectance = Rgb::Constant(0.5f);  // diffuse albedo, or base colour of glossy
  // Glass: `transmittance` is the pane's total transmittance at normal incidence (thin)
  // or the body's transmittance per crossing (solid); `internal_transmittance` is derived.
  Rgb transmittance = Rgb::Constant(0.8f);
  Rgb internal_transmittance = Rgb::Ones();
  float ior = 1.52f;
  bool thin = true;
  float roughness = 0.5f;  // glossy: GGX alpha = roughness^2
  float metallic = 0.0f;

  bool is_glass() const { return type == MaterialType::Glass; }
  bool is_thin_glass() const { return type == MaterialType::Glass && thin; }
  std::string to_string() const;
};

}  // namespace fenestra
