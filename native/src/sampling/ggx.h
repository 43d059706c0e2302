#pragma once
// GGX (Trowbridge-Reitz) microfacet distribution with visible-normal sampling (Heitz 2018),
// in a local frame with +Z the macro normal. alpha = roughness^2, as in Blender's Principled BSDF.
#include <algorithm>
#include <cmath>

#include "math/vec.h"

namespace fenestra {

struct Ggx {
  float alpha;

  float D(const Vec3& h) const {
    if (h.z() <= 0.0f) return 0.0f;
    const float a2 = alpha * alpha;
    const float c2 = h.z() * h.z();
    // c2 (a2 - 1) + 1 with 1 - c2 = sin^2 taken from x and y: near the peak the usual form
    // cancels catastrophically (6e-8 / a2 relative error: 6% at the smallest alpha, 1e-3).
    const float d = c2 * a2 + (h.x() * h.x() + h.y() * h.y());
    return a2 / (kPi * d * d);
  }
  float lambda(const Vec3& w) const {
    const float c2 = w.z() * w.z();
    if (c2 <= 0.0f) return 0.0f;
    const float tan2 = std::max(0.0f, 1.0f - c2) / c2;
    return 0.5f * (-1.0f + std::sqrt(1.0f + alpha * alpha * tan2));
  }
  float G1(const Vec3& w) const { return 1.0f / (1.0f + lambda(w)); }
  float G2(const Vec3& wo, const Vec3& wi) const { return 1.0f / (1.0f + lambda(wo) + lambda(wi)); }

  // Visible normal h for a view direction wo (wo.z > 0).
  Vec3 sample_visible_normal(const Vec3& wo, const Vec2& u) const {
    const Vec3 vh = Vec3(alpha * wo.x(), alpha * wo.y(), wo.z()).normalized();
    const float lensq = vh.x() * vh.x() + vh.y() * vh.y();
    const Vec3 t1 = lensq > 0.0f ? Vec3(-vh.y(), vh.x(), 0.0f) / std::sqrt(lensq) : Vec3(1.0f, 0.0f, 0.0f);
    const Vec3 t2 = vh.cross(t1);
    const float r = std::sqrt(u.x());
    const float phi = 2.0f * kPi * u.y();
    const float p1 = r * std::cos(phi);
    const float s = 0.5f * (1.0f + vh.z());
    const float p2 = (1.0f - s) * std::sqrt(std::max(0.0f, 1.0f - p1 * p1)) + s * r * std::sin(phi);
    const Vec3 nh = p1 * t1 + p2 * t2 + std::sqrt(std::max(0.0f, 1.0f - p1 * p1 - p2 * p2)) * vh;
    return Vec3(alpha * nh.x(), alpha * nh.y(), std::max(1e-7f, nh.z())).normalized();
  }
  // Density of h from sample_visible_normal.
  float visible_normal_pdf(const Vec3& wo, const Vec3& h) const {
    if (wo.z() <= 0.0f) return 0.0f;
    return G1(wo) * std::max(0.0f, wo.dot(h)) * D(h) / wo.z();
  }
  // Density of the reflected direction wi = reflect(wo, h), in solid angle.
  float reflection_pdf(const Vec3& wo, const Vec3& wi) const {
    if (wo.z() <= 0.0f || wi.z() <= 0.0f) return 0.0f;
    const Vec3 h = (wo + wi).normalized();
    const float wo_h = wo.dot(h);
    if (wo_h <= 0.0f) return 0.0f;
    return visible_normal_pdf(wo, h) / (4.0f * wo_h);
  }
};

inline Vec3 reflect(const Vec3& wo, const Vec3& n) { return 2.0f * wo.dot(n) * n - wo; }

}  // namespace fenestra
