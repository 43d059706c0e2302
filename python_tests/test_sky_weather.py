"""The weather-driven skies of the scene file ("perez", "climate") through the Python API and the
command line (docs/sky.md, "Perez sky" and "Climate")."""

import json
import os
import subprocess
import warnings

import numpy as np
import pytest

import fenestra
from conftest import CLI, EXAMPLES

CHICAGO = os.path.join(EXAMPLES, "weather", "USA_IL_Chicago-OHare.Intl.AP.725300_TMY3.epw")
PEREZ = {"type": "perez", "latitude": 41.98, "longitude": -87.92, "utc_offset": -6, "date": "2026-06-21",
         "start": "10:00", "end": "14:00", "step_minutes": 60, "direct_normal": 700, "diffuse_horizontal": 120,
         "resolution": [128, 64]}
CLIMATE = {"type": "climate", "weather": CHICAGO, "resolution": [64, 32]}


def with_sky(small_room, sky):
    scene = json.loads(small_room.read_text())
    scene["sky"] = sky
    small_room.write_text(json.dumps(scene))
    return small_room


def horizontal_illuminance(sky_map):
    """Upper hemisphere of an equirectangular map, each pixel's solid angle times its mean cosine."""
    h, w, _ = sky_map.shape
    lum = sky_map @ np.array([0.2126, 0.7152, 0.0722])
    t0 = np.pi * np.arange(h // 2) / h
    t1 = np.pi * (np.arange(h // 2) + 1) / h
    weight = 0.5 * (np.sin(t1) ** 2 - np.sin(t0) ** 2) * 2 * np.pi / w
    return float((lum[: h // 2].sum(axis=1) * weight).sum())


def test_perez_scene_loads_with_its_map_and_suns(small_room):
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no weather file, nothing to warn about
        scene = fenestra.load_scene(with_sky(small_room, PEREZ))
    sky = fenestra.sky(scene)
    assert "Perez sky" in sky["description"]
    assert sky["steps"] == 4 and sky["steps_with_sun"] == 4 and len(sky["suns"]) == 4
    e = sky["horizontal_illuminance"]
    # About 120 W/m^2 x 110-130 lm/W of diffuse light, 700 W/m^2 x about 100 lm/W of direct.
    assert 10000 < e["sky"] < 20000 and 40000 < e["sun"] < 70000
    assert horizontal_illuminance(sky["map"]) == pytest.approx(e["sky"], rel=1e-4)
    assert sum(s["weight"] for s in sky["suns"]) == pytest.approx(1.0)
    for s in sky["suns"]:
        assert 60000 < s["normal_illuminance"] < 80000


def test_perez_scene_from_a_weather_file_takes_its_place_and_clock(small_room):
    sky = {"type": "perez", "weather": CHICAGO, "date": "2026-06-21", "time": "11:30", "resolution": [64, 32]}
    scene = fenestra.load_scene(with_sky(small_room, sky))
    summary = fenestra.sky(scene)
    assert "weather" in summary["description"] and len(summary["suns"]) == 1
    assert summary["suns"][0]["utc"] == "2026-06-21T17:30:00Z"  # the file's standard time, UTC-6


def test_climate_scene_loads_and_its_cumulative_sky_spans_the_occupied_hours(small_room, tmp_path):
    scene = fenestra.load_scene(with_sky(small_room, CLIMATE))
    sky = fenestra.sky(scene)
    assert sky["description"].startswith("EnvironmentMap(climate of")
    assert sky["steps"] == 3650 and sky["map"].shape == (32, 64, 3)
    assert 3000 < len(sky["suns"]) < 3650
    assert all(s["weight"] == pytest.approx(1 / 3650) for s in sky["suns"])
    # Chicago's occupied-hour means: some 20 klx of diffuse and 18 klx of direct horizontal light.
    e = sky["horizontal_illuminance"]
    assert 15000 < e["sky"] < 25000 and 12000 < e["sun"] < 25000
    # The command line lists the first suns and keeps all of them in the JSON summary.
    out, summary = tmp_path / "sky.exr", tmp_path / "sky.json"
    r = subprocess.run([CLI, "sky", str(small_room), "-o", str(out), "--json", str(summary), "--quiet"],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    assert "more (all in the --json summary)" in r.stdout
    assert len(json.loads(summary.read_text())["suns"]) == len(sky["suns"])


def test_climate_scene_far_from_its_station_warns(small_room):
    sky = dict(CLIMATE, latitude=37.98, longitude=23.73)
    with pytest.warns(RuntimeWarning, match="km from the weather file's station"):
        scene = fenestra.load_scene(with_sky(small_room, sky))
    assert len(fenestra._core.sky_warnings(scene)) == 1
    r = subprocess.run([CLI, "sky", str(small_room), "-o", str(small_room.parent / "s.exr"), "--quiet"],
                       capture_output=True, text=True)
    assert r.returncode == 0 and "fenestra: warning: the scene's place" in r.stderr


@pytest.mark.parametrize("sky, needle", [
    (dict(CLIMATE, weather="missing.epw"), "sky.weather"),
    (dict(CLIMATE, patches=3), "sky.patches"),
    (dict(CLIMATE, turbidity=3), "sky.turbidity"),
    (dict(PEREZ, weather=CHICAGO), "sky.direct_normal"),
    (dict(PEREZ, diffuse_horizontal=-1), "sky.diffuse_horizontal"),
])
def test_bad_weather_sky_is_a_clear_error(small_room, sky, needle):
    with pytest.raises(ValueError, match=needle.replace(".", r"\.")):
        fenestra.load_scene(with_sky(small_room, sky))
