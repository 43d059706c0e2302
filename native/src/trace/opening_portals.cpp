#include "trace/opening_portals.h"

#include <algorithm>
#include <cmath>

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

float OpeningPortals::weight(const Portal& p, const Vec3& x, const Vec3& n) const {
  const float depth = (x - p.corner).dot(p.outward);
  if (!(depth < -kMinDepth)) return 0.0f;
  const Vec3 to_centre = p.centre - x;
  const float distance2 = to_centre.squaredNorm();
  const float distance = std::sqrt(distance2);
  const float facing = -depth / distance;  // the portal's cosine toward x, from its centre
  const float solid_angle = std::min(2.0f * kPi, p.area * std::max(facing, kCosineFloor) / distance2);
  if (!(solid_angle >= kMinSolidAngle)) return 0.0f;
  const float cosine = std::max(0.0f, n.dot(to_centre) / distance);
  return solid_angle * (cosine + kCosineFloor);
}

bool OpeningPortals::candidates(const Vec3& x, const Vec3& n) const {
  for (const Portal& p : portals_)
    if (weight(p, x, n) > 0.0f) return true;
  return false;
}

bool OpeningPortals::sample(const Vec3& x, const Vec3& n, float u_pick, const Vec2& uv, Sample* out) const {
  float total = 0.0f;
  for (const Portal& p : portals_) total += weight(p, x, n);
  if (!(total > 0.0f)) return false;
  const float target = u_pick * total;
  float running = 0.0f;
  const Portal* picked = nullptr;
  for (const Portal& p : portals_) {
    const float w = weight(p, x, n);
    if (!(w > 0.0f)) continue;
    picked = &p;
    running += w;
    if (target < running) break;
  }
  const SphericalRectangle seen(x, picked->corner, picked->u, picked->v);
  if (!(seen.solid_angle() > 0.0)) return false;
  const Vec3 to = seen.sample(uv) - x;
  const float distance = to.norm();
  if (!(distance > 0.0f)) return false;
  out->direction = to / distance;
  out->distance = distance;
  return true;
}

float OpeningPortals::pdf(const Vec3& x, const Vec3& n, const Vec3& dir, float reach, bool* candidates) const {
  float total = 0.0f, density = 0.0f;
  for (const Portal& p : portals_) {
    const float w = weight(p, x, n);
    if (!(w > 0.0f)) continue;
    total += w;
    const float along = dir.dot(p.outward);
    if (!(along > 0.0f)) continue;
    const float t = -(x - p.corner).dot(p.outward) / along;
    if (!(t < reach)) continue;
    const Vec3 on = x + t * dir - p.corner;
    const float a = on.dot(p.unit_u), b = on.dot(p.unit_v);
    if (a < 0.0f || a > p.width || b < 0.0f || b > p.height) continue;
    const double solid_angle = rectangle_solid_angle(x, p.corner, p.u, p.v);
    if (solid_angle > 0.0) density += w / static_cast<float>(solid_angle);
  }
  if (candidates) *candidates = total > 0.0f;
  return total > 0.0f ? density / total : 0.0f;
}

}  // namespace fenestra
