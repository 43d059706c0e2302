#include "scene/bsdf.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "sampling/ggx.h"
#include "sampling/warp.h"

namespace fenestra {
namespace {

Ggx ggx_of(const Material& m) { return Ggx{std::max(1e-3f, m.roughness * m.roughness)}; }

Rgb specular_f0(const Material& m) { return Rgb::Constant(0.04f) * (1.0f - m.metallic) + m.reflectance * m.metallic; }
Rgb diffuse_albedo(const Material& m) { return m.reflectance * (1.0f - m.metallic); }

Rgb schlick(const Rgb& f0, float cos) {
  const float c = std::clamp(1.0f - cos, 0.0f, 1.0f);
  const float c5 = c * c * c * c * c;
  return f0 + (Rgb::Ones() - f0) * c5;
}

// Probability of choosing the specular lobe of a glossy material.
float specular_probability(const Material& m) {
  const float s = luminance(specular_f0(m));
  const float d = luminance(diffuse_albedo(m));
  if (d <= 0.0f) return 1.0f;
  return std::clamp(s / (s + d), 0.1f, 0.9f);
}

Rgb glossy_eval(const Material& m, const Vec3& wo, const Vec3& wi) {
  if (wo.z() <= 0.0f || wi.z() <= 0.0f) return Rgb::Zero();
  const Ggx ggx = ggx_of(m);
  const Vec3 h = (wo + wi).normalized();
  const Rgb f0 = specular_f0(m);
  const Rgb spec = schlick(f0, wo.dot(h)) * (ggx.D(h) * ggx.G2(wo, wi) / (4.0f * wo.z()));
  // The diffuse base sees only what the specular layer does not reflect: 1 - F at both macro
  // cosines (reciprocal), normalised by 1 - (cosine-weighted mean of F = f0 + (1 - f0) / 21) so its
  // albedo from wo is diffuse_albedo * (1 - F(wo.z)). Adding it to the specular lobe unweighted
  // made white glossy surfaces reflect up to 1.3x the incident energy at grazing incidence. The
  // lobe's own albedo stays below F(wo.z) except at mid angles for roughness 0.15-0.35 (by up to
  // 1.3e-3, facets tilted towards grazing), so only a base colour above ~0.99 can exceed 1.
  const Rgb one = Rgb::Ones();
  const Rgb through = (one - schlick(f0, wo.z())) * (one - schlick(f0, wi.z())) / (one - (f0 + (one - f0) / 21.0f)).max(1e-6f);
  return spec + diffuse_albedo(m) * through * (kInvPi * wi.z());
}

float glossy_pdf(const Material& m, const Vec3& wo, const Vec3& wi) {
  if (wo.z() <= 0.0f || wi.z() <= 0.0f) return 0.0f;
  const float ps = specular_probability(m);
  return ps * ggx_of(m).reflection_pdf(wo, wi) + (1.0f - ps) * square_to_cosine_hemisphere_pdf(wi);
}

}  // namespace

std::string Material::to_string() const {
  std::ostringstream s;
  const char* kind = type == MaterialType::Diffuse ? "diffuse" : type == MaterialType::Glass ? "glass" : "glossy";
  s << "Material('" << name << "', " << kind << ", reflectance=[" << reflectance.transpose() << "]";
  if (type == MaterialType::Glass)
    s << ", transmittance=[" << transmittance.transpose() << "], ior=" << ior << (thin ? ", thin" : ", solid");
  if (type == MaterialType::Glossy) s << ", roughness=" << roughness << ", metallic=" << metallic;
  s << ")";
  return s.str();
}

float fresnel_dielectric(float cos_i, float eta) {
  cos_i = std::clamp(cos_i, 0.0f, 1.0f);
  const float sin2_t = (1.0f - cos_i * cos_i) / (eta * eta);
  if (sin2_t >= 1.0f) return 1.0f;
  const float cos_t = std::sqrt(1.0f - sin2_t);
  const float rs = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
  const float rp = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
  return 0.5f * (rs * rs + rp * rp);
}

namespace {
// Pane of two parallel interfaces with internal transmittance tau along the refracted path.
void thin_pane(const Material& m, float cos_i, Rgb* reflect, Rgb* transmit) {
  cos_i = std::clamp(std::abs(cos_i), 1e-4f, 1.0f);
  const float r = fresnel_dielectric(cos_i, m.ior);
  const float t = 1.0f - r;
  const float sin2_t = (1.0f - cos_i * cos_i) / (m.ior * m.ior);
  const float cos_t = std::sqrt(std::max(1e-6f, 1.0f - sin2_t));
  const Rgb tau = m.internal_transmittance.pow(1.0f / cos_t);
  const Rgb denom = Rgb::Ones() - r * r * tau * tau;
  if (transmit) *transmit = t * t * tau / denom;
  if (reflect) *reflect = r + t * t * r * tau * tau / denom;
}
}  // namespace

Rgb thin_glass_transmittance(const Material& m, float cos_i) {
  Rgb t;
  thin_pane(m, cos_i, nullptr, &t);
  return t;
}

Rgb thin_glass_reflectance(const Material& m, float cos_i) {
  Rgb r;
  thin_pane(m, cos_i, &r, nullptr);
  return r;
}

Rgb thin_glass_internal_transmittance(const Rgb& total, float ior, const std::string& name) {
  const float r = fresnel_dielectric(1.0f, ior);
  const float t2 = (1.0f - r) * (1.0f - r);
  const float max_total = t2 / (1.0f - r * r);
  Rgb tau;
  for (int c = 0; c < 3; ++c) {
    const float T = total[c];
    if (T > max_total + 1e-6f) {
      std::ostringstream s;
      s << "material '" << name << "': glass transmittance " << T << " exceeds " << max_total
        << ", the most a clear pane of ior " << ior << " transmits at normal incidence";
      throw std::invalid_argument(s.str());
    }
    if (T <= 0.0f) {
      tau[c] = 0.0f;
    } else if (r * r * T < 1e-12f) {
      tau[c] = T / t2;
    } else {
      // T r^2 tau^2 + t^2 tau - T = 0, positive root in the form without cancellation
      // ((-t2 + sqrt(...)) / 2a loses all precision for dark panes, T of a few percent).
      const float a = T * r * r;
      tau[c] = 2.0f * T / (t2 + std::sqrt(t2 * t2 + 4.0f * a * T));
    }
    tau[c] = std::clamp(tau[c], 0.0f, 1.0f);
  }
  return tau;
}

Rgb bsdf_eval(const Material& m, const Vec3& wo, const Vec3& wi) {
  switch (m.type) {
    case MaterialType::Diffuse:
      if (wo.z() <= 0.0f || wi.z() <= 0.0f) return Rgb::Zero();
      return m.reflectance * (kInvPi * wi.z());
    case MaterialType::Glossy:
      return glossy_eval(m, wo, wi);
    case MaterialType::Glass:
      return Rgb::Zero();
  }
  return Rgb::Zero();
}

float bsdf_pdf(const Material& m, const Vec3& wo, const Vec3& wi) {
  switch (m.type) {
    case MaterialType::Diffuse:
      return wo.z() > 0.0f ? square_to_cosine_hemisphere_pdf(wi) : 0.0f;
    case MaterialType::Glossy:
      return glossy_pdf(m, wo, wi);
    case MaterialType::Glass:
      return 0.0f;
  }
  return 0.0f;
}

bool bsdf_sample(const Material& m, const Vec3& wo, const Vec2& u, float u_lobe, bool front_face, BsdfSample* out) {
  if (wo.z() <= 0.0f) return false;
  switch (m.type) {
    case MaterialType::Diffuse: {
      out->wi = square_to_cosine_hemisphere(u);
      out->pdf = square_to_cosine_hemisphere_pdf(out->wi);
      if (out->pdf <= 0.0f) return false;
      out->weight = m.reflectance;
      out->specular = out->straight = false;
      return true;
    }
    case MaterialType::Glossy: {
      const Ggx ggx = ggx_of(m);
      if (u_lobe < specular_probability(m)) {
        const Vec3 h = ggx.sample_visible_normal(wo, u);
        out->wi = reflect(wo, h);
      } else {
        out->wi = square_to_cosine_hemisphere(u);
      }
      out->pdf = glossy_pdf(m, wo, out->wi);
      if (out->pdf <= 0.0f) return false;
      out->weight = glossy_eval(m, wo, out->wi) / out->pdf;
      out->specular = out->straight = false;
      return true;
    }
    case MaterialType::Glass: {
      out->pdf = 0.0f;
      out->specular = true;
      if (m.thin) {
        Rgb r, t;
        thin_pane(m, wo.z(), &r, &t);
        const float pr = luminance(r) / std::max(1e-8f, luminance(r) + luminance(t));
        if (u_lobe < pr) {
          out->wi = Vec3(-wo.x(), -wo.y(), wo.z());
          out->weight = r / pr;
          out->straight = false;
        } else {
          out->wi = -wo;
          out->weight = t / (1.0f - pr);
          out->straight = true;
        }
        return true;
      }
      // Solid dielectric: +Z is on the incident side; front_face says whether we enter the body.
      const float eta = front_face ? m.ior : 1.0f / m.ior;
      const float f = fresnel_dielectric(wo.z(), eta);
      out->straight = false;
      if (u_lobe < f) {
        out->wi = Vec3(-wo.x(), -wo.y(), wo.z());
        out->weight = Rgb::Ones();
        return true;
      }
      const float sin2_t = (1.0f - wo.z() * wo.z()) / (eta * eta);
      const float cos_t = std::sqrt(std::max(0.0f, 1.0f - sin2_t));
      out->wi = Vec3(-wo.x() / eta, -wo.y() / eta, -cos_t).normalized();
      out->weight = m.transmittance.sqrt();  // two crossings of a body make `transmittance`
      return true;
    }
  }
  return false;
}

}  // namespace fenestra
