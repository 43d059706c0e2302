"""The daylight models of the native module (docs/sky.md), with their arguments checked first
(fenestra.arguments); no bpy here. Directions: +Z up, +Y north, +X east; azimuth clockwise
from north."""

from . import _core
from . import arguments as _arg


def solar_position(utc_seconds, latitude_deg, longitude_deg, elevation_m=0.0, refraction=True,
                   pressure_hpa=1010.0, temperature_c=10.0):
    """Apparent topocentric (zenith_deg, azimuth_deg) of the sun at POSIX seconds UTC; azimuth
    clockwise from north. Refraction (standard atmosphere unless pressure and temperature are
    given) lifts the sun near the horizon."""
    return _core.solar_position(
        _arg.number(utc_seconds, "utc_seconds"), _arg.number(latitude_deg, "latitude_deg"),
        _arg.number(longitude_deg, "longitude_deg"), _arg.number(elevation_m, "elevation_m"),
        _arg.flag(refraction, "refraction"), _arg.number(pressure_hpa, "pressure_hpa"),
        _arg.number(temperature_c, "temperature_c"))


def sun_direction(zenith_deg, azimuth_deg):
    """Unit world vector toward the sun, shape (3,)."""
    return _core.sun_direction(_arg.number(zenith_deg, "zenith_deg"), _arg.number(azimuth_deg, "azimuth_deg"))


def utc_seconds(date, clock, utc_offset=None, timezone=None):
    """POSIX seconds (UTC) of a local date "YYYY-MM-DD" and clock "HH:MM[:SS]" in a fixed UTC
    offset (hours) or an IANA time zone."""
    return _core.utc_seconds(_arg.text(date, "date"), _arg.text(clock, "clock"),
                             _arg.optional_number(utc_offset, "utc_offset"), _arg.optional_text(timezone, "timezone"))


def sunrise_sunset(date, latitude_deg, longitude_deg, utc_offset=None, timezone=None):
    """Sunrise and sunset as local clock minutes after midnight of the date: {"kind": "normal" |
    "polar_day" | "polar_night", "sunrise_minutes", "sunset_minutes", "solar_noon_minutes"}."""
    return _core.sunrise_sunset(_arg.text(date, "date"), _arg.number(latitude_deg, "latitude_deg"),
                                _arg.number(longitude_deg, "longitude_deg"),
                                _arg.optional_number(utc_offset, "utc_offset"),
                                _arg.optional_text(timezone, "timezone"))


def preetham_radiance(turbidity, sun_direction, directions):
    """Preetham clear-sky radiance, linear sRGB in cd/m^2, shape (n, 3), for world directions (n, 3)."""
    return _core.preetham_radiance(_arg.number(turbidity, "turbidity"),
                                   _arg.array(sun_direction, "sun_direction", "of shape (3,)", ndim=1),
                                   _arg.array(directions, "directions", "of shape (n, 3)", ndim=2))


def preetham_sun(turbidity, sun_zenith_deg):
    """The solar disk through a Preetham atmosphere: {"radiance", "solid_angle", "normal_illuminance"}."""
    return _core.preetham_sun(_arg.number(turbidity, "turbidity"), _arg.number(sun_zenith_deg, "sun_zenith_deg"))
