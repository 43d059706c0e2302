#include "trace/opening_portals.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "math/constants.h"
#include "sampling/spherical_rectangle.h"

namespace fenestra {
namespace {

// Meters: a point nearer a portal's plane than this sees it edge-on (and may lie on it).
constexpr float kMinDepth = 1e-4f;
// Steradians: a portal seen smaller than this is left to BSDF and sky sampling (its solid angle's
// formula loses precision, and it carries little light).
constexpr float kMinSolidAngle = 1e-5f;
// The receiver's cosine toward a portal's centre, floored: part of a portal low on the horizon
// may still face the receiver.
constexpr float kCosineFloor = 0.05f;

}  // namespace

OpeningPortals::OpeningPortals(const CutterSet& openings) {
  for (const Cutter& c : openings) {
    if (c.chart || !(c.width > 0.0f && c.height > 0.0f)) continue;
    Portal p;
    p.corner = c.origin;
    p.unit_u = c.u_axis;
    p.unit_v = c.v_axis;
    p.width = c.width;
    p.height = c.height;
    p.u = c.width * c.u_axis;
    p.v = c.height * c.v_axis;
    p.outward = c.normal;  // cutter normals point out through the wall
    p.centre = c.origin + 0.5f * (p.u + p.v);
    p.area = c.width * c.height;
    portals_.push_back(p);
  }
}

float OpeningPortals::weight(const Portal& p, const Vec3& x, const Vec3& n) {
  const float depth = (x - p.corner).dot(p.outward);
  if (!(depth < -kMinDepth)) return 0.0f;
  const Vec3 to_centre = p.centre - x;
  const float distance2 = to_centre.squaredNorm();
  const float inverse_distance = 1.0f / std::sqrt(distance2);
  const float facing = -depth * inverse_distance;  // the portal's cosine toward x, from its centre
  const float solid_angle = std::min(2.0f * kPi, p.area * std::max(facing, kCosineFloor) / distance2);
  if (!(solid_angle >= kMinSolidAngle)) return 0.0f;
  const float cosine = std::max(0.0f, n.dot(to_centre) * inverse_distance);
  return solid_angle * (cosine + kCosineFloor);
}

OpeningPortals::From::From(const OpeningPortals& portals, const Vec3& x, const Vec3& n)
    : portals_(portals), x_(x), n_(n) {
  const size_t count = portals.portals_.size();
  if (count > inline_.size()) spilled_.resize(count - inline_.size());
  for (size_t k = 0; k < count; ++k) {
    const float w = OpeningPortals::weight(portals.portals_[k], x, n);
    (k < inline_.size() ? inline_[k] : spilled_[k - inline_.size()]) = w;
    total_ += w;
  }
}

float OpeningPortals::From::crossing_density(size_t k, const Vec3& dir, float reach) const {
  const float w = weight(k);
  if (!(w > 0.0f)) return 0.0f;
  const Portal& p = portals_.portals_[k];
  const float along = dir.dot(p.outward);
  if (!(along > 0.0f)) return 0.0f;
  const float t = -(x_ - p.corner).dot(p.outward) / along;
  if (!(t < reach)) return 0.0f;
  const Vec3 on = x_ + t * dir - p.corner;
  const float a = on.dot(p.unit_u), b = on.dot(p.unit_v);
  if (a < 0.0f || a > p.width || b < 0.0f || b > p.height) return 0.0f;
  const double solid_angle = rectangle_solid_angle(x_, p.corner, p.u, p.v);
  return solid_angle > 0.0 ? w / static_cast<float>(solid_angle) : 0.0f;
}

float OpeningPortals::From::pdf(const Vec3& dir, float reach) const {
  if (!any()) return 0.0f;
  float density = 0.0f;
  for (size_t k = 0; k < portals_.portals_.size(); ++k) density += crossing_density(k, dir, reach);
  return density / total_;
}

bool OpeningPortals::From::sample(float u_pick, const Vec2& uv, Sample* out) const {
  if (!any()) return false;
  const float target = u_pick * total_;
  float running = 0.0f;
  size_t picked = 0;
  for (size_t k = 0; k < portals_.portals_.size(); ++k) {
    const float w = weight(k);
    if (!(w > 0.0f)) continue;
    picked = k;
    running += w;
    if (target < running) break;
  }
  const Portal& p = portals_.portals_[picked];
  const SphericalRectangle seen(x_, p.corner, p.u, p.v);
  if (!(seen.solid_angle() > 0.0)) return false;
  const Vec3 to = seen.sample(uv) - x_;
  const float distance = to.norm();
  if (!(distance > 0.0f)) return false;
  out->direction = to / distance;
  out->distance = distance;
  // The density: the drawn portal's from the solid angle just computed, any other's it crosses as
  // pdf() finds them.
  float density = weight(picked) / static_cast<float>(seen.solid_angle());
  for (size_t k = 0; k < portals_.portals_.size(); ++k)
    if (k != picked) density += crossing_density(k, out->direction, std::numeric_limits<float>::infinity());
  out->pdf = density / total_;
  return true;
}

}  // namespace fenestra
