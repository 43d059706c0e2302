"""Models in site coordinates (UTM eastings near 5e5 m, northings up to 1e7 m) give the numbers of
the same model at the origin, and every output comes back in the coordinates it was given in."""
import json
import subprocess

import numpy as np
import pytest
from scipy import stats

import fenestra
from conftest import CLI, write_small_room

# A t bound for a normal 4 sigma at 15 degrees of freedom per standard error (16 replicate groups).
BOUND = stats.t.isf(stats.norm.sf(4.0), 15)
WINDOW = [[0.5, 0, 0.5], [2.5, 0, 0.5], [2.5, 0, 2.0], [0.5, 0, 2.0]]  # on the south wall, room coordinates


def write_room(folder, offset, paths=2048, goals=None):
    """The conftest's small room moved by `offset` (meters), with goals in lux if given, and
    window.json: WINDOW in the same coordinates; returns the scene file's path."""
    path = write_small_room(folder, offset, paths=paths)
    if goals is not None:
        scene = json.loads(path.read_text())
        scene["goals"] = {"per_sensor": goals, "units": "lux"}
        path.write_text(json.dumps(scene))
    (folder / "window.json").write_text(json.dumps({"openings": [{"corners": (np.array(WINDOW) + offset).tolist()}]}))
    return path


UTM = (499_993.0, 9_999_990.0, 187.0)  # an easting, a northing near the limit, an elevation


def agree(a, sa, b, sb):
    return np.all(np.abs(np.asarray(a) - b) <= BOUND * np.hypot(sa, sb))


def test_a_room_at_utm_coordinates_gives_the_origins_numbers(tmp_path):
    home = fenestra.load_scene(write_room(tmp_path / "home", (0, 0, 0)))
    site = fenestra.load_scene(write_room(tmp_path / "site", UTM))
    np.testing.assert_allclose(site.sensor_points - UTM, home.sensor_points, atol=1e-9)
    np.testing.assert_allclose(site.element_corners - UTM, home.element_corners, atol=1e-6)
    c_home, c_site = fenestra.contributions(home), fenestra.contributions(site)
    assert np.all(c_site.closed == 0.0), c_site.closed  # a closed room leaks nothing
    assert np.all(c_home.all_open > 0)
    assert agree(c_site.all_open, c_site.all_open_stderr, c_home.all_open, c_home.all_open_stderr)
    # Rectangles given in site coordinates: as openings of the contributions and really cut.
    window = np.array([WINDOW])
    v_home, s_home = fenestra.evaluate(home, window)
    v_site, s_site = fenestra.evaluate(site, window + UTM)
    assert agree(v_site, s_site, v_home, s_home)
    e_home, _ = c_home.evaluate_openings(home, window)
    e_site, _ = c_site.evaluate_openings(site, window + UTM)
    assert agree(e_site, c_site.all_open_stderr, e_home, c_home.all_open_stderr)


def test_the_cli_writes_site_coordinates_and_reads_them(tmp_path):
    home = write_room(tmp_path / "home", (0, 0, 0))
    site = write_room(tmp_path / "site", UTM)
    out = {}
    for name, scene in (("home", home), ("site", site)):
        subprocess.run([CLI, "contributions", str(scene), "-o", str(tmp_path / name / "c.npz"), "--quiet"], check=True)
        subprocess.run([CLI, "evaluate", str(scene), "--openings", str(scene.parent / "window.json"),
                        "-o", str(tmp_path / name / "e.json"), "--quiet"], check=True)
        out[name] = (np.load(tmp_path / name / "c.npz"), json.loads((tmp_path / name / "c.json").read_text()),
                     json.loads((tmp_path / name / "e.json").read_text()))
    (npz_h, sum_h, ev_h), (npz_s, sum_s, ev_s) = out["home"], out["site"]
    np.testing.assert_allclose(npz_s["element_corners"] - UTM, npz_h["element_corners"], atol=1e-6)
    corners_s = np.array([e["corners"] for e in sum_s["elements"]])
    np.testing.assert_allclose(corners_s - UTM, np.array([e["corners"] for e in sum_h["elements"]]), atol=1e-6)
    np.testing.assert_allclose(np.array(sum_s["panels"][0]["origin"]) - UTM, sum_h["panels"][0]["origin"], atol=1e-6)
    assert np.all(npz_s["closed"] == 0.0)
    assert agree(npz_s["all_open"], npz_s["all_open_stderr"], npz_h["all_open"], npz_h["all_open_stderr"])
    vs = [(s["value"], s["stderr"]) for s in ev_s["sensors"]]
    vh = [(s["value"], s["stderr"]) for s in ev_h["sensors"]]
    assert agree([v for v, _ in vs], [e for _, e in vs], [v for v, _ in vh], [e for _, e in vh])


@pytest.mark.parametrize("axis", [0, 1, 2])
def test_a_solve_far_away_returns_its_openings_where_the_model_is(tmp_path, axis):
    # Moved by whole meters away from the origin, a model keeps its local frame: the solve is the
    # same bit for bit, its openings moved by exactly the offset.
    goals = [300.0, 120.0, 350.0]
    results = []
    for k, distance in enumerate((1e5, 9e6)):
        offset = np.zeros(3)
        offset[axis] = distance
        scene = fenestra.load_scene(write_room(tmp_path / str(k), offset, paths=512, goals=goals))
        result = fenestra.solve(scene)
        results.append((offset, result))
    (o1, r1), (o2, r2) = results
    assert r1["openings"], "the solve found no opening"
    assert [s["predicted"] for s in r1["sensors"]] == [s["predicted"] for s in r2["sensors"]]
    assert len(r1["openings"]) == len(r2["openings"])
    for a, b in zip(r1["openings"], r2["openings"]):
        np.testing.assert_allclose(np.array(a["corners"]) - o1, np.array(b["corners"]) - o2, atol=1e-6)
        np.testing.assert_allclose(np.array(a["centre"]) - o1, np.array(b["centre"]) - o2, atol=1e-6)
        # and on the model's south wall (y = offset), within the room's 3 m
        corners = np.array(b["corners"]) - o2
        assert np.all(np.abs(corners[:, 1]) < 1e-6) and corners[:, 0].min() >= -1e-6 and corners[:, 0].max() <= 3 + 1e-6
    # The result's corners read back as they were written.
    path = tmp_path / "openings.json"
    path.write_text(json.dumps({"openings": [{"corners": o["corners"]} for o in r2["openings"]]}))
    read = fenestra.read_openings(str(path))
    np.testing.assert_array_equal(np.asarray(read), np.array([o["corners"] for o in r2["openings"]]))


def test_coordinates_beyond_the_utm_range_are_refused(tmp_path):
    with pytest.raises(ValueError, match=r"sensors.points\[0\].*1e\+07 m"):
        scene = write_room(tmp_path / "far", (0, 9_999_990.0, 0))
        data = json.loads(scene.read_text())
        data["sensors"]["points"][0][1] = 1.2e7
        scene.write_text(json.dumps(data))
        fenestra.load_scene(scene)
    with pytest.raises(ValueError, match=r"1e\+06 m from the model's local origin"):
        fenestra.evaluate(fenestra.load_scene(write_room(tmp_path / "near", UTM, paths=16)),
                          np.array([WINDOW]))  # room coordinates given for a model on the site


def test_a_cluster_gives_one_process_numbers_at_utm_coordinates(tmp_path):
    pytest.importorskip("distributed")
    from fenestra import distributed

    path = write_room(tmp_path / "site", UTM, paths=256)
    window = np.array([WINDOW]) + UTM
    scene = fenestra.load_scene(str(path))
    one = fenestra.contributions(scene)
    cut = fenestra.evaluate(scene, window)
    with distributed.Cluster(workers=2, threads_per_worker=1, timeout=30) as cluster, \
            distributed.contributions(str(path), cluster, shards=3) as many:
        for name in ("E", "A", "T", "closed", "all_open", "all_open_stderr"):
            assert np.array_equal(np.asarray(getattr(many, name)), np.asarray(getattr(one, name))), name
        assert np.array_equal(many.evaluate_openings(window)[0], one.evaluate_openings(scene, window)[0])
        sharded = distributed.evaluate(str(path), window, cluster, shards=3)
        assert np.array_equal(sharded[0], cut[0]) and np.array_equal(sharded[1], cut[1])
        many.save(str(tmp_path / "many"))
    corners = np.load(tmp_path / "many.npz")["element_corners"]
    np.testing.assert_allclose(corners, scene.element_corners, atol=0)
    assert corners[..., 1].min() > 9e6  # in the input's coordinates
