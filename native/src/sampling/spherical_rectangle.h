#pragma once
// Uniform sampling of the solid angle a rectangle subtends from a point (Urena, Fajardo and King
// 2013, "An Area-Preserving Parametrization for Spherical Rectangles"). A point near a window
// element sees it under a strongly varying 1/d^2 and cosine: area sampling then leaves most of
// the estimator's variance in geometry, solid-angle sampling leaves only the radiance and the
// receiver's cosine. The map from [0, 1)^2 is continuous and area preserving, so stratified
// points stay stratified in solid angle.
#include <algorithm>
#include <cmath>

#include "math/vec.h"

namespace fenestra {

// The solid angle alone (Van Oosterom and Strackee 1983, over the rectangle's two triangles):
// cheaper than building a SphericalRectangle, for densities of directions already drawn. Agrees
// with SphericalRectangle::solid_angle() to rounding, so that both sides of a threshold match.
inline double triangle_solid_angle(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const double la = a.norm(), lb = b.norm(), lc = c.norm();
  const double numerator = std::abs(a.dot(b.cross(c)));
  const double denominator = la * lb * lc + a.dot(b) * lc + a.dot(c) * lb + b.dot(c) * la;
  double omega = 2.0 * std::atan2(numerator, denominator);
  return omega < 0.0 ? omega + 2.0 * M_PI : omega;
}
inline double rectangle_solid_angle(const Vec3& from, const Vec3& corner, const Vec3& u, const Vec3& v) {
  const Eigen::Vector3d a = corner.cast<double>() - from.cast<double>();
  const Eigen::Vector3d b = a + u.cast<double>(), d = a + v.cast<double>(), c = b + v.cast<double>();
  return triangle_solid_angle(a, b, c) + triangle_solid_angle(a, c, d);
}

class SphericalRectangle {
 public:
  // The rectangle corner + s * u + t * v (s, t in [0, 1]) seen from `from`. Computed in double:
  // the solid angle is a small difference of angles near 2 pi for a far rectangle.
  SphericalRectangle(const Vec3& from, const Vec3& corner, const Vec3& u, const Vec3& v) {
    const Eigen::Vector3d o = from.cast<double>(), c = corner.cast<double>();
    const Eigen::Vector3d ud = u.cast<double>(), vd = v.cast<double>();
    length_u_ = ud.norm();
    length_v_ = vd.norm();
    x_axis_ = ud / length_u_;
    y_axis_ = vd / length_v_;
    z_axis_ = x_axis_.cross(y_axis_);
    origin_ = o;
    const Eigen::Vector3d d = c - o;
    x0_ = d.dot(x_axis_);
    y0_ = d.dot(y_axis_);
    z0_ = d.dot(z_axis_);
    if (z0_ > 0.0) {  // the rectangle's plane below the local origin: z points toward it
      z_axis_ = -z_axis_;
      z0_ = -z0_;
    }
    x1_ = x0_ + length_u_;
    y1_ = y0_ + length_v_;
    if (!(z0_ < 0.0)) return;  // `from` lies in the rectangle's plane: no solid angle
    // Normals of the planes through `from` and each edge, and the rectangle's internal angles.
    const Eigen::Vector3d v00(x0_, y0_, z0_), v01(x0_, y1_, z0_), v10(x1_, y0_, z0_), v11(x1_, y1_, z0_);
    n0_ = v00.cross(v10).normalized();
    const Eigen::Vector3d n1 = v10.cross(v11).normalized();
    n2_ = v11.cross(v01).normalized();
    const Eigen::Vector3d n3 = v01.cross(v00).normalized();
    auto angle = [](const Eigen::Vector3d& a, const Eigen::Vector3d& b) { return std::acos(std::clamp(-a.dot(b), -1.0, 1.0)); };
    g0_ = angle(n0_, n1);
    g1_ = angle(n1, n2_);
    g2_ = angle(n2_, n3);
    g3_ = angle(n3, n0_);
    solid_angle_ = g0_ + g1_ + g2_ + g3_ - 2.0 * M_PI;
  }

  // Steradians; 0 when seen edge-on.
  double solid_angle() const { return solid_angle_ > 0.0 ? solid_angle_ : 0.0; }

  // The point of the rectangle in direction sample u, uniform in solid angle (density
  // 1 / solid_angle()); valid when solid_angle() > 0.
  Vec3 sample(const Vec2& u) const {
    const double b0 = n0_.z(), b1 = n2_.z();
    // The azimuth of the sample's edge plane, then the x where that plane meets the rectangle.
    const double au = u.x() * (g0_ + g1_ - 2.0 * M_PI) + (u.x() - 1.0) * (g2_ + g3_);
    const double fu = (std::cos(au) * b0 - b1) / std::sin(au);
    double cu = std::copysign(1.0 / std::sqrt(fu * fu + b0 * b0), fu);
    cu = std::clamp(cu, -1.0 + 1e-12, 1.0 - 1e-12);
    double xu = -(cu * z0_) / std::sqrt(std::max(0.0, 1.0 - cu * cu));
    xu = std::clamp(xu, x0_, x1_);
    // Along y: uniform in the sine of the elevation above the plane y = 0.
    const double d = std::sqrt(xu * xu + z0_ * z0_);
    const double h0 = y0_ / std::sqrt(d * d + y0_ * y0_), h1 = y1_ / std::sqrt(d * d + y1_ * y1_);
    const double hv = h0 + u.y() * (h1 - h0), hv2 = hv * hv;
    const double yv = hv2 < 1.0 - 1e-12 ? std::clamp(hv * d / std::sqrt(1.0 - hv2), y0_, y1_) : y1_;
    return (origin_ + xu * x_axis_ + yv * y_axis_ + z0_ * z_axis_).cast<float>();
  }

 private:
  Eigen::Vector3d origin_, x_axis_, y_axis_, z_axis_;
  Eigen::Vector3d n0_ = Eigen::Vector3d::Zero(), n2_ = Eigen::Vector3d::Zero();
  double length_u_ = 0.0, length_v_ = 0.0;
  double x0_ = 0.0, y0_ = 0.0, z0_ = 0.0, x1_ = 0.0, y1_ = 0.0;
  double g0_ = 0.0, g1_ = 0.0, g2_ = 0.0, g3_ = 0.0, solid_angle_ = 0.0;
};

}  // namespace fenestra
