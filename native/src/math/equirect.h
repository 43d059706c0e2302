#pragma once
// Blender's equirectangular projection, shared by environment maps and the daylight skies built
// into them: map coordinates uv in [0,1)^2 (u across, v down from the zenith) to the world
// direction they show, +Z up; u = 0.5 looks along +X, u = 0.25 along +Y.
#include <cmath>

#include "math/vec.h"

namespace fenestra {

inline Vec3 equirect_direction(const Vec2& uv) {
  const float theta = uv.y() * kPi;
  const float phi = (0.5f - uv.x()) * 2.0f * kPi;
  const float st = std::sin(theta);
  return Vec3(st * std::cos(phi), st * std::sin(phi), std::cos(theta));
}

}  // namespace fenestra
