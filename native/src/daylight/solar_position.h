#pragma once
// Where the sun is, seen from a place on Earth at a UTC instant (apparent topocentric position).
// World directions follow the scene: +Z up, +Y north, +X east.
#include "math/vec.h"

namespace fenestra {

struct Place {
  double latitude_deg = 0.0;   // north positive, [-90, 90]
  double longitude_deg = 0.0;  // east positive, [-180, 180]
  double elevation_m = 0.0;    // above sea level
};

struct SunPosition {
  double zenith_deg = 0.0;   // apparent zenith angle (with refraction when asked), degrees
  double azimuth_deg = 0.0;  // clockwise from north: 0 N, 90 E, 180 S, 270 W, in [0, 360)
};

// `utc_seconds`: seconds since 1970-01-01T00:00:00 UTC (POSIX time). Accurate to 0.05 degrees or
// better against NREL SPA over 1950-2050. `refraction`: standard-atmosphere refraction near the horizon.
SunPosition solar_position(double utc_seconds, const Place& place, bool refraction = true);

// Unit world direction toward the sun (+Z up, +Y north, +X east).
Vec3 sun_direction(const SunPosition& position);

}  // namespace fenestra
