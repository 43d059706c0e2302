"""Annual studies of a "climate" scene (docs/annual.md): the command line, the Python API, their
agreement with a path-traced reference of the occupied hours' mean, and bad input."""

import json
import os
import random
import subprocess

import numpy as np
import pytest

import fenestra
from conftest import CLI, EXAMPLES

CHICAGO = os.path.join(EXAMPLES, "weather", "USA_IL_Chicago-OHare.Intl.AP.725300_TMY3.epw")
WINDOW = {"openings": [{"corners": [[0.5, 0, 1.0], [2.5, 0, 1.0], [2.5, 0, 2.0], [0.5, 0, 2.0]]}]}
# The Tregenza patches stand for the continuous cumulative sky: their patch means differ from it by
# 0.5 % on average in the diffuse illuminance they give (docs/sky.md, "The patch sum").
PATCH_MODEL = 0.01


def climate_room(small_room, **sky):
    scene = json.loads(small_room.read_text())
    scene["sky"] = {"type": "climate", "weather": CHICAGO, "resolution": [64, 32], **sky}
    small_room.write_text(json.dumps(scene))
    (small_room.parent / "window.json").write_text(json.dumps(WINDOW))
    return small_room


def cli(*args):
    return subprocess.run([CLI, *map(str, args)], capture_output=True, text=True)


def test_cli_writes_the_year_and_its_metrics(small_room, tmp_path):
    scene = climate_room(small_room)
    out = tmp_path / "year"
    r = cli("annual", scene, "--openings", tmp_path / "window.json", "-o", out, "--quiet")
    assert r.returncode == 0, r.stderr
    assert "sDA" in r.stdout and "ASE" in r.stdout
    arrays = np.load(str(out) + ".npz")
    summary = json.loads((tmp_path / "year.json").read_text())
    assert arrays["illuminance"].shape == (3, 8760) and arrays["illuminance"].dtype == np.float32
    assert arrays["direct_sun"].shape == (3, 8760)
    assert summary["format"] == "fenestra-annual" and summary["occupied_hours"] == int(arrays["occupied"].sum()) == 3650
    assert summary["dropped"] == {"non_finite": 0, "truncated_conditions": 0}
    e, d = arrays["illuminance"], arrays["direct_sun"]
    assert np.all(e >= 0) and np.all(d >= 0) and np.all(d <= e * (1 + 1e-5) + 1e-3)
    night = (arrays["hour_clock"] < 3) | (arrays["hour_clock"] > 22)
    assert e[:, night].max() == 0.0
    occupied = arrays["occupied"].astype(bool)
    mean = e[:, occupied].mean(axis=1)
    assert np.allclose(mean, summary["per_sensor"]["mean_illuminance_lux"], rtol=1e-5)
    assert np.allclose(arrays["daylight_autonomy"], (e[:, occupied] >= 300).mean(axis=1))
    # The sensor 1 m behind the window gets direct sun; the one 2.5 m back at the side barely.
    assert summary["per_sensor"]["ase_hours"][0] > 250 > summary["per_sensor"]["ase_hours"][1]
    assert 0.0 <= summary["space"]["spatial_daylight_autonomy"] <= 1.0


def test_the_year_matches_a_path_traced_mean_of_the_occupied_hours(small_room):
    scene = fenestra.load_scene(climate_room(small_room))
    result = fenestra.annual(scene, WINDOW)
    per_sensor = result["summary"]["per_sensor"]
    reference = fenestra.load_scene(str(small_room))
    reference.render.paths_per_sensor = 1 << 15
    truth, truth_se = fenestra.evaluate(reference, WINDOW)  # the cumulative sky of the occupied hours
    year = np.array(per_sensor["mean_illuminance_lux"])
    se = np.array(per_sensor["mean_illuminance_stderr_lux"])
    allowed = 4 * np.hypot(se, truth_se) + PATCH_MODEL * truth
    assert np.all(np.abs(year - truth) <= allowed), (year, truth, allowed)
    # The same mean straight from the records' values (the sun clusters instead of the exact sun).
    records = np.array(per_sensor["mean_illuminance_from_records_lux"])
    assert np.all(np.abs(records - truth) <= 4 * np.hypot(se, truth_se) + PATCH_MODEL * truth)


def test_python_and_cli_agree_and_contributions_are_reused(small_room, tmp_path):
    path = climate_room(small_room)
    scene = fenestra.load_scene(path)
    c = fenestra.contributions(scene)
    assert c.has_annual
    a = fenestra.annual(scene, WINDOW, contributions=c, output=tmp_path / "py")
    r = cli("annual", path, "--openings", tmp_path / "window.json", "-o", tmp_path / "cli", "--quiet")
    assert r.returncode == 0, r.stderr
    from_cli = np.load(tmp_path / "cli.npz")
    assert np.array_equal(a["illuminance"], from_cli["illuminance"])
    assert np.array_equal(np.load(tmp_path / "py.npz")["illuminance"], from_cli["illuminance"])
    # The window covers whole elements: the mask of those elements gives the same year.
    window = fenestra.openings_array(WINDOW)[0]
    lo, hi = window.min(axis=0), window.max(axis=0)
    centres = np.asarray(scene.element_corners).mean(axis=1)
    mask = np.all((centres >= lo - 1e-6) & (centres <= hi + 1e-6), axis=1)
    assert mask.sum() == 8  # 2 x 1 m of 0.5 m elements
    by_mask = c.annual(mask)
    assert np.allclose(by_mask["illuminance"], a["illuminance"], rtol=1e-5, atol=1e-3)


def test_closed_openings_give_a_dark_year(small_room):
    scene = fenestra.load_scene(climate_room(small_room))
    c = fenestra.contributions(scene)
    dark = c.annual(np.zeros(scene.element_count, bool))
    assert dark["illuminance"].max() == 0.0
    assert dark["summary"]["space"]["spatial_daylight_autonomy"] == 0.0
    assert dark["summary"]["space"]["en17037"]["level_reached"] == "none"


def test_occupied_hours_come_from_the_scene(small_room):
    scene = fenestra.load_scene(climate_room(small_room, occupied=["09:00", "17:00"]))
    summary = fenestra.annual(scene, WINDOW)["summary"]
    assert summary["occupied_hours"] == 8 * 365
    assert summary["occupied"]["start_hour"] == 9.0


def test_annual_needs_a_climate_sky(small_room, tmp_path):
    (tmp_path / "window.json").write_text(json.dumps(WINDOW))
    scene = fenestra.load_scene(small_room)
    with pytest.raises(ValueError, match="climate"):
        fenestra.annual(scene, WINDOW)
    with pytest.raises(ValueError, match="climate"):
        fenestra.contributions(scene).annual(np.ones(scene.element_count, bool))
    r = cli("annual", small_room, "--openings", tmp_path / "window.json", "-o", tmp_path / "out", "--quiet")
    assert r.returncode == 1 and "climate" in r.stderr
    assert not (tmp_path / "out.npz").exists() and not (tmp_path / "out.json").exists()


def test_bad_openings_and_masks_are_refused_naming_them(small_room, tmp_path):
    scene = fenestra.load_scene(climate_room(small_room))
    c = fenestra.contributions(scene)
    with pytest.raises(ValueError, match="open mask has 2 entries; the contributions have 30 elements"):
        c.annual(np.ones(2, bool))
    off = {"openings": [{"corners": [[0.5, 5, 1.0], [2.5, 5, 1.0], [2.5, 5, 2.0], [0.5, 5, 2.0]]}]}
    with pytest.raises(ValueError, match="opening 0"):
        fenestra.annual(scene, off, contributions=c)
    (tmp_path / "off.json").write_text(json.dumps(off))
    r = cli("annual", small_room, "--openings", tmp_path / "off.json", "-o", tmp_path / "out", "--quiet")
    assert r.returncode == 1 and "opening 0" in r.stderr, r.stderr
    assert not list(tmp_path.glob("out.*"))
    r = cli("annual", small_room, "-o", tmp_path / "out")
    assert r.returncode == 2 and "--openings" in r.stderr


def test_seeded_mutations_of_the_climate_sky_load_or_are_refused_by_name(small_room):
    base = json.loads(climate_room(small_room).read_text())
    rng = random.Random(16)
    values = [None, -1, 0, 3, 1e9, float("nan"), "x", "25:00", ["08:00"], ["18:00", "08:00"], ["08:00", "18:00"],
              [], {}, True, "missing.epw"]
    for _ in range(40):
        scene = json.loads(json.dumps(base))
        key = rng.choice(["occupied", "patches", "weather", "north_offset_deg", "ground_reflectance", "latitude",
                          "elevation", "bogus"])
        value = rng.choice(values)
        scene["sky"][key] = value
        text = json.dumps(scene, allow_nan=True)
        try:
            loaded = fenestra.Scene.from_json(text, str(small_room.parent), "fuzz.json")
        except ValueError as e:
            assert "sky" in str(e), (key, value, str(e))
            continue
        assert loaded.has_climate


def da_tolerance(records_year, occupied, relative_se):
    """How far a sensor's DA300 from an independent estimate of the same year may lie: the share of
    occupied hours whose value lies within four relative standard errors of 300 lux (an hour moves
    by about the mean's relative error), the only hours that can change sides."""
    e = records_year[:, occupied]
    return (np.abs(e - 300.0) <= 4.0 * relative_se[:, None] * e).mean(axis=1)


def test_cli_cutters_traces_the_year_with_the_openings_cut(small_room, tmp_path):
    path = climate_room(small_room)
    r = cli("annual", path, "--openings", tmp_path / "window.json", "-o", tmp_path / "cut", "--cutters",
            "--paths", 32768, "--quiet")
    assert r.returncode == 0, r.stderr
    assert "openings cut" in r.stdout and "sDA" in r.stdout
    r = cli("annual", path, "--openings", tmp_path / "window.json", "-o", tmp_path / "records", "--quiet")
    assert r.returncode == 0, r.stderr
    cut, records = np.load(tmp_path / "cut.npz"), np.load(tmp_path / "records.npz")
    cs = json.loads((tmp_path / "cut.json").read_text())
    rs = json.loads((tmp_path / "records.json").read_text())
    assert cs["paths"] == "traced with the openings cut" and rs["paths"] == "contribution records"
    assert cs["paths_per_sensor"] == 32768 and "mean_illuminance_from_records_lux" not in cs["per_sensor"]
    assert cut["illuminance"].shape == records["illuminance"].shape == (3, 8760)
    occupied = cut["occupied"].astype(bool)

    # The means: two independent estimates of the same year, within four combined standard errors.
    mean_cut = np.array(cs["per_sensor"]["mean_illuminance_lux"])
    mean_records = np.array(rs["per_sensor"]["mean_illuminance_lux"])
    se = np.hypot(cs["per_sensor"]["mean_illuminance_stderr_lux"], rs["per_sensor"]["mean_illuminance_stderr_lux"])
    assert np.all(np.abs(mean_cut - mean_records) <= 4 * se), (mean_cut, mean_records, se)
    assert np.allclose(mean_cut, cut["illuminance"][:, occupied].mean(axis=1), rtol=1e-5)

    # The sun straight to the sensor is the same ray both ways: equal wherever both see it; only
    # rays grazing the window's edges may differ.
    d_cut, d_records = cut["direct_sun"], records["direct_sun"]
    both = (d_cut > 0) & (d_records > 0)
    assert np.array_equal(d_cut[both], d_records[both])
    differ = (d_cut > 0) != (d_records > 0)
    assert differ.sum() <= 0.01 * both.sum(), (differ.sum(), both.sum())
    # ASE: a sensor's hours above 1000 lux move by at most its differing hours.
    allowed = (differ & occupied).sum(axis=1)
    assert np.all(np.abs(cut["ase_hours"] - records["ase_hours"]) <= allowed)
    undecided = np.abs(records["ase_hours"] - 250) <= allowed
    assert abs(cs["space"]["annual_sunlight_exposure"] - rs["space"]["annual_sunlight_exposure"]) <= undecided.mean()

    # DA300 per sensor within its derived tolerance; sDA300/50 % changes only by sensors whose DA
    # is that close to 50 %.
    tolerance = da_tolerance(records["illuminance"], occupied, se / mean_records)
    da_cut, da_records = cut["daylight_autonomy"], records["daylight_autonomy"]
    assert np.all(np.abs(da_cut - da_records) <= tolerance + 1e-9), (da_cut, da_records, tolerance)
    undecided = np.abs(da_records - 0.5) <= tolerance
    assert abs(cs["space"]["spatial_daylight_autonomy"] - rs["space"]["spatial_daylight_autonomy"]) <= undecided.mean()


def test_python_cutters_match_the_cli_and_refuse_bad_input(small_room, tmp_path):
    path = climate_room(small_room)
    scene = fenestra.load_scene(path)
    a = fenestra.annual(scene, WINDOW, cutters=True, paths=2048, output=tmp_path / "py")
    assert a["summary"]["paths"] == "traced with the openings cut" and a["summary"]["paths_per_sensor"] == 2048
    r = cli("annual", path, "--openings", tmp_path / "window.json", "-o", tmp_path / "cli", "--cutters",
            "--paths", 2048, "--threads", 1, "--quiet")
    assert r.returncode == 0, r.stderr
    assert np.array_equal(a["illuminance"], np.load(tmp_path / "cli.npz")["illuminance"])  # any thread count
    assert np.array_equal(np.load(tmp_path / "py.npz")["illuminance"], a["illuminance"])

    off = {"openings": [WINDOW["openings"][0], {"corners": [[0.5, 5, 1.0], [2.5, 5, 1.0], [2.5, 5, 2.0],
                                                            [0.5, 5, 2.0]]}]}
    with pytest.raises(ValueError, match="opening 1"):
        fenestra.annual(scene, off, cutters=True, output=tmp_path / "off")
    assert not list(tmp_path.glob("off.*"))
    (tmp_path / "off.json").write_text(json.dumps(off))
    r = cli("annual", path, "--openings", tmp_path / "off.json", "-o", tmp_path / "out", "--cutters", "--quiet")
    assert r.returncode == 1 and "opening 1" in r.stderr, r.stderr
    assert not list(tmp_path.glob("out.*"))
    with pytest.raises(ValueError, match="contributions"):
        fenestra.annual(scene, WINDOW, contributions=fenestra.contributions(scene), cutters=True)
    with pytest.raises(ValueError, match="paths"):
        fenestra.annual(scene, WINDOW, cutters=True, paths=-1)
    r = cli("evaluate", path, "--openings", tmp_path / "window.json", "-o", tmp_path / "e.json", "--cutters")
    assert r.returncode == 2 and "--cutters" in r.stderr
    json_scene = json.loads(small_room.read_text())
    json_scene["sky"] = {"type": "uniform", "radiance": 100}
    plain = fenestra.Scene.from_json(json.dumps(json_scene), str(small_room.parent), "plain.json")
    with pytest.raises(ValueError, match="climate"):
        fenestra.annual(plain, WINDOW, cutters=True)


def test_cutters_study_openings_off_the_grid_in_a_thick_wall(small_room):
    path = climate_room(small_room)
    scene_json = json.loads(path.read_text())
    scene_json["opening_domain"]["thickness"] = 0.25
    path.write_text(json.dumps(scene_json))
    scene = fenestra.load_scene(path)
    # 0.1 m inside the window on every side: off the 0.5 m grid, which the records refuse in a thick wall.
    inset = {"openings": [{"corners": [[0.6, 0, 1.1], [2.4, 0, 1.1], [2.4, 0, 1.9], [0.6, 0, 1.9]]}]}
    seen = []
    with pytest.raises(ValueError, match="opening 0 has an edge between the element grid's lines"):
        fenestra.annual(scene, inset, callback=lambda fraction, status: seen.append(status))
    assert seen == []  # refused before any path is traced
    small = fenestra.annual(scene, inset, cutters=True, paths=8192)
    full = fenestra.annual(scene, WINDOW, cutters=True, paths=8192)
    # The smaller hole lets the sun through a subset of the rays, none of them more.
    assert np.all(small["direct_sun"] <= full["direct_sun"])
    assert 0 < (small["direct_sun"] > 0).sum() < (full["direct_sun"] > 0).sum()
    # The year's light follows the hole: less through the smaller one at every sensor (28 % less
    # area; each mean's standard error is about 1 %).
    small_mean = np.array(small["summary"]["per_sensor"]["mean_illuminance_lux"])
    full_mean = np.array(full["summary"]["per_sensor"]["mean_illuminance_lux"])
    se = np.hypot(small["summary"]["per_sensor"]["mean_illuminance_stderr_lux"],
                  full["summary"]["per_sensor"]["mean_illuminance_stderr_lux"])
    assert np.all(small_mean + 4 * se < full_mean), (small_mean, full_mean, se)
