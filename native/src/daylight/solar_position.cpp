// Solar position after Jean Meeus, "Astronomical Algorithms" (2nd ed., 1998): the sun's geometric
// longitude from ch. 25, nutation and obliquity from ch. 22, apparent sidereal time from ch. 12,
// parallax from ch. 11 and 40, and the refraction of ch. 16 (Saemundsson), corrected for the
// atmosphere as NREL's Solar Position Algorithm (Reda & Andreas 2004) does.
#include "daylight/solar_position.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "math/constants.h"

namespace fenestra {

namespace {

constexpr double kRad = kPiD / 180.0;  // radians per degree
constexpr double kArcsec = 1.0 / 3600.0;  // degrees per arc second
constexpr double kJ2000Unix = 946728000.0;  // 2000-01-01T12:00:00 (JD 2451545.0), POSIX seconds
constexpr double kDaysPerCentury = 36525.0;

// The sun's upper limb touches the horizon at this geometric zenith of its centre (degrees).
constexpr double kSunSemidiameterDeg = 0.26667;
constexpr double kHorizonRefractionDeg = 0.5667;
constexpr double kRiseSetZenithDeg = 90.0 + kSunSemidiameterDeg + kHorizonRefractionDeg;

double wrap_360(double deg) {
  const double r = std::fmod(deg, 360.0);
  return r < 0.0 ? r + 360.0 : r;
}

// Nutation in longitude and obliquity, arc seconds (Meeus ch. 22, the four largest terms: 0.5" in
// longitude and 0.1" in obliquity).
struct Nutation {
  double longitude_arcsec, obliquity_arcsec;
};

Nutation nutation(double T) {
  const double moon_node = (125.04452 - 1934.136261 * T + 0.0020708 * T * T + T * T * T / 450000.0) * kRad;
  const double sun_mean_longitude = (280.4665 + 36000.7698 * T) * kRad;
  const double moon_mean_longitude = (218.3165 + 481267.8813 * T) * kRad;
  return {-17.20 * std::sin(moon_node) - 1.32 * std::sin(2 * sun_mean_longitude) -
              0.23 * std::sin(2 * moon_mean_longitude) + 0.21 * std::sin(2 * moon_node),
          9.20 * std::cos(moon_node) + 0.57 * std::cos(2 * sun_mean_longitude) +
              0.10 * std::cos(2 * moon_mean_longitude) - 0.09 * std::cos(2 * moon_node)};
}

// Mean obliquity of the ecliptic, degrees (Meeus 22.2, IAU 1976).
double mean_obliquity_deg(double T) {
  return 23.0 + 26.0 / 60.0 + (21.448 - 46.8150 * T - 0.00059 * T * T + 0.001813 * T * T * T) * kArcsec;
}

// The sun as seen from the Earth's centre, in the true equator and equinox of date.
struct GeocentricSun {
  double right_ascension;       // radians
  double declination;           // radians
  double distance_au;
  double equation_of_equinoxes_deg;  // nutation seen along the equator: apparent minus mean sidereal time
};

// `T`: Julian centuries of terrestrial time since J2000.0.
GeocentricSun geocentric_sun(double T) {
  // Geometric longitude and distance referred to the mean equinox of date (Meeus ch. 25, 0.01 deg).
  const double mean_longitude = 280.46646 + 36000.76983 * T + 0.0003032 * T * T;
  const double mean_anomaly = (357.52911 + 35999.05029 * T - 0.0001537 * T * T) * kRad;
  const double eccentricity = 0.016708634 - 0.000042037 * T - 0.0000001267 * T * T;
  const double equation_of_centre = (1.914602 - 0.004817 * T - 0.000014 * T * T) * std::sin(mean_anomaly) +
                                    (0.019993 - 0.000101 * T) * std::sin(2 * mean_anomaly) +
                                    0.000289 * std::sin(3 * mean_anomaly);
  const double true_longitude = mean_longitude + equation_of_centre;
  const double true_anomaly = mean_anomaly + equation_of_centre * kRad;
  const double distance = 1.000001018 * (1 - eccentricity * eccentricity) / (1 + eccentricity * std::cos(true_anomaly));

  // Apparent longitude: add nutation, and the aberration of the light's 8-minute travel.
  const Nutation n = nutation(T);
  const double aberration_deg = -20.4898 * kArcsec / distance;
  const double longitude = (true_longitude + n.longitude_arcsec * kArcsec + aberration_deg) * kRad;
  const double obliquity = (mean_obliquity_deg(T) + n.obliquity_arcsec * kArcsec) * kRad;

  // Ecliptic to equatorial; the sun's ecliptic latitude (under 1.2") is neglected.
  GeocentricSun sun;
  sun.right_ascension = std::atan2(std::cos(obliquity) * std::sin(longitude), std::cos(longitude));
  sun.declination = std::asin(std::sin(obliquity) * std::sin(longitude));
  sun.distance_au = distance;
  sun.equation_of_equinoxes_deg = n.longitude_arcsec * kArcsec * std::cos(obliquity);
  return sun;
}

// Greenwich mean sidereal time, degrees (Meeus 12.4); `days` since J2000.0 in universal time.
double greenwich_mean_sidereal_deg(double days) {
  const double T = days / kDaysPerCentury;
  return wrap_360(280.46061837 + 360.98564736629 * days + 0.000387933 * T * T - T * T * T / 38710000.0);
}

// Right ascension and declination as seen from the observer rather than the Earth's centre: the
// parallax of the sun is at most 8.8" (Meeus 40.2-40.3, observer on the IAU 1976 ellipsoid, ch. 11).
struct Topocentric {
  double hour_angle, declination;  // radians
};

Topocentric topocentric(double hour_angle, double declination, double distance_au, const Place& place) {
  constexpr double kPolarOverEquatorial = 0.99664719;  // b / a of the Earth's ellipsoid
  constexpr double kEquatorialRadiusM = 6378140.0;
  const double latitude = place.latitude_deg * kRad;
  const double u = std::atan(kPolarOverEquatorial * std::tan(latitude));
  const double height = place.elevation_m / kEquatorialRadiusM;
  const double rho_sin = kPolarOverEquatorial * std::sin(u) + height * std::sin(latitude);
  const double rho_cos = std::cos(u) + height * std::cos(latitude);
  const double sin_parallax = std::sin(8.794 * kArcsec * kRad) / distance_au;

  const double denominator = std::cos(declination) - rho_cos * sin_parallax * std::cos(hour_angle);
  const double delta_ra = std::atan2(-rho_cos * sin_parallax * std::sin(hour_angle), denominator);
  const double dec = std::atan2((std::sin(declination) - rho_sin * sin_parallax) * std::cos(delta_ra), denominator);
  return {hour_angle - delta_ra, dec};
}

// How much the air lifts the sun at a true (airless) elevation, degrees: Saemundsson's formula
// (Meeus 16.4) scaled for pressure and temperature. Like NREL's SPA, none once the sun's upper limb
// is below the standard horizon, where the formula no longer holds.
double refraction_deg(double true_elevation_deg, const Atmosphere& air) {
  if (true_elevation_deg < -(kSunSemidiameterDeg + kHorizonRefractionDeg)) return 0.0;
  const double h = true_elevation_deg;
  const double arcmin = 1.02 / std::tan((h + 10.3 / (h + 5.11)) * kRad);
  return (air.pressure_hpa / 1010.0) * (283.0 / (273.0 + air.temperature_c)) * arcmin / 60.0;
}

void check(const Place& place) {
  if (!(std::abs(place.latitude_deg) <= 90.0) || !std::isfinite(place.longitude_deg) ||
      !std::isfinite(place.elevation_m))
    throw std::invalid_argument("place (latitude " + std::to_string(place.latitude_deg) + ", longitude " +
                                std::to_string(place.longitude_deg) +
                                "): latitude must lie in [-90, 90] and all values be finite");
}

SunPosition position(double utc_seconds, const Place& place, const Atmosphere* air) {
  if (!std::isfinite(utc_seconds)) throw std::invalid_argument("solar position: the instant is not finite");
  check(place);
  // Universal time (UTC within a second) turns the Earth; terrestrial time moves the sun.
  const double days_ut = (utc_seconds - kJ2000Unix) / 86400.0;
  const double days_tt = days_ut + delta_t_seconds(2000.0 + days_ut / 365.25) / 86400.0;
  const GeocentricSun sun = geocentric_sun(days_tt / kDaysPerCentury);

  const double sidereal_deg = greenwich_mean_sidereal_deg(days_ut) + sun.equation_of_equinoxes_deg;
  const double hour_angle = (sidereal_deg + place.longitude_deg) * kRad - sun.right_ascension;
  const Topocentric seen = topocentric(hour_angle, sun.declination, sun.distance_au, place);

  // Equatorial to horizon coordinates; azimuth clockwise from north.
  const double latitude = place.latitude_deg * kRad;
  const double sin_elevation = std::sin(latitude) * std::sin(seen.declination) +
                               std::cos(latitude) * std::cos(seen.declination) * std::cos(seen.hour_angle);
  double elevation_deg = std::asin(std::max(-1.0, std::min(1.0, sin_elevation))) / kRad;
  const double azimuth = std::atan2(-std::cos(seen.declination) * std::sin(seen.hour_angle),
                                    std::sin(seen.declination) * std::cos(latitude) -
                                        std::cos(seen.declination) * std::cos(seen.hour_angle) * std::sin(latitude));
  if (air) elevation_deg += refraction_deg(elevation_deg, *air);

  SunPosition p;
  p.zenith_deg = 90.0 - elevation_deg;
  p.azimuth_deg = wrap_360(azimuth / kRad);
  return p;
}

}  // namespace

double delta_t_seconds(double y) {
  // Espenak & Meeus, "Five Millennium Canon of Solar Eclipses" (NASA/TP-2006-214141), fitted to
  // observed Delta T up to 2005 and extrapolated after; the long-term parabola outside 1800-2150.
  if (y >= 2050.0 && y < 2150.0) {
    const double u = (y - 1820.0) / 100.0;
    return -20.0 + 32.0 * u * u - 0.5628 * (2150.0 - y);
  }
  if (y >= 2005.0 && y < 2050.0) {
    const double t = y - 2000.0;
    return 62.92 + 0.32217 * t + 0.005589 * t * t;
  }
  if (y >= 1986.0 && y < 2005.0) {
    const double t = y - 2000.0;
    return 63.86 + t * (0.3345 + t * (-0.060374 + t * (0.0017275 + t * (0.000651814 + t * 0.00002373599))));
  }
  if (y >= 1961.0 && y < 1986.0) {
    const double t = y - 1975.0;
    return 45.45 + 1.067 * t - t * t / 260.0 - t * t * t / 718.0;
  }
  if (y >= 1941.0 && y < 1961.0) {
    const double t = y - 1950.0;
    return 29.07 + 0.407 * t - t * t / 233.0 + t * t * t / 2547.0;
  }
  if (y >= 1920.0 && y < 1941.0) {
    const double t = y - 1920.0;
    return 21.20 + t * (0.84493 + t * (-0.076100 + t * 0.0020936));
  }
  if (y >= 1900.0 && y < 1920.0) {
    const double t = y - 1900.0;
    return -2.79 + t * (1.494119 + t * (-0.0598939 + t * (0.0061966 - t * 0.000197)));
  }
  if (y >= 1860.0 && y < 1900.0) {
    const double t = y - 1860.0;
    return 7.62 + t * (0.5737 + t * (-0.251754 + t * (0.01680668 + t * (-0.0004473624 + t / 233174.0))));
  }
  if (y >= 1800.0 && y < 1860.0) {
    const double t = y - 1800.0;
    return 13.72 + t * (-0.332447 + t * (0.0068612 + t * (0.0041116 + t * (-0.00037436 +
                        t * (0.0000121272 + t * (-0.0000001699 + t * 0.000000000875))))));
  }
  const double u = (y - 1820.0) / 100.0;
  return -20.0 + 32.0 * u * u;
}

SunPosition solar_position(double utc_seconds, const Place& place, bool refraction) {
  const Atmosphere standard;
  return position(utc_seconds, place, refraction ? &standard : nullptr);
}

SunPosition solar_position(double utc_seconds, const Place& place, const Atmosphere& atmosphere) {
  if (!(atmosphere.pressure_hpa >= 0.0) || !(atmosphere.temperature_c > -273.0))
    throw std::invalid_argument("atmosphere: pressure " + std::to_string(atmosphere.pressure_hpa) +
                                " hPa and temperature " + std::to_string(atmosphere.temperature_c) +
                                " C are not physical");
  return position(utc_seconds, place, &atmosphere);
}

Vec3 sun_direction(const SunPosition& p) {
  const double zenith = p.zenith_deg * kRad, azimuth = p.azimuth_deg * kRad;
  return Vec3(static_cast<float>(std::sin(zenith) * std::sin(azimuth)),
              static_cast<float>(std::sin(zenith) * std::cos(azimuth)), static_cast<float>(std::cos(zenith)));
}

SunPosition model_sun_position(double utc_seconds, const Place& place, double north_offset_deg) {
  SunPosition p = solar_position(utc_seconds, place, true);
  const double turned = std::fmod(p.azimuth_deg + north_offset_deg, 360.0);
  p.azimuth_deg = turned < 0.0 ? turned + 360.0 : turned;
  if (p.azimuth_deg >= 360.0) p.azimuth_deg = 0.0;  // -1e-17 + 360 rounds to 360
  return p;
}

// ---- Sunrise and sunset ----

namespace {

constexpr double kSampleSeconds = 600.0;       // coarse step: the sun's zenith is smooth over minutes
constexpr double kHalfArcSeconds = 12.5 * 3600.0;  // noon to the next lower culmination, with margin
constexpr double kRootSeconds = 0.01;

// The instant within [lo, hi] where the geometric zenith is least (the sun highest).
template <class Zenith>
double highest_instant(const Zenith& zenith, double lo, double hi) {
  double best = lo, best_zenith = zenith(lo);
  for (double t = lo + kSampleSeconds; t < hi + kSampleSeconds; t += kSampleSeconds) {
    const double clamped = std::min(t, hi), z = zenith(clamped);
    if (z < best_zenith) best = clamped, best_zenith = z;
  }
  // Golden-section refinement between the neighbours of the best sample.
  double a = std::max(lo, best - kSampleSeconds), b = std::min(hi, best + kSampleSeconds);
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  while (b - a > 1.0) {
    const double c = b - g * (b - a), d = a + g * (b - a);
    if (zenith(c) < zenith(d))
      b = d;
    else
      a = c;
  }
  return 0.5 * (a + b);
}

// Walks from `noon` by `direction` (-1 back toward sunrise, +1 on toward sunset) until the sun is
// below the rise/set zenith, then bisects; NaN when it stays up for the whole half arc.
template <class Zenith>
double horizon_crossing(const Zenith& zenith, double noon, int direction) {
  double up = noon;
  for (double step = kSampleSeconds; step <= kHalfArcSeconds + 0.5 * kSampleSeconds; step += kSampleSeconds) {
    double down = noon + direction * step;
    if (zenith(down) <= kRiseSetZenithDeg) {
      up = down;
      continue;
    }
    while (std::abs(down - up) > kRootSeconds) {
      const double mid = 0.5 * (up + down);
      if (zenith(mid) <= kRiseSetZenithDeg)
        up = mid;
      else
        down = mid;
    }
    return 0.5 * (up + down);
  }
  return std::numeric_limits<double>::quiet_NaN();
}

}  // namespace

SunriseSunset sunrise_sunset(const LocalDate& date, const TimeZone& zone, const Place& place) {
  check(place);
  const auto zenith = [&](double t) { return solar_position(t, place, false).zenith_deg; };
  const double day_start = zone.utc_seconds(date, 0.0), day_end = zone.utc_seconds(date, 1440.0);
  const double noon = highest_instant(zenith, day_start, day_end);

  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  SunriseSunset s;
  s.solar_noon_minutes = zone.local_minutes(date, noon);
  s.sunrise_minutes = s.sunset_minutes = nan;
  if (zenith(noon) > kRiseSetZenithDeg) {
    s.kind = SunriseSunset::PolarNight;
    return s;
  }
  const double rise = horizon_crossing(zenith, noon, -1), set = horizon_crossing(zenith, noon, +1);
  if (std::isnan(rise) && std::isnan(set)) {
    s.kind = SunriseSunset::PolarDay;
    return s;
  }
  s.kind = SunriseSunset::Normal;
  if (!std::isnan(rise)) s.sunrise_minutes = zone.local_minutes(date, rise);
  if (!std::isnan(set)) s.sunset_minutes = zone.local_minutes(date, set);
  return s;
}

std::string SunriseSunset::to_string() const {
  std::ostringstream out;
  const auto clock = [&](double minutes) {
    if (std::isnan(minutes)) return std::string("none");
    const long seconds = std::lround(minutes * 60.0);
    const long h = seconds / 3600, m = std::labs(seconds / 60) % 60;
    char text[32];
    std::snprintf(text, sizeof text, "%s%02ld:%02ld", seconds < 0 ? "-" : "", std::labs(h), m);
    return std::string(text);
  };
  out << "SunriseSunset(";
  if (kind == PolarDay) out << "polar day";
  else if (kind == PolarNight) out << "polar night";
  else out << "sunrise " << clock(sunrise_minutes) << ", sunset " << clock(sunset_minutes);
  out << ", solar noon " << clock(solar_noon_minutes) << ")";
  return out.str();
}

}  // namespace fenestra
