#pragma once
// The sun of one time step of a daylight sky, kept apart from the sky's map as an explicit
// directional source (daylight/sun_lights.h samples a list of them).
#include <algorithm>
#include <vector>

#include "math/vec.h"

namespace fenestra {

struct SunLight {
  Vec3 direction;            // unit, toward the sun's centre (+Z up, +Y north, +X east)
  Rgb normal_illuminance;    // lux on a surface facing the sun, times the step's share of the interval
  double weight = 1.0;       // the step's share of the interval (normal_illuminance / weight: the instant's)
  double utc_seconds = 0.0;  // the step's instant (POSIX seconds)
  double zenith_deg = 0.0, azimuth_deg = 0.0;  // apparent position (azimuth clockwise from north)
};

// Illuminance of a list of suns on an unobstructed horizontal surface (lux per channel).
inline Rgb horizontal_illuminance(const std::vector<SunLight>& suns) {
  Rgb e = Rgb::Zero();
  for (const SunLight& s : suns) e += s.normal_illuminance * std::max(0.0f, s.direction.z());
  return e;
}

}  // namespace fenestra
