#pragma once
// BSDF evaluation and sampling in the shading frame (+Z the normal on the side of wo).
// Values are f * |cos(wi)|; sampled weights are f * |cos(wi)| / pdf.
#include "math/vec.h"
#include "scene/material.h"

namespace fenestra {

struct BsdfSample {
  Vec3 wi;
  Rgb weight;
  float pdf = 0.0f;       // solid-angle density; 0 for delta lobes
  bool specular = false;  // delta lobe: next-event estimation cannot reach this direction
  bool straight = false;  // thin-glass transmission: direction unchanged, light sampling still valid
};

Rgb bsdf_eval(const Material& m, const Vec3& wo, const Vec3& wi);
float bsdf_pdf(const Material& m, const Vec3& wo, const Vec3& wi);
// front_face: wo is on the side the geometric normal points to (entering a solid dielectric).
bool bsdf_sample(const Material& m, const Vec3& wo, const Vec2& u, float u_lobe, bool front_face, BsdfSample* out);

// Unpolarised Fresnel reflectance of a dielectric interface; eta = n_transmitted / n_incident.
float fresnel_dielectric(float cos_i, float eta);
// Straight-through transmittance of a thin pane (both interfaces and the body) at incidence cosine.
Rgb thin_glass_transmittance(const Material& m, float cos_i);
Rgb thin_glass_reflectance(const Material& m, float cos_i);
// Internal transmittance giving a thin pane the total normal-incidence transmittance T
// (throws if T exceeds what a clear pane of that ior can transmit).
Rgb thin_glass_internal_transmittance(const Rgb& total, float ior, const std::string& material_name);

}  // namespace fenestra
