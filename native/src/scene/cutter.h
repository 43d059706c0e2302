#pragma once
// What an opening removes from the scene. On a flat panel, a box: a rectangle on the panel extruded
// along its normal, which removes every surface inside it (the domain's face and, through a thick
// wall, its outer face). On a curved panel (single surfaces only), a rectangle of the panel's chart,
// which removes the surface points whose chart point lies in it. Reveal faces are never cut.
#include <cstdint>
#include <vector>

#include "math/vec.h"
#include "scene/surface_chart.h"

namespace fenestra {

struct Cutter {
  Vec3 origin;                 // a corner of the rectangle
  Vec3 u_axis, v_axis, normal;  // orthonormal
  float width = 0, height = 0;  // rectangle extent along u and v (meters)
  float depth_back = 0, depth_front = 0;  // extent along -normal and along +normal from the plane
  const SurfaceChart* chart = nullptr;    // set: a chart rectangle, (origin, width, height) unused
  float u0 = 0, u1 = 0, v0 = 0, v1 = 0;   // the chart rectangle, meters

  // Whether the box holds p (a chart rectangle holds no point off its surface).
  bool contains(const Vec3& p) const {
    if (chart) return false;
    const Vec3 d = p - origin;
    const float a = d.dot(u_axis), b = d.dot(v_axis), c = d.dot(normal);
    return a > 0.0f && a < width && b > 0.0f && b < height && c > -depth_back && c < depth_front;
  }
  // Whether p, a point of scene triangle `triangle`, is cut away.
  bool cuts(const Vec3& p, uint32_t triangle) const {
    if (!chart) return contains(p);
    if (!chart->holds(triangle)) return false;
    const Vec2 q = chart->chart_point(triangle, p);
    return q.x() > u0 && q.x() < u1 && q.y() > v0 && q.y() < v1;
  }
};

using CutterSet = std::vector<Cutter>;

inline bool any_contains(const CutterSet& cutters, const Vec3& p) {
  for (const auto& c : cutters)
    if (c.contains(p)) return true;
  return false;
}

inline bool any_cuts(const CutterSet& cutters, const Vec3& p, uint32_t triangle) {
  for (const auto& c : cutters)
    if (c.cuts(p, triangle)) return true;
  return false;
}

}  // namespace fenestra
