#pragma once
// A box-shaped cutter: a rectangle on a panel extruded along the panel normal.
// Surfaces of the scene inside a cutter are removed; reveal faces are never cut.
#include <vector>

#include "math/vec.h"

namespace fenestra {

struct CutterBox {
  Vec3 origin;                 // a corner of the rectangle
  Vec3 u_axis, v_axis, normal;  // orthonormal
  float width = 0, height = 0;  // rectangle extent along u and v (meters)
  float depth_back = 0, depth_front = 0;  // extent along -normal and along +normal from the plane

  bool contains(const Vec3& p) const {
    const Vec3 d = p - origin;
    const float a = d.dot(u_axis), b = d.dot(v_axis), c = d.dot(normal);
    return a > 0.0f && a < width && b > 0.0f && b < height && c > -depth_back && c < depth_front;
  }
};

using CutterSet = std::vector<CutterBox>;

inline bool any_contains(const CutterSet& cutters, const Vec3& p) {
  for (const auto& c : cutters)
    if (c.contains(p)) return true;
  return false;
}

}  // namespace fenestra
