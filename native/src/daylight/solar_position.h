#pragma once
// Where the sun is, seen from a place on Earth at a UTC instant (apparent topocentric position).
// World directions follow the scene: +Z up, +Y north, +X east.
#include <string>

#include "daylight/local_time.h"
#include "math/vec.h"

namespace fenestra {

struct Place {
  double latitude_deg = 0.0;   // north positive, [-90, 90]
  double longitude_deg = 0.0;  // east positive, [-180, 180]
  double elevation_m = 0.0;    // above sea level
};

// Air at the observer, which sets how much refraction lifts the sun near the horizon.
// The defaults are the standard atmosphere of NREL's Solar Position Algorithm.
struct Atmosphere {
  double pressure_hpa = 1010.0;
  double temperature_c = 10.0;
};

struct SunPosition {
  double zenith_deg = 0.0;   // apparent zenith angle (with refraction when asked), degrees
  double azimuth_deg = 0.0;  // clockwise from north: 0 N, 90 E, 180 S, 270 W, in [0, 360)
};

// `utc_seconds`: seconds since 1970-01-01T00:00:00 UTC (POSIX time). Accurate to 0.05 degrees or
// better against NREL SPA over 1950-2050 (about 0.01 in practice). `refraction`: standard-atmosphere refraction near the horizon.
SunPosition solar_position(double utc_seconds, const Place& place, bool refraction = true);
// The same with refraction through a given atmosphere.
SunPosition solar_position(double utc_seconds, const Place& place, const Atmosphere& atmosphere);

// Unit world direction toward the sun (+Z up, +Y north, +X east).
Vec3 sun_direction(const SunPosition& position);

// The apparent position (standard-atmosphere refraction) in a model whose true north lies
// `north_offset_deg` clockwise from +Y seen from above: the azimuth is turned by the offset, so it
// is measured clockwise from +Y, in [0, 360), and sun_direction() gives the world direction. What
// every daylight sky uses, so that the sky and the sun of one instant agree.
SunPosition model_sun_position(double utc_seconds, const Place& place, double north_offset_deg);

// Delta T = TT - UT in seconds at a decimal year (Espenak & Meeus polynomials), what turns the
// clock time of the Earth's rotation into the uniform time of the planets' motion.
double delta_t_seconds(double decimal_year);

// The sun's daily arc over a local date. Sunrise and sunset are the instants its upper limb meets a
// flat sea-level horizon: geometric centre zenith 90.833 degrees (0.267 semi-diameter plus 0.567 of
// standard refraction), the convention of NOAA's calculator and the USNO tables.
struct SunriseSunset {
  enum Kind {
    Normal,      // the sun rises and sets around this date's solar noon
    PolarDay,    // the sun stays up all day (midnight sun)
    PolarNight,  // the sun stays down all day
  };
  Kind kind = Normal;
  // Local clock minutes after midnight of the date, for the daylight arc through this date's solar
  // noon: sunset exceeds 1440 when the sun sets after local midnight (and sunrise is negative when it
  // rose the evening before). NaN when the arc has no such event: on the one day a polar day begins,
  // the sun rises but does not set within 12 hours of noon; on the day it ends, it sets without
  // having risen. Both are NaN for PolarDay and PolarNight.
  double sunrise_minutes = 0.0;
  double sunset_minutes = 0.0;
  double solar_noon_minutes = 0.0;  // when the sun is highest during the local date

  std::string to_string() const;
};

SunriseSunset sunrise_sunset(const LocalDate& date, const TimeZone& zone, const Place& place);

}  // namespace fenestra
