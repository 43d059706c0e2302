#pragma once
// Square-to-direction warps as (sample, pdf, inverse) triplets, in a local frame with +Z the normal.
#include <algorithm>
#include <cmath>

#include "math/vec.h"

namespace fenestra {

inline Vec2 square_to_uniform_disk_concentric(const Vec2& u) {
  const float ox = 2.0f * u.x() - 1.0f, oy = 2.0f * u.y() - 1.0f;
  if (ox == 0.0f && oy == 0.0f) return Vec2(0.0f, 0.0f);
  float r, theta;
  if (std::abs(ox) > std::abs(oy)) {
    r = ox;
    theta = (kPi / 4.0f) * (oy / ox);
  } else {
    r = oy;
    theta = (kPi / 2.0f) - (kPi / 4.0f) * (ox / oy);
  }
  return Vec2(r * std::cos(theta), r * std::sin(theta));
}

inline Vec2 uniform_disk_concentric_to_square(const Vec2& p) {
  const float r = std::sqrt(p.x() * p.x() + p.y() * p.y());
  float phi = std::atan2(p.y(), p.x());
  if (phi < -kPi / 4.0f) phi += 2.0f * kPi;
  float a, b;
  if (phi < kPi / 4.0f) {
    a = r;
    b = phi * a / (kPi / 4.0f);
  } else if (phi < 3.0f * kPi / 4.0f) {
    b = r;
    a = -(phi - kPi / 2.0f) * b / (kPi / 4.0f);
  } else if (phi < 5.0f * kPi / 4.0f) {
    a = -r;
    b = (phi - kPi) * a / (kPi / 4.0f);
  } else {
    b = -r;
    a = -(phi - 3.0f * kPi / 2.0f) * b / (kPi / 4.0f);
  }
  return Vec2(0.5f * (a + 1.0f), 0.5f * (b + 1.0f));
}

// Cosine-weighted hemisphere (Malley's method), pdf = cos(theta) / pi.
inline Vec3 square_to_cosine_hemisphere(const Vec2& u) {
  const Vec2 d = square_to_uniform_disk_concentric(u);
  const float z = std::sqrt(std::max(0.0f, 1.0f - d.squaredNorm()));
  return Vec3(d.x(), d.y(), z);
}
inline float square_to_cosine_hemisphere_pdf(const Vec3& v) { return v.z() > 0.0f ? v.z() * kInvPi : 0.0f; }
inline Vec2 cosine_hemisphere_to_square(const Vec3& v) { return uniform_disk_concentric_to_square(Vec2(v.x(), v.y())); }

// Uniform sphere, pdf = 1 / (4 pi).
inline Vec3 square_to_uniform_sphere(const Vec2& u) {
  const float z = 1.0f - 2.0f * u.x();
  const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
  const float phi = 2.0f * kPi * u.y();
  return Vec3(r * std::cos(phi), r * std::sin(phi), z);
}
inline float square_to_uniform_sphere_pdf(const Vec3&) { return 1.0f / (4.0f * kPi); }
inline Vec2 uniform_sphere_to_square(const Vec3& v) {
  float phi = std::atan2(v.y(), v.x());
  if (phi < 0.0f) phi += 2.0f * kPi;
  return Vec2((1.0f - v.z()) * 0.5f, phi / (2.0f * kPi));
}

// Linear density on [0, 1] from a at 0 to b at 1 (a, b >= 0, not both 0): inverts its CDF.
inline float square_to_linear(float u, float a, float b) {
  if (a == b) return u;
  const float x = u * (a + b) / (a + std::sqrt((1.0f - u) * a * a + u * b * b));
  return std::min(x, 0.99999994f);
}
inline float linear_pdf(float x, float a, float b) { return 2.0f * ((1.0f - x) * a + x * b) / (a + b); }

// Bilinear density on the unit square with corner weights w = {w00, w10, w01, w11} (w_xy >= 0, sum
// > 0): the marginal in y, then the conditional in x (Hart et al. 2020, "Practical Product Sampling
// by Fitting and Composing Warps"). Composed with an area-preserving warp, it follows a smooth
// factor such as a receiver's cosine.
inline Vec2 square_to_bilinear(const Vec2& u, const float w[4]) {
  const float y = square_to_linear(u.y(), w[0] + w[1], w[2] + w[3]);
  const float x = square_to_linear(u.x(), (1.0f - y) * w[0] + y * w[2], (1.0f - y) * w[1] + y * w[3]);
  return Vec2(x, y);
}
inline float bilinear_pdf(const Vec2& p, const float w[4]) {
  const float sum = w[0] + w[1] + w[2] + w[3];
  return 4.0f *
         ((1.0f - p.x()) * (1.0f - p.y()) * w[0] + p.x() * (1.0f - p.y()) * w[1] + (1.0f - p.x()) * p.y() * w[2] +
          p.x() * p.y() * w[3]) /
         sum;
}

}  // namespace fenestra
