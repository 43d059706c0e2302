"""Bad input through the command line and Python: every number is
checked after its conversion, and every error names the file and the key or line in words. The
command line exits with status 1 (2 for usage errors), never on a signal, and writes nothing;
Python raises ValueError with the same text."""

import json
import os
import re
import subprocess
import warnings

import numpy as np
import pytest

from conftest import CLI

import fenestra


def run(*args, timeout=120):
    return subprocess.run([CLI, *map(str, args)], capture_output=True, text=True, errors="replace",
                          timeout=timeout)


def edited(small_room, edit, name="bad.json"):
    """A copy of the small room's scene.json with `edit(scene_dict)` applied."""
    scene = json.loads(small_room.read_text())
    edit(scene)
    path = small_room.parent / name
    path.write_text(json.dumps(scene))
    return path


def expect_cli_error(scene, fragments, command="contributions", extra=(), status=1):
    folder = scene.parent
    before = sorted(os.listdir(folder))
    out = folder / ("out.npz" if command == "contributions" else "out.json")
    if command == "evaluate" and "--openings" not in extra:
        extra = (*extra, "--openings", write_openings(folder, [[1, 0, 1], [2, 0, 1], [2, 0, 2], [1, 0, 2]]))
        before = sorted(os.listdir(folder))
    r = run(command, scene, "-o", out, "--quiet", "--paths", 16, *extra)
    assert r.returncode == status, (r.returncode, r.stderr)  # a signal gives a negative status
    for fragment in fragments:
        assert fragment in r.stderr, r.stderr
    assert "json.exception" not in r.stderr, r.stderr
    assert sorted(os.listdir(folder)) == before  # no output, not even a partial one
    return r.stderr


def expect_python_error(scene, fragments):
    with pytest.raises(ValueError) as error:
        fenestra.load_scene(scene)
    for fragment in fragments:
        assert fragment in str(error.value)
    assert "json.exception" not in str(error.value)
    return str(error.value)


def write_openings(folder, *corners):
    path = folder / "openings.json"
    path.write_text(json.dumps({"openings": [{"corners": c} for c in corners]}))
    return path


def set_in(*keys_and_value):
    *keys, value = keys_and_value

    def edit(scene):
        d = scene
        for k in keys[:-1]:
            d = d.setdefault(k, {})
        d[keys[-1]] = value
    return edit


ROOM_SENSOR = [1.5, 1.0, 0.8]
POLAR = {"type": "preetham", "latitude": 78.0, "longitude": 15.0, "utc_offset": 1, "date": "2026-12-21",
         "resolution": [64, 32]}

# (case, edit of the scene dict, fragments the message must contain besides the file name)
SCENE_CASES = [
    # Coordinates: 1e39 is infinite as a float, 2e18 aborted inside Embree.
    ("sensor 1e39", set_in("sensors", "points", [ROOM_SENSOR, [1e39, 1, 1]]), ["sensors.points[1]", "1e+07 m"]),
    ("sensor 2e18", set_in("sensors", "points", [[2e18, 1, 1]]), ["sensors.points[0]", "1e+07 m"]),
    ("normal 1e30", set_in("sensors", "normals", [1e30, 0, 0]), ["sensors.normals[0]"]),
    ("normal 1e-30", set_in("sensors", "normals", [1e-30, 0, 0]), ["sensors.normals[0]", "zero"]),
    # Integers: read as int, 4294967297 was 1; the others wrapped.
    ("version 2^32+1", set_in("fenestra", 4294967297), ["fenestra", "4294967297"]),
    ("resolution 2^32+128", set_in("sky", {"type": "cie_overcast", "resolution": [4294967424, 64]}),
     ["sky.resolution[0]", "16384"]),
    ("paths 2^32", set_in("render", "paths_per_sensor", 4294967296), ["render.paths_per_sensor", "1073741824"]),
    ("threads 2^31", set_in("render", "threads", 2147483648), ["render.threads", "4096"]),
    # Radiance and angles as floats: 1e39 cd/m^2 gave all zeros.
    ("radiance 1e39", set_in("sky", "radiance", 1e39), ["sky.radiance"]),
    ("radiance 1e13", set_in("sky", "radiance", [1, 1, 1e13]), ["sky.radiance", "1e+12 cd/m^2"]),
    ("sky without type", set_in("sky", {"radiance": 100}), ["sky.type", "missing"]),
    ("north offset 1e300", set_in("sky", dict(POLAR, north_offset_deg=1e300)), ["sky.north_offset_deg", "360"]),
    ("step 1e-300 minutes", set_in("sky", dict(POLAR, step_minutes=1e-300)), ["sky.step_minutes"]),
    ("overcast 1e300 lux", set_in("sky", {"type": "cie_overcast", "horizontal_illuminance": 1e300}),
     ["sky.horizontal_illuminance", "lux"]),
    ("thickness 1e30", set_in("opening_domain", "thickness", 1e30), ["opening_domain.thickness"]),
    ("module -0.05", set_in("solver", "constraints", "module", -0.05), ["solver.constraints.module"]),
    ("module 1e300", set_in("solver", "constraints", "module", 1e300), ["module"]),
    ("refine_edges 1", set_in("solver", "refine_edges", 1), ["solver.refine_edges", "true or false"]),
    ("verify_paths -1", set_in("solver", "verify_paths", -1), ["solver.verify_paths", "whole number"]),
    ("verify_paths 2.5", set_in("solver", "verify_paths", 2.5), ["solver.verify_paths", "whole number"]),
    ("verify_paths 1e300", set_in("solver", "verify_paths", 1e300), ["solver.verify_paths"]),
    ("search_evaluations -1", set_in("solver", "search_evaluations", -1), ["solver.search_evaluations", "whole number"]),
    ("search_evaluations 2^32", set_in("solver", "search_evaluations", 4294967296),
     ["solver.search_evaluations", "10000000"]),
    ("search_evaluations 1.5", set_in("solver", "search_evaluations", 1.5), ["solver.search_evaluations", "whole number"]),
    ("search_evaluations null", set_in("solver", "search_evaluations", None),
     ["solver.search_evaluations", "expected a number"]),
    ("lux goal 1e300", lambda s: s["sensors"].update(goals=[1e300, 1, 1], goal_units="lux"), ["goals[0]"]),
    # Messages name the key in words rather than nlohmann's "[json.exception.type_error.302]".
    ("sky type 3", set_in("sky", "type", 3), ["sky.type", "expected a string"]),
    ("material type 3", set_in("materials", "grey", "type", 3), ["materials.grey.type", "expected a string"]),
]


@pytest.mark.parametrize("case, edit, fragments", SCENE_CASES, ids=[c[0] for c in SCENE_CASES])
def test_bad_numbers_are_refused_by_the_cli(small_room, case, edit, fragments):
    expect_cli_error(edited(small_room, edit), ["bad.json", *fragments])


@pytest.mark.parametrize("case, edit, fragments", SCENE_CASES, ids=[c[0] for c in SCENE_CASES])
def test_bad_numbers_raise_value_error_in_python(small_room, case, edit, fragments):
    path = edited(small_room, edit)
    expect_python_error(path, ["bad.json", *fragments])
    with pytest.raises(ValueError) as error:
        fenestra.scene_from_dict(json.loads(path.read_text()), small_room.parent)
    assert all(f in str(error.value) for f in fragments), str(error.value)


def test_json_number_overflow_names_file_line_and_key(small_room):
    text = json.dumps(json.loads(small_room.read_text()), indent=1).replace("0.8", "1e400", 1)
    bad = small_room.parent / "bad.json"
    bad.write_text(text)
    line = text[:text.index("1e400")].count("\n") + 1
    fragments = ["bad.json", "line %d" % line, "sensors.points[0][2]", "1e400"]
    expect_cli_error(bad, fragments)
    expect_python_error(bad, fragments)


def test_obj_indices_and_coordinates_are_checked_with_their_line(small_room):
    room = (small_room.parent / "room.obj").read_text()
    lines = room.count("\n")
    cases = [
        ("f 1 2 18446744073709551619\n", ["line %d" % (lines + 2), "18446744073709551619"]),  # wrapped past 2^64
        ("f 1 2 999\n", ["line %d" % (lines + 2), "past the last vertex"]),
        ("f 1 2 -999\n", ["line %d" % (lines + 2), "-999"]),
    ]
    for face, fragments in cases:
        (small_room.parent / "bad.obj").write_text(room + "usemtl grey\n" + face)
        scene = edited(small_room, set_in("geometry", "bad.obj"))
        expect_cli_error(scene, ["bad.obj", *fragments])
        expect_python_error(scene, ["bad.obj", *fragments])
    (small_room.parent / "bad.obj").write_text(room.replace("v 0 0 0", "v 0 0 2e+07", 1))
    scene = edited(small_room, set_in("geometry", "bad.obj"))
    expect_cli_error(scene, ["bad.obj", "line 3", "out of range"])
    expect_python_error(scene, ["bad.obj", "line 3", "out of range"])


def test_envmap_scale_and_rotation_must_stay_finite(small_room):
    fenestra.write_image(str(small_room.parent / "sky.exr"), np.full((8, 16, 3), 1000.0, np.float32))
    envmap = {"type": "envmap", "file": "sky.exr"}
    for extra, fragments in [({"scale": 1e300}, ["sky.scale"]),
                             ({"scale": 1e10}, ["sky.file", "brightest pixel"]),  # 1e13 cd/m^2
                             ({"rotation_deg": 1e300}, ["sky.rotation_deg", "360"])]:
        scene = edited(small_room, set_in("sky", dict(envmap, **extra)))
        expect_cli_error(scene, ["bad.json", *fragments])
        expect_python_error(scene, ["bad.json", *fragments])
    fenestra.load_scene(edited(small_room, set_in("sky", dict(envmap, scale=2.0, rotation_deg=-90))))


def test_openings_out_of_range_are_refused(small_room):
    openings = write_openings(small_room.parent, [[1, 0, 1], [2, 0, 1], [2, 0, 2], [1e39, 0, 2]])
    expect_cli_error(small_room, ["openings.json", "opening 0", "corner 3", "1e+07 m"], command="evaluate",
                     extra=("--openings", openings))
    scene = fenestra.load_scene(small_room)
    with pytest.raises(ValueError, match="opening 0, corner 3"):
        fenestra.evaluate(scene, [[[1, 0, 1], [2, 0, 1], [2, 0, 2], [1e39, 0, 2]]])
    with pytest.raises(ValueError, match="opening 0, corner 0"):
        fenestra.evaluate(scene, [[[2e18, 0, 1], [2, 0, 1], [2, 0, 2], [1, 0, 2]]])


@pytest.mark.parametrize("flag, value", [("--paths", 4294967296), ("--paths", 4294967297), ("--paths", 0),
                                         ("--threads", 2147483648), ("--threads", 4097), ("--seed", -1),
                                         ("--seed", 2 ** 64 + 1)])
def test_cli_counts_are_bounded_like_the_scene_keys(small_room, flag, value):
    folder = small_room.parent
    before = sorted(os.listdir(folder))
    r = run("contributions", small_room, "-o", folder / "out.npz", "--quiet", flag, value)
    assert r.returncode == 2, r.stderr
    assert flag in r.stderr and str(value) in r.stderr and "integer from" in r.stderr
    assert sorted(os.listdir(folder)) == before


@pytest.mark.parametrize("attribute, value", [("paths_per_sensor", 0), ("paths_per_sensor", 2 ** 32),
                                              ("paths_per_sensor", -1), ("max_bounces", 1001),
                                              ("threads", 2 ** 31), ("threads", -1), ("seed", 2 ** 64)])
def test_render_setters_validate_like_the_loader(small_room, attribute, value):
    scene = fenestra.load_scene(small_room)
    before = getattr(scene.render, attribute)
    with pytest.raises(ValueError, match="render.%s" % attribute):
        setattr(scene.render, attribute, value)
    assert getattr(scene.render, attribute) == before
    with pytest.raises(TypeError, match="render.%s" % attribute):
        setattr(scene.render, attribute, 1.5)
    setattr(scene.render, attribute, np.int64(1))  # NumPy integers are integers
    assert getattr(scene.render, attribute) == 1


def test_non_regular_input_files_are_refused(small_room):
    for edit, fragments in [(set_in("geometry", "/dev/zero"), ["geometry", "/dev/zero", "not a regular file"]),
                            (set_in("sky", {"type": "envmap", "file": "/dev/zero"}),
                             ["sky.file", "/dev/zero", "not a regular file"]),
                            (set_in("geometry", "."), ["geometry", "not a regular file"])]:
        scene = edited(small_room, edit)
        expect_cli_error(scene, ["bad.json", *fragments])  # /dev/zero was read forever
        expect_python_error(scene, fragments)
    r = run("contributions", "/dev/zero", "-o", small_room.parent / "out.npz", "--quiet", timeout=60)
    assert r.returncode == 1 and "not a regular file" in r.stderr


def test_polar_night_is_refused_by_solve_and_warned_by_evaluate(small_room):
    def polar(scene):
        scene["sky"] = POLAR
        scene["sensors"]["goals"] = [0.5, 0.5, 0.5]
    path = edited(small_room, polar)
    message = expect_cli_error(path, ["bad.json", "2026-12-21", "78, 15", "below the horizon"], command="solve")
    assert "cannot be met" in message
    out = small_room.parent / "eval.json"
    openings = write_openings(small_room.parent, [[1, 0, 1], [2, 0, 1], [2, 0, 2], [1, 0, 2]])
    r = run("evaluate", path, "--openings", openings, "-o", out, "--paths", 16, "--quiet")
    assert r.returncode == 0, r.stderr
    assert "warning" in r.stderr and "below the horizon" in r.stderr
    assert all(s["value"] == 0 for s in json.loads(out.read_text())["sensors"])

    scene = fenestra.load_scene(path)
    scene.render.paths_per_sensor = 16
    with pytest.raises(ValueError, match="2026-12-21"):
        fenestra.solve(scene)
    with pytest.warns(RuntimeWarning, match="below the horizon"):
        fenestra.evaluate(scene, [])
    with pytest.warns(RuntimeWarning, match="below the horizon"):
        fenestra.contributions(scene)
    daylit = fenestra.load_scene(edited(small_room, set_in("sky", dict(POLAR, latitude=48.0)), "day.json"))
    daylit.render.paths_per_sensor = 16
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        fenestra.evaluate(daylit, [])


def test_contributions_of_another_scene_are_refused(small_room, tmp_path):
    scene = fenestra.load_scene(small_room)
    scene.render.paths_per_sensor = 32
    c = fenestra.contributions(scene)

    def with_goals(s):
        s["sensors"]["goals"] = [0.5] * len(s["sensors"]["points"])
    more = edited(small_room, lambda s: (s["sensors"]["points"].append([1, 1, 1]), with_goals(s)), "more.json")
    with pytest.raises(ValueError, match="3 sensors x 30 elements.*4 sensors x 30 elements"):
        fenestra.solve(fenestra.load_scene(more), contributions=c)
    # Same counts, other sensors: caught by the fingerprint (it used to solve the wrong scene).
    moved = edited(small_room, lambda s: (s["sensors"]["points"].__setitem__(0, [1.5, 2.0, 0.8]), with_goals(s)),
                   "moved.json")
    with pytest.raises(ValueError, match="moved.json.*sensors or the element grid differ"):
        fenestra.solve(fenestra.load_scene(moved), contributions=c)
    other_sky = fenestra.load_scene(edited(small_room, set_in("sky", "radiance", 50), "sky50.json"))
    with pytest.raises(ValueError, match="different sky"):
        c.save(other_sky, str(tmp_path / "c"))
    assert not (tmp_path / "c.npz").exists() and not (tmp_path / "c.json").exists()
    with pytest.raises(ValueError, match="sensors or the element grid differ"):
        c.save(fenestra.load_scene(moved), str(tmp_path / "c"))
    assert not (tmp_path / "c.npz").exists()
    c.save(fenestra.load_scene(small_room), str(tmp_path / "c"))  # the same scene, loaded again
    assert (tmp_path / "c.npz").exists()


def test_messages_with_bytes_that_are_not_utf8_reach_python(small_room):
    folder = os.fsencode(small_room.parent)
    with pytest.raises(ValueError) as error:
        fenestra.load_scene(os.path.join(folder, b"sc\xffne.json"))  # was an empty ValueError
    # The byte that is not UTF-8 is named, as in any path a message quotes.
    assert "cannot open scene file" in str(error.value) and "sc\\xFFne.json" in str(error.value)
    bad = small_room.parent / "bad.json"
    bad.write_bytes(small_room.read_bytes().replace(b"room.obj", b"ro\xffom.obj"))
    message = expect_python_error(bad, ["bad.json", "not valid JSON", "line 1"])
    assert "UTF-8" in message
    r = run("contributions", bad, "-o", small_room.parent / "out.npz", "--quiet")
    assert r.returncode == 1 and "not valid JSON" in r.stderr


def test_out_of_memory_is_reported_in_words(small_room):
    """A sky map of 16384 x 8192 under a 1.5 GB address-space limit: refused up front or out of
    memory, but in words, with status 1 and no signal."""
    import resource

    scene = edited(small_room, set_in("sky", {"type": "cie_overcast", "resolution": [16384, 8192]}))

    def limit():
        resource.setrlimit(resource.RLIMIT_AS, (1500 << 20, 1500 << 20))
    r = subprocess.run([CLI, "sky", str(scene), "-o", str(small_room.parent / "sky.exr"), "--quiet"],
                       capture_output=True, text=True, errors="replace", preexec_fn=limit, timeout=300)
    assert r.returncode == 1, r.stderr
    assert "memory" in r.stderr and "bad.json" in r.stderr and "std::bad_alloc" not in r.stderr
    assert not (small_room.parent / "sky.exr").exists()


# ---- Python inputs: open masks, openings, goals, the sun -----------------------------------------


@pytest.fixture
def small_contributions(small_room):
    scene = fenestra.load_scene(small_room)
    scene.render.paths_per_sensor = 64
    return scene, fenestra.contributions(scene)


@pytest.mark.parametrize("bad, shown", [(0.5, "0.5"), (np.nan, "nan"), (np.inf, "inf"), (2.0, "2.0"), (-1, "-1"),
                                        (2, "2"), (1 + 0j, "(1+0j)"), (0.5j, "0.5j"), ("1", "'1'"), (None, "None")])
def test_open_masks_hold_only_zero_and_one(small_contributions, bad, shown):
    """A mask value that is neither closed nor open was read as one of them (0.5 as closed, NaN as
    open, ...): it is refused, naming the first bad entry and its value."""
    scene, c = small_contributions
    mask = [1, 0, 1, 0] + [0] * (scene.element_count - 4)
    mask[3] = bad
    with pytest.raises(ValueError, match=r"open mask entry 3 is %s: an open mask holds bools, or integers or floats "
                                         r"that are exactly 0 \(closed\) or 1 \(open\)" % re.escape(shown)):
        c.evaluate(mask)
    with pytest.raises(ValueError, match="open mask entry 3 is"):
        c.annual(mask)  # checked before anything else
    if isinstance(bad, (int, float)):  # in an array of numbers too (complex ones are all refused: entry 0)
        with pytest.raises(ValueError, match="open mask entry 3 is"):
            c.evaluate(np.array(mask))


def test_open_masks_of_bools_integers_and_floats_agree(small_contributions):
    scene, c = small_contributions
    n = scene.element_count
    chosen = np.zeros(n, dtype=bool)
    chosen[[0, 2, n - 1]] = True
    expected = c.evaluate(chosen)
    for mask in (chosen.astype(np.int64), chosen.astype(np.uint8), chosen.astype(np.float32), chosen.astype(float),
                 [int(x) for x in chosen], [bool(x) for x in chosen], np.where(chosen, 1.0, -0.0),
                 np.array([int(x) for x in chosen], dtype=object)):
        v, e = c.evaluate(mask)
        assert np.array_equal(v, expected[0]) and np.array_equal(e, expected[1])
    with pytest.raises(ValueError, match=r"open mask has %d entries; the contributions have %d elements" % (n - 1, n)):
        c.evaluate(chosen[:-1])
    with pytest.raises(ValueError, match=r"open mask must have shape \(%d,\)" % n):
        c.evaluate(np.ones((2, n), dtype=bool))
    with pytest.raises(ValueError, match="open mask: expected an array"):
        c.evaluate([[1, 0], [1]])


def test_evaluate_openings_takes_every_form_of_an_openings_file(small_contributions):
    """Contributions.evaluate_openings refused {"panel", "parameter_rectangle"} openings, which an
    openings file and fenestra.evaluate take: it now takes the same forms, converted in one place."""
    scene, c = small_contributions
    a = scene.element_size
    grid, corners = scene.element_grid, scene.element_corners
    # Elements of panel 0, rows 1..2 and columns 1..3 (the rectangle [a, 4a] x [a, 3a]).
    inside = (grid[:, 0] == 0) & (grid[:, 1] >= 1) & (grid[:, 1] <= 2) & (grid[:, 2] >= 1) & (grid[:, 2] <= 3)
    assert inside.sum() == 6
    rectangle = {"u0": a, "u1": 4 * a, "v0": a, "v1": 3 * a}
    by_parameter = [{"panel": 0, "parameter_rectangle": rectangle}]
    box = corners[inside].reshape(-1, 3)
    lo, hi = box.min(axis=0), box.max(axis=0)
    assert lo[1] == hi[1] == 0.0  # the south wall
    by_corners = [[[lo[0], 0.0, lo[2]], [hi[0], 0.0, lo[2]], [hi[0], 0.0, hi[2]], [lo[0], 0.0, hi[2]]]]
    expected = c.evaluate(inside)
    for openings in (by_parameter, {"openings": by_parameter}, by_corners, np.array(by_corners),
                     [{"corners": by_corners[0]}], {"openings": [{"corners": by_corners[0]}]},
                     [{"corners": by_corners[0], "panel": 0, "parameter_rectangle": rectangle, "width": 3 * a}]):
        v, e = c.evaluate_openings(scene, openings)
        np.testing.assert_allclose(v, expected[0], rtol=1e-12, err_msg=repr(openings))
        np.testing.assert_allclose(e, expected[1], rtol=1e-12, err_msg=repr(openings))
    # Both forms in one list: the union.
    other = (grid[:, 0] == 0) & (grid[:, 1] == 3) & (grid[:, 2] == 0)
    cell = corners[other][0]
    mixed = [{"corners": cell.tolist()}, {"panel": 0, "parameter_rectangle": rectangle}]
    np.testing.assert_allclose(c.evaluate_openings(scene, mixed)[0], c.evaluate(inside | other)[0], rtol=1e-12)
    with pytest.raises(ValueError, match=r"a dict must be an openings file's \{\"openings\": \[...\]\}"):
        c.evaluate_openings(scene, {"panel": 0, "parameter_rectangle": rectangle})
    with pytest.raises(ValueError, match=r"opening 0: parameter_rectangle v1 is nan, not a finite number"):
        c.evaluate_openings(scene, [{"panel": 0, "parameter_rectangle": dict(rectangle, v1=float("nan"))}])
    with pytest.raises(ValueError, match=r"opening 1, corner 0: has a non-finite coordinate"):
        c.evaluate_openings(scene, [by_parameter[0], {"corners": [[float("inf"), 0, 1]] + by_corners[0][1:]}])


def test_goal_error_refuses_what_it_cannot_measure():
    goals, values = np.array([100.0, np.nan, 50.0]), np.array([90.0, 5.0, 50.0])
    assert fenestra.goal_error(goals, values)["worst_sensor"] == 0  # NaN: no goal, as null in a scene file
    for bad_goals, message in (([np.nan] * 3, "no sensor has a goal"), ([-1.0, np.nan, -5.0], "no sensor has a goal"),
                               ([100.0, np.inf, 50.0], r"goals\[1\] is inf: a goal is a number of lux up to 1e12"),
                               ([-np.inf, 1.0, 50.0], r"goals\[0\] is -inf"),
                               ([100.0, 1e300, 50.0], r"goals\[1\] is 1e\+300")):
        with pytest.raises(ValueError, match=message):
            fenestra.goal_error(np.array(bad_goals), values)
    for bad in (np.nan, np.inf, -np.inf, 1e300):
        with pytest.raises(ValueError, match=r"values\[1\] is .*: every value must be a finite number of lux"):
            fenestra.goal_error(goals, np.array([90.0, bad, 50.0]))
    with pytest.raises(ValueError, match="no sensor has a goal"):
        fenestra.goal_error(goals, values, weights=[0.0, 1.0, 0.0])
    for bad in (np.nan, -1.0, np.inf, 1e7):
        with pytest.raises(ValueError, match=r"weights\[2\] is .*: a weight is a number from 0 to 1e6"):
            fenestra.goal_error(goals, values, weights=[1.0, 1.0, bad])


def test_absurd_times_and_places_of_the_sun_are_refused():
    from fenestra import _core

    first = _core.utc_seconds("0001-01-01", "00:00", utc_offset=14)
    last = _core.utc_seconds("9999-12-31", "24:00", utc_offset=-14)
    for t in (first, last, 0.0):  # the instants a scene's dates can give
        zenith, azimuth = fenestra.solar_position(t, 45.0, 7.0)
        assert np.isfinite(zenith) and 0.0 <= azimuth < 360.0
    for t in (1e300, -1e300, np.nan, np.inf, first - 1, last + 1):
        with pytest.raises(ValueError, match=r"utc_seconds is .*: expected POSIX seconds of a date in the years 0001 "
                                             r"to 9999"):
            fenestra.solar_position(t, 45.0, 7.0)
    for kwargs, message in (({"latitude_deg": 90.5}, r"latitude_deg is 90.5: expected -90 to 90 degrees"),
                            ({"latitude_deg": np.nan}, "latitude_deg is nan"),
                            ({"longitude_deg": 181.0}, r"longitude_deg is 181: expected -180 to 180 degrees"),
                            ({"longitude_deg": -np.inf}, "longitude_deg is -inf"),
                            ({"elevation_m": 1e7}, r"elevation_m is 1e\+07: expected -1e\+06 to 1e\+06 m"),
                            ({"pressure_hpa": -1.0}, r"pressure_hpa is -1: expected 0 to 2000 hPa"),
                            ({"temperature_c": -300.0}, r"temperature_c is -300: expected -90 to 60 degrees C"),
                            ({"temperature_c": np.nan}, "temperature_c is nan")):
        args = dict({"utc_seconds": 1.7e9, "latitude_deg": 45.0, "longitude_deg": 7.0}, **kwargs)
        with pytest.raises(ValueError, match=message):
            fenestra.solar_position(**args)
    with pytest.raises(ValueError, match="latitude_deg is 91"):
        fenestra.sunrise_sunset("2024-06-21", 91.0, 0.0, utc_offset=0)
    with pytest.raises(ValueError, match="longitude_deg is 1000"):
        fenestra.sunrise_sunset("2024-06-21", 45.0, 1000.0, utc_offset=0)
    with pytest.raises(ValueError, match="zenith_deg is nan"):
        _core.sun_direction(np.nan, 0.0)


def rename(*keys_and_new):
    """An edit renaming the key at keys to new (a typo)."""
    *keys, new = keys_and_new

    def edit(scene):
        d = scene
        for k in keys[:-1]:
            d = d[k]
        d[new] = d.pop(keys[-1])
    return edit


# Typos at every level: each ran with the default before (0.25 m elements, reflectance 0.5, ...).
TYPO_CASES = [
    ("top level", rename("render", "rendr"), "rendr: unknown key; did you mean `render`?"),
    ("element size", rename("opening_domain", "element_size", "element_sise"),
     "opening_domain.element_sise: unknown key; did you mean `element_size`?"),
    ("reflectance", rename("materials", "grey", "reflectance", "reflectence"),
     "materials.grey.reflectence: unknown key; did you mean `reflectance`?"),
    ("sensors", rename("sensors", "normals", "normal"), "sensors.normal: unknown key; did you mean `normals`?"),
    ("sky type", rename("sky", "type", "tpye"), "sky.tpye: unknown key; did you mean `type`?"),
    ("render", rename("render", "max_bounces", "max_bounce"), "render.max_bounce: unknown key; did you mean"),
    ("solver", set_in("solver", "populaton", 8), "solver.populaton: unknown key; did you mean `population`?"),
    ("search_evaluations", set_in("solver", "search_evaluation", 5),
     "solver.search_evaluation: unknown key; did you mean `search_evaluations`?"),
    ("constraints", set_in("solver", "constraints", "min_widht", 0.5),
     "solver.constraints.min_widht: unknown key; did you mean `min_width`?"),
    ("catalogue", set_in("solver", "constraints", "catalogue", {"wals": [[1, 1]]}),
     "solver.constraints.catalogue.wals: unknown key; did you mean `walls`?"),
    ("goals", set_in("goals", {"uniform": [{"sensors": "all", "levl": 0.3}]}),
     "goals.uniform[0].levl: unknown key; did you mean `level`?"),
    ("glass reflectance", set_in("materials", "grey", {"type": "glass", "reflectance": 0.1}),
     "materials.grey.reflectance: unknown key"),
]


@pytest.mark.parametrize("case, edit, words", TYPO_CASES, ids=[c[0] for c in TYPO_CASES])
def test_a_typo_is_refused_naming_the_closest_key(small_room, case, edit, words):
    path = edited(small_room, edit)
    expect_cli_error(path, ["bad.json", words])
    expect_python_error(path, ["bad.json", words])
    with pytest.raises(ValueError, match="scene '<dict>': " + re.escape(words)):
        fenestra.scene_from_dict(json.loads(path.read_text()), small_room.parent)


def test_duplicate_keys_are_refused_with_their_lines(small_room):
    text = json.dumps(json.loads(small_room.read_text()), indent=1)
    text = text.replace('"element_size": 0.5', '"element_size": 0.5,\n  "element_size": 2', 1)
    bad = small_room.parent / "bad.json"
    bad.write_text(text)
    line = text[:text.index('"element_size": 2')].count("\n") + 1
    words = ["bad.json', line %d: opening_domain.element_size: the key is given twice (first on line %d)"
             % (line, line - 1)]
    expect_cli_error(bad, words)
    expect_python_error(bad, words)
    with pytest.raises(ValueError, match="materials: key 1 is not a string"):  # json.dumps: "1", a duplicate
        fenestra.scene_from_dict(dict(json.loads(small_room.read_text()), materials={"1": {}, 1: {}}))


def test_json_syntax_errors_are_in_words_and_short(small_room):
    bad = small_room.parent / "bad.json"
    for text, words in [('{"fenestra": 1,\n "sky": {"type": tru}}',
                         "line 2, column 18 (under key sky.type): expected a value (a number, string, true, false, "
                         "null, object or array), found 'tru'"),
                        ('{"fenestra": 0x10}', "found '0x10' (JSON numbers are finite and decimal"),
                        ('{"fenestra": 1,}', "expected a key in double quotes, found '}'"),
                        ("[" * 1000000, "nest deeper than 64 levels"),
                        ('{"a": "' + "x" * 100000, "a string has no closing")]:
        bad.write_text(text)
        message = expect_cli_error(bad, ["bad.json", words])
        assert len(message) < 2000 and "syntax error" not in message and "last read" not in message, message[:500]
        message = expect_python_error(bad, ["bad.json", words])
        assert len(message) < 600 and "syntax error" not in message and "literal" not in message, message[:500]


def test_nul_bytes_in_paths_are_refused(small_room, tmp_path):
    path = edited(small_room, set_in("geometry", "room.obj\u0000x"))  # loaded room.obj
    expect_cli_error(path, ["bad.json", "geometry", "room.obj\\u0000x", "NUL byte"])
    expect_python_error(path, ["geometry", "NUL byte"])
    with pytest.raises(ValueError, match="NUL byte"):
        fenestra.load_scene(str(small_room) + "\u0000x")
    scene = fenestra.load_scene(small_room)
    with pytest.raises(ValueError, match="NUL byte"):
        fenestra.write_sky(scene, str(tmp_path / "sky.exr\u0000x"))
    assert not (tmp_path / "sky.exr").exists()
    openings = write_openings(small_room.parent, [[1, 0, 1], [2, 0, 1], [2, 0, 2], [1, 0, 2]])
    with pytest.raises(ValueError, match="NUL byte"):
        fenestra.read_openings(str(openings) + "\u0000x")


@pytest.mark.parametrize("line, words", [("f", "at least 3 corners, got 0"), ("f 1", "at least 3 corners, got 1"),
                                         ("f 1 2", "at least 3 corners, got 2"),
                                         ("v 0x10 0 0", "'0x10' is not a finite decimal number"),
                                         ("v inf 0 0", "'inf' is not a finite decimal number"),
                                         ("v 1e 0 0", "'1e' is not a finite decimal number"),
                                         ("f 1/1/1/1 2 3", "is not v, v/vt, v//vn or v/vt/vn")])
def test_obj_lines_are_checked_in_fenestras_words(small_room, line, words):
    room = (small_room.parent / "room.obj").read_text()
    (small_room.parent / "bad.obj").write_text(room + "usemtl grey\n" + line + "\n")
    scene = edited(small_room, set_in("geometry", "bad.obj"))
    fragments = ["bad.obj', line %d: " % (room.count("\n") + 2), words]
    message = expect_cli_error(scene, fragments)
    assert "Failed parse" not in message  # tinyobjloader's words
    expect_python_error(scene, fragments)


def test_openings_keys_are_checked_in_files_and_dicts(small_room):
    corners = [[1, 0, 1], [2, 0, 1], [2, 0, 2], [1, 0, 2]]
    bad = small_room.parent / "openings.json"
    for openings, words in [({"openings": [{"corner": corners}]}, "opening 0: corner: unknown key; did you mean `corners`?"),
                            ({"opening": [{"corners": corners}]}, "opening: unknown key; did you mean `openings`?")]:
        bad.write_text(json.dumps(openings))
        expect_cli_error(small_room, ["openings.json", words], command="evaluate", extra=("--openings", bad))
        with pytest.raises(ValueError, match=re.escape(words)):
            fenestra.read_openings(str(bad))
        scene = fenestra.load_scene(small_room)
        with pytest.raises(ValueError, match="openings 'argument': " + re.escape(words)):
            fenestra.evaluate(scene, openings)
    with pytest.raises(ValueError, match=re.escape("opening 0: name: unknown key")):
        fenestra.evaluate(scene, [{"corners": corners, "name": "south window"}])
    with pytest.raises(ValueError, match=re.escape("opening 0, corner 0: has a non-finite coordinate")):
        fenestra.evaluate(scene, [{"corners": [[np.nan, 0, 1]] + corners[1:]}])


def test_scene_dicts_take_numpy_values_and_refuse_what_json_cannot_hold(small_room):
    scene = json.loads(small_room.read_text())
    scene["sensors"]["points"] = np.array(scene["sensors"]["points"], np.float32)
    scene["render"]["seed"] = np.int64(3)
    fenestra.scene_from_dict(scene, small_room.parent)  # "Object of type float32 is not JSON serializable"
    scene["sensors"]["points"][0][0] = np.nan
    with pytest.raises(ValueError, match=re.escape("scene '<dict>': sensors.points[0][0]: nan is not a finite")):
        fenestra.scene_from_dict(scene, small_room.parent)
    scene = json.loads(small_room.read_text())
    scene["sky"]["radiance"] = {1, 2}
    with pytest.raises(ValueError, match=re.escape("scene '<dict>': sky.radiance: a set is not a JSON value")):
        fenestra.scene_from_dict(scene, small_room.parent)
    deep = []
    for _ in range(100000):
        deep = [deep]
    scene["sky"]["radiance"] = deep  # json.dumps: RecursionError
    with pytest.raises(ValueError, match="nest deeper than 64 levels"):
        fenestra.scene_from_dict(scene, small_room.parent)


@pytest.mark.parametrize("flag, value", [("--max-memory", "0x10G"), ("--max-memory", "infG"),
                                         ("--max-memory", "1eG"), ("--paths", "0x10"), ("--paths", "1e3")])
def test_cli_numbers_take_the_decimal_form_only(small_room, flag, value):
    folder = small_room.parent
    before = sorted(os.listdir(folder))
    r = run("contributions", small_room, "-o", folder / "out.npz", "--quiet", flag, value)
    assert r.returncode == 2, r.stderr
    assert flag in r.stderr and value in r.stderr
    assert sorted(os.listdir(folder)) == before
    with pytest.raises(ValueError):
        fenestra.check_cost(fenestra.load_scene(small_room), "contributions", max_memory="0x10G")


def test_cluster_command_line_counts_are_ascii_digits():
    from fenestra import distributed_cli
    for value in ("\u00b2", "\u0663", "0x2", "+2", "2.0"):  # "²".isdigit() is True, int("²") raises
        with pytest.raises(distributed_cli.UsageError, match="--workers expects an integer"):
            distributed_cli.parse(["contributions", "s.json", "-o", "o.npz", "--workers", value])
