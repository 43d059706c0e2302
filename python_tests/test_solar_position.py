"""Solar position and local time, checked against astropy (ERFA), an independent implementation.

astropy is a test-only dependency: Fenestra itself never imports it.
"""

import math
import warnings

import numpy as np
import pytest

from fenestra import _core

import astropy.units as u
from astropy.coordinates import AltAz, EarthLocation, get_sun
from astropy.time import Time
from astropy.utils import iers

# Offline and quiet: the IERS tables shipped with astropy are enough at this accuracy (UT1 - UTC
# below a second moves the sun by under 0.004 deg); outside them astropy only warns.
iers.conf.auto_download = False
if hasattr(iers.conf, "iers_degraded_accuracy"):
    iers.conf.iers_degraded_accuracy = "warn"

TOLERANCE_DEG = 0.05  # required agreement with NREL SPA, which astropy matches to ~0.001 deg


def astropy_sun(utc_seconds, latitude_deg, longitude_deg, elevation_m, pressure_hpa=0.0, temperature_c=10.0):
    """(zenith_deg, azimuth_deg) arrays from astropy; pressure 0 turns refraction off."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # stale IERS data, 'dubious year' before 1960 UTC
        t = Time(np.asarray(utc_seconds, float), format="unix", scale="utc")
        where = EarthLocation.from_geodetic(np.asarray(longitude_deg) * u.deg, np.asarray(latitude_deg) * u.deg,
                                            np.asarray(elevation_m) * u.m)
        frame = AltAz(obstime=t, location=where, pressure=pressure_hpa * u.hPa,
                      temperature=temperature_c * u.deg_C, relative_humidity=0.0, obswl=0.55 * u.micron)
        altaz = get_sun(t).transform_to(frame)
        return 90.0 - altaz.alt.deg, altaz.az.deg


def azimuth_arc(azimuth, reference, zenith):
    """Azimuth difference wrapped to [-180, 180], times sin(zenith): its arc on the sky."""
    return ((np.asarray(azimuth) - reference + 180.0) % 360.0 - 180.0) * np.sin(np.radians(zenith))


def random_instants_and_places(count, seed):
    rng = np.random.default_rng(seed)
    start = _core.utc_seconds("1950-01-01", "00:00", utc_offset=0)
    end = _core.utc_seconds("2050-12-31", "24:00", utc_offset=0)
    t = rng.uniform(start, end, count)
    # Uniform over the sphere's area up to 85 degrees of latitude.
    lat = np.degrees(np.arcsin(rng.uniform(-1.0, 1.0, count) * math.sin(math.radians(85.0))))
    lon = rng.uniform(-180.0, 180.0, count)
    elevation = rng.uniform(0.0, 3000.0, count)
    return t, lat, lon, elevation


def test_matches_astropy_without_refraction_1950_to_2050():
    t, lat, lon, elevation = random_instants_and_places(800, seed=20240621)
    ref_zenith, ref_azimuth = astropy_sun(t, lat, lon, elevation)
    ours = np.array([_core.solar_position(*args, refraction=False) for args in zip(t, lat, lon, elevation)])

    up = ref_zenith < 95.0  # the sun above -5 deg altitude
    assert up.sum() >= 300, "too few daytime samples to mean anything: %d" % up.sum()
    assert (lat[up] < 0).sum() >= 100 and (lat[up] > 0).sum() >= 100, "both hemispheres must be sampled"

    zenith_error = np.abs(ours[up, 0] - ref_zenith[up])
    azimuth_error = np.abs(azimuth_arc(ours[up, 1], ref_azimuth[up], ref_zenith[up]))
    worst = int(np.argmax(zenith_error))
    assert zenith_error.max() <= TOLERANCE_DEG, "max zenith difference %.4f deg over %d samples (at %s, %.2f, %.2f)" % (
        zenith_error.max(), up.sum(), Time(t[up][worst], format="unix").iso, lat[up][worst], lon[up][worst])
    assert azimuth_error.max() <= TOLERANCE_DEG, "max azimuth difference x sin(zenith) %.4f deg over %d samples" % (
        azimuth_error.max(), up.sum())
    # Observed: about 0.009 deg for both; the Meeus series for the sun's longitude is the limit.


def test_polar_day_and_polar_night_match_astropy():
    # Midnight sun and polar night at 80 N and 80 S, every three hours over a solstice day.
    t0 = _core.utc_seconds("2031-06-21", "00:00", utc_offset=0)
    t = t0 + 3 * 3600.0 * np.arange(8)
    for latitude in (80.0, -80.0):
        ref_zenith, ref_azimuth = astropy_sun(t, latitude, 20.0, 0.0)
        ours = np.array([_core.solar_position(x, latitude, 20.0, refraction=False) for x in t])
        assert np.all((ours[:, 0] < 90.0) == (latitude > 0)), "sun up all day in the north, down in the south"
        assert np.abs(ours[:, 0] - ref_zenith).max() <= TOLERANCE_DEG
        assert np.abs(azimuth_arc(ours[:, 1], ref_azimuth, ref_zenith)).max() <= TOLERANCE_DEG


def test_refraction_agrees_with_astropy_well_above_the_horizon():
    # Both refraction models are the same physics within a few arc seconds above 10 deg altitude
    # (astropy's is ERFA's, ours Saemundsson's as NREL SPA); nearer the horizon they part ways.
    t, lat, lon, elevation = random_instants_and_places(300, seed=7)
    ref_zenith, _ = astropy_sun(t, lat, lon, elevation, pressure_hpa=1010.0, temperature_c=10.0)
    ours = np.array([_core.solar_position(*args) for args in zip(t, lat, lon, elevation)])
    high = ref_zenith < 80.0
    assert high.sum() >= 50
    error = np.abs(ours[high, 0] - ref_zenith[high])
    assert error.max() <= TOLERANCE_DEG, "max zenith difference with refraction %.4f deg" % error.max()


def test_spa_paper_example():
    # Reda & Andreas, NREL/TP-560-34302, table A4: Golden, Colorado.
    t = _core.utc_seconds("2003-10-17", "12:30:30", utc_offset=-7)
    zenith, azimuth = _core.solar_position(t, 39.742476, -105.1786, elevation_m=1830.14, pressure_hpa=820.0,
                                           temperature_c=11.0)
    assert zenith == pytest.approx(50.11162, abs=TOLERANCE_DEG)
    assert azimuth == pytest.approx(194.34024, abs=TOLERANCE_DEG)


def test_sun_direction_axes():
    east = _core.sun_direction(90.0, 90.0)
    assert east.shape == (3,)
    np.testing.assert_allclose(east, [1.0, 0.0, 0.0], atol=1e-6)
    np.testing.assert_allclose(_core.sun_direction(90.0, 0.0), [0.0, 1.0, 0.0], atol=1e-6)
    np.testing.assert_allclose(_core.sun_direction(60.0, 180.0), [0.0, -math.sin(math.radians(60)), 0.5], atol=1e-6)


def test_utc_seconds_fixed_offsets_and_zones():
    assert _core.utc_seconds("2000-01-01", "00:00", utc_offset=0) == 946684800.0
    assert _core.utc_seconds("2000-01-01", "00:00", utc_offset=-7) == 946684800.0 + 7 * 3600
    # Athens keeps summer time (UTC+3) in July and UTC+2 in January.
    assert _core.utc_seconds("2024-07-15", "12:00", timezone="Europe/Athens") == _core.utc_seconds(
        "2024-07-15", "09:00", utc_offset=0)
    assert _core.utc_seconds("2024-01-15", "12:00", timezone="Europe/Athens") == _core.utc_seconds(
        "2024-01-15", "10:00", utc_offset=0)


@pytest.mark.parametrize("kwargs, message", [
    (dict(date="2026-02-30", clock="12:00", utc_offset=0), "2026-02-30"),
    (dict(date="17/10/2003", clock="12:00", utc_offset=0), "17/10/2003"),
    (dict(date="2024-01-01", clock="24:30", utc_offset=0), "24:30"),
    (dict(date="2024-01-01", clock="noon", utc_offset=0), "noon"),
    (dict(date="2024-01-01", clock="12:00", timezone="Atlantis/Capital"), "Atlantis/Capital"),
    (dict(date="2024-01-01", clock="12:00", utc_offset=15), "offset"),
    (dict(date="2024-01-01", clock="12:00", utc_offset=1, timezone="Europe/Athens"), "not both"),
    (dict(date="2024-01-01", clock="12:00"), "utc_offset"),
])
def test_utc_seconds_errors_name_the_input(kwargs, message):
    with pytest.raises(ValueError, match=message):
        _core.utc_seconds(**kwargs)


def test_sunrise_sunset():
    # USNO for Atlanta (33.8 N, 84.4 W), 2009-09-06 EDT: sunrise 7:15 a.m., sunset 7:56 p.m.
    day = _core.sunrise_sunset("2009-09-06", 33.8, -84.4, timezone="America/New_York")
    assert day["kind"] == "normal"
    assert day["sunrise_minutes"] == pytest.approx(7 * 60 + 15, abs=1.5)
    assert day["sunset_minutes"] == pytest.approx(19 * 60 + 56, abs=1.5)

    assert _core.sunrise_sunset("2024-06-21", 78.22, 15.63, utc_offset=2)["kind"] == "polar_day"
    night = _core.sunrise_sunset("2024-12-21", 78.22, 15.63, utc_offset=1)
    assert night["kind"] == "polar_night" and night["sunrise_minutes"] is None and night["sunset_minutes"] is None
