#pragma once
// Geometry in float (what Embree consumes), colours as linear-RGB arrays.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>

#include "math/constants.h"

namespace fenestra {

using Vec3 = Eigen::Vector3f;
using Vec2 = Eigen::Vector2f;
using Rgb = Eigen::Array3f;

// Rec. 709 / sRGB luminance weights: sensor values are luminance-weighted irradiance.
inline float luminance(const Rgb& c) { return 0.2126f * c[0] + 0.7152f * c[1] + 0.0722f * c[2]; }

inline bool is_finite(const Vec3& v) { return std::isfinite(v.x()) && std::isfinite(v.y()) && std::isfinite(v.z()); }

// Orthonormal basis around a unit normal (Duff et al. 2017, branchless).
struct Frame {
  Vec3 s, t, n;
  Frame() = default;
  explicit Frame(const Vec3& normal) : n(normal) {
    const float sign = std::copysign(1.0f, n.z());
    const float a = -1.0f / (sign + n.z());
    const float b = n.x() * n.y() * a;
    s = Vec3(1.0f + sign * n.x() * n.x() * a, sign * b, -sign * n.x());
    t = Vec3(b, sign + n.y() * n.y() * a, -n.y());
  }
  Vec3 to_local(const Vec3& v) const { return Vec3(v.dot(s), v.dot(t), v.dot(n)); }
  Vec3 to_world(const Vec3& v) const { return s * v.x() + t * v.y() + n * v.z(); }
};

}  // namespace fenestra
