// Python bindings of the daylight models (solar position, analytic skies).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>

#include "daylight/local_time.h"
#include "daylight/sky_models.h"
#include "daylight/solar_position.h"
#include "number_text.h"
#include "scene/input_limits.h"

namespace py = pybind11;
using namespace fenestra;

// ---- Solar position and local time ----

namespace {

// The time zone given either as a fixed UTC offset in hours or as an IANA name, exactly one of them.
TimeZone zone_from(const std::optional<double>& utc_offset, const std::optional<std::string>& timezone) {
  if (utc_offset && timezone)
    throw std::invalid_argument("give either utc_offset (hours) or timezone (IANA name), not both");
  if (utc_offset) return TimeZone::fixed(*utc_offset);
  if (timezone) return TimeZone::named(*timezone);
  throw std::invalid_argument("give utc_offset (hours, e.g. -7) or timezone (IANA name, e.g. \"Europe/Athens\")");
}

// `name` in [lo, hi] (NaN refused), else ValueError naming it, its value and the range.
double within(const char* name, double v, double lo, double hi, const char* unit) {
  if (!(v >= lo && v <= hi)) {
    std::ostringstream s;
    s << name << " is " << number_text(v) << ": expected " << lo << " to " << hi << unit;
    throw std::invalid_argument(s.str());
  }
  return v;
}

// The place as a scene's sky takes it (docs/scene-format.md, "Accepted ranges").
Place place_from(double latitude_deg, double longitude_deg, double elevation_m) {
  return Place{within("latitude_deg", latitude_deg, -90.0, 90.0, " degrees"),
               within("longitude_deg", longitude_deg, -180.0, 180.0, " degrees"),
               within("elevation_m", elevation_m, -limits::kMaxElevation, limits::kMaxElevation, " m")};
}

// The instants of the dates a scene may give (years 0001 to 9999, "YYYY-MM-DD") in any UTC offset
// (+-14 h): POSIX seconds of 0001-01-01 00:00 at UTC+14 and of 10000-01-01 00:00 at UTC-14.
constexpr double kFirstInstant = -62135596800.0 - 14 * 3600.0;
constexpr double kLastInstant = 253402300800.0 + 14 * 3600.0;

py::object minutes_or_none(double minutes) { return std::isnan(minutes) ? py::none() : py::cast(minutes); }

const char* kind_name(SunriseSunset::Kind kind) {
  switch (kind) {
    case SunriseSunset::PolarDay: return "polar_day";
    case SunriseSunset::PolarNight: return "polar_night";
    default: return "normal";
  }
}

void bind_solar(py::module_& m) {
  m.def(
      "solar_position",
      [](double utc_seconds, double latitude_deg, double longitude_deg, double elevation_m, bool refraction,
         double pressure_hpa, double temperature_c) {
        if (!(utc_seconds >= kFirstInstant && utc_seconds <= kLastInstant))
          throw std::invalid_argument("utc_seconds is " + number_text(utc_seconds) +
                                      ": expected POSIX seconds of a date in the years 0001 to 9999 (-6.2e10 to 2.5e11), "
                                      "as fenestra.utc_seconds gives them");
        const Place place = place_from(latitude_deg, longitude_deg, elevation_m);
        within("pressure_hpa", pressure_hpa, 0.0, 2000.0, " hPa");
        within("temperature_c", temperature_c, -90.0, 60.0, " degrees C");
        const SunPosition p = refraction ? solar_position(utc_seconds, place, Atmosphere{pressure_hpa, temperature_c})
                                         : solar_position(utc_seconds, place, false);
        return py::make_tuple(p.zenith_deg, p.azimuth_deg);
      },
      py::arg("utc_seconds"), py::arg("latitude_deg"), py::arg("longitude_deg"), py::arg("elevation_m") = 0.0,
      py::arg("refraction") = true, py::arg("pressure_hpa") = 1010.0, py::arg("temperature_c") = 10.0,
      "Apparent topocentric (zenith_deg, azimuth_deg) of the sun at POSIX seconds UTC; azimuth clockwise from "
      "north. Refraction (standard atmosphere unless pressure and temperature are given) lifts the sun near the "
      "horizon. ValueError outside the accepted ranges: an instant of the years 0001 to 9999, latitude -90..90, "
      "longitude -180..180, elevation within +-1e6 m, pressure 0..2000 hPa, temperature -90..60 degrees C.");
  m.def(
      "sun_direction",
      [](double zenith_deg, double azimuth_deg) {
        within("zenith_deg", zenith_deg, 0.0, 180.0, " degrees");
        within("azimuth_deg", azimuth_deg, -360.0, 360.0, " degrees");
        const Vec3 d = sun_direction(SunPosition{zenith_deg, azimuth_deg});
        py::array_t<double> out(3);
        auto w = out.mutable_unchecked<1>();
        for (int k = 0; k < 3; ++k) w(k) = d[k];
        return out;
      },
      py::arg("zenith_deg"), py::arg("azimuth_deg"), "Unit world vector toward the sun, shape (3,): +Z up, +Y north, +X east.");
  m.def(
      "utc_seconds",
      [](const std::string& date, const std::string& clock, std::optional<double> utc_offset,
         std::optional<std::string> timezone) {
        return zone_from(utc_offset, timezone).utc_seconds(parse_date(date), parse_clock_minutes(clock));
      },
      py::arg("date"), py::arg("clock"), py::arg("utc_offset") = py::none(), py::arg("timezone") = py::none(),
      "POSIX seconds (UTC) of a local date \"YYYY-MM-DD\" and clock \"HH:MM[:SS]\" in a fixed UTC offset (hours) "
      "or an IANA time zone. Clock times skipped or repeated by a daylight-saving change take the offset in force "
      "before the change.");
  m.def(
      "sunrise_sunset",
      [](const std::string& date, double latitude_deg, double longitude_deg, std::optional<double> utc_offset,
         std::optional<std::string> timezone) {
        const SunriseSunset s = sunrise_sunset(parse_date(date), zone_from(utc_offset, timezone),
                                               place_from(latitude_deg, longitude_deg, 0.0));
        py::dict out;
        out["kind"] = kind_name(s.kind);
        out["sunrise_minutes"] = minutes_or_none(s.sunrise_minutes);
        out["sunset_minutes"] = minutes_or_none(s.sunset_minutes);
        out["solar_noon_minutes"] = s.solar_noon_minutes;
        return out;
      },
      py::arg("date"), py::arg("latitude_deg"), py::arg("longitude_deg"), py::arg("utc_offset") = py::none(),
      py::arg("timezone") = py::none(),
      "Sunrise and sunset (upper limb on a flat horizon, centre zenith 90.833 deg) as local clock minutes after "
      "midnight of the date: {'kind': 'normal' | 'polar_day' | 'polar_night', 'sunrise_minutes', "
      "'sunset_minutes', 'solar_noon_minutes'}. Sunset exceeds 1440 when the sun sets after midnight; a missing "
      "event is None.");
}

}  // namespace

// ---- Analytic skies and the sun ----

namespace {

using DoubleArray = py::array_t<double, py::array::c_style | py::array::forcecast>;

py::array_t<double> rgb_array(const Rgb& c) {
  py::array_t<double> out(3);
  auto w = out.mutable_unchecked<1>();
  for (int k = 0; k < 3; ++k) w(k) = c[k];
  return out;
}

void bind_sky_models(py::module_& m) {
  m.def(
      "preetham_radiance",
      [](double turbidity, DoubleArray sun_direction, DoubleArray directions) {
        if (sun_direction.ndim() != 1 || sun_direction.shape(0) != 3)
          throw std::invalid_argument("sun_direction must have shape (3,)");
        if (directions.ndim() != 2 || directions.shape(1) != 3)
          throw std::invalid_argument("directions must have shape (n, 3)");
        const auto s = sun_direction.unchecked<1>();
        const PreethamSky sky(turbidity, Vec3(s(0), s(1), s(2)));
        const py::ssize_t n = directions.shape(0);
        py::array_t<double> out({n, py::ssize_t(3)});
        const auto d = directions.unchecked<2>();
        auto w = out.mutable_unchecked<2>();
        {
          py::gil_scoped_release release;
          for (py::ssize_t i = 0; i < n; ++i) {
            const Vec3 dir(d(i, 0), d(i, 1), d(i, 2));
            if (!is_finite(dir) || !(dir.norm() > 0.0f))
              throw std::invalid_argument("direction " + std::to_string(i) + " is zero or not finite");
            const Rgb c = sky.radiance(dir.normalized());
            for (int k = 0; k < 3; ++k) w(i, k) = c[k];
          }
        }
        return out;
      },
      py::arg("turbidity"), py::arg("sun_direction"), py::arg("directions"),
      "Preetham clear-sky radiance, linear sRGB in cd/m^2, shape (n, 3), for world directions (n, 3) (+Z up; "
      "normalised here; below the horizon 0). Raises ValueError for a turbidity outside [1.7, 10] or a sun not "
      "above the horizon.");
  m.def(
      "preetham_sun",
      [](double turbidity, double sun_zenith_deg) {
        const SunDisk disk = preetham_sun(turbidity, sun_zenith_deg * (3.14159265358979323846 / 180.0));
        py::dict out;
        out["radiance"] = rgb_array(disk.radiance);
        out["solid_angle"] = disk.solid_angle;
        out["normal_illuminance"] = rgb_array(disk.normal_illuminance());
        return out;
      },
      py::arg("turbidity"), py::arg("sun_zenith_deg"),
      "The solar disk through a Preetham atmosphere: {'radiance': mean disk radiance (3,) linear sRGB cd/m^2, "
      "'solid_angle': sr (0.53 deg disk), 'normal_illuminance': (3,) lux on a plane facing the sun}. Zero radiance "
      "at or below the horizon; ValueError for a turbidity outside [1.7, 10].");
}

}  // namespace

void bind_daylight(py::module_& m) {
  bind_solar(m);
  bind_sky_models(m);
}
