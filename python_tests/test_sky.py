"""Daylight skies through the documented interfaces: the scene file's "sky", `fenestra sky` and
fenestra.sky()."""

import json
import subprocess

import numpy as np
import pytest

import fenestra
from conftest import CLI

PREETHAM = {"type": "preetham", "latitude": 37.98, "longitude": 23.73, "utc_offset": 3, "date": "2026-06-21",
            "start": "09:00", "end": "17:00", "step_minutes": 30, "turbidity": 3.0, "ground_reflectance": 0.2,
            "resolution": [256, 128]}


def with_sky(small_room, sky):
    scene = json.loads(small_room.read_text())
    scene["sky"] = sky
    small_room.write_text(json.dumps(scene))
    return small_room


def run(*args):
    return subprocess.run([CLI, *map(str, args)], capture_output=True, text=True)


def horizontal_illuminance(sky_map):
    """Upper hemisphere of an equirectangular map, each pixel's solid angle times its mean cosine."""
    h, w, _ = sky_map.shape
    lum = sky_map @ np.array([0.2126, 0.7152, 0.0722])
    t0 = np.pi * np.arange(h // 2) / h
    t1 = np.pi * (np.arange(h // 2) + 1) / h
    weight = 0.5 * (np.sin(t1) ** 2 - np.sin(t0) ** 2) * 2 * np.pi / w
    return float((lum[: h // 2].sum(axis=1) * weight).sum())


def test_python_sky_gives_map_suns_and_illuminances(small_room):
    sky = fenestra.sky(fenestra.load_scene(with_sky(small_room, PREETHAM)))
    assert sky["map"].shape == (128, 256, 3) and sky["map"].dtype == np.float32
    assert np.isfinite(sky["map"]).all() and (sky["map"] >= 0).all()
    assert sky["steps"] == 16 and sky["steps_with_sun"] == 16 and len(sky["suns"]) == 16
    e = sky["horizontal_illuminance"]
    assert e["total"] == pytest.approx(e["sky"] + e["sun"], rel=1e-6)
    assert horizontal_illuminance(sky["map"]) == pytest.approx(e["sky"], rel=1e-4)
    # The suns carry the direct part: weights sum to one, their horizontal share adds up.
    suns = sky["suns"]
    assert sum(s["weight"] for s in suns) == pytest.approx(1.0)
    direct = sum(s["weight"] * s["normal_illuminance"] * s["direction"][2] for s in suns)
    assert direct == pytest.approx(e["sun"], rel=1e-4)
    # Morning sun in the east, afternoon sun in the west (azimuth clockwise from north).
    assert 60 < suns[0]["azimuth_deg"] < 120 and 240 < suns[-1]["azimuth_deg"] < 300
    # Below the horizon: a grey ground of reflectance 0.2 lit by sky and sun.
    ground = sky["map"][-1, 0] @ np.array([0.2126, 0.7152, 0.0722])
    assert ground == pytest.approx(0.2 * e["total"] / np.pi, rel=1e-4)


def test_cli_sky_writes_map_and_prints_suns(small_room, tmp_path):
    scene = with_sky(small_room, PREETHAM)
    for name in ("sky.exr", "sky.hdr"):
        out, summary = tmp_path / name, tmp_path / (name + ".json")
        r = run("sky", scene, "-o", out, "--json", summary, "--quiet")
        assert r.returncode == 0, r.stderr
        assert out.stat().st_size > 1000
        assert "suns" in r.stdout and "horizontal illuminance" in r.stdout
        data = json.loads(summary.read_text())
        assert len(data["suns"]) == 16
        assert data["horizontal_illuminance"]["total"] > 50000  # a clear midsummer day in Athens


def test_cie_overcast_daylight_factor(small_room, tmp_path):
    scene = with_sky(small_room, {"type": "cie_overcast", "horizontal_illuminance": 10000, "resolution": [256, 128]})
    sky = fenestra.sky(fenestra.load_scene(scene))
    assert sky["horizontal_illuminance"]["total"] == pytest.approx(10000, rel=1e-4)
    assert sky["suns"] == []
    openings = tmp_path / "openings.json"
    openings.write_text(json.dumps({"openings": [{"corners": [[1, 0, 1], [2, 0, 1], [2, 0, 2], [1, 0, 2]]}]}))
    out = tmp_path / "eval.json"
    r = run("evaluate", scene, "--openings", openings, "-o", out, "--paths", 256, "--quiet")
    assert r.returncode == 0, r.stderr
    result = json.loads(out.read_text())
    assert result["horizontal_illuminance"] == pytest.approx(10000, rel=1e-4)
    for s in result["sensors"]:
        assert s["daylight_factor"] == pytest.approx(100 * s["value"] / result["horizontal_illuminance"])
        assert 0 < s["daylight_factor"] < 100


@pytest.mark.parametrize("change, needle", [
    ({"turbidity": 0.5}, "sky.turbidity"),
    ({"timezone": "Nowhere/Atlantis", "utc_offset": None}, "Nowhere/Atlantis"),
    ({"date": "2026-13-01"}, "2026-13-01"),
    ({"end": "9 pm"}, "9 pm"),
    ({"step_minutes": -15}, "sky.step_minutes"),
    ({"latitude": None}, "sky.latitude"),
    ({"resolution": [100, 51]}, "resolution"),
    ({"sun": "yes"}, "sky.sun"),
])
def test_bad_sky_is_a_clear_error_and_writes_nothing(small_room, tmp_path, change, needle):
    sky = dict(PREETHAM)
    for key, value in change.items():
        if value is None:
            sky.pop(key, None)
        else:
            sky[key] = value
    scene = with_sky(small_room, sky)
    out = tmp_path / "sky.exr"
    r = run("sky", scene, "-o", out, "--quiet")
    assert r.returncode == 1
    assert needle in r.stderr and "scene.json" in r.stderr
    assert not out.exists()
    with pytest.raises(ValueError, match="sky"):
        fenestra.load_scene(scene)
