"""The fenestra command-line program: outputs, formats and errors."""

import json
import os
import subprocess

import numpy as np
import pytest

from conftest import CLI, EXAMPLES, write_stacked_panels


def run(*args):
    return subprocess.run([CLI, *map(str, args)], capture_output=True, text=True)


def test_contributions_writes_npz_and_summary(small_room, tmp_path):
    out = tmp_path / "contrib.npz"
    r = run("contributions", small_room, "-o", out, "--paths", 256, "--quiet")
    assert r.returncode == 0, r.stderr
    with np.load(out) as data:
        assert data["E"].shape == (3, 30)
        assert data["T"].shape == (30, 30)
        E = data["E"]
    summary = json.loads((tmp_path / "contrib.json").read_text())
    assert summary["element_count"] == 30 and summary["sensors"] == 3
    first = summary["elements"][0]
    assert {"index", "panel", "row", "col", "corners"} <= set(first)
    assert np.array(first["corners"]).shape == (4, 3)
    assert len(summary["all_open"]) == 3
    assert np.isfinite(E).all()
    assert summary["dropped"] == {"non_finite": 0, "truncated_conditions": 0}  # a sound scene drops nothing
    assert "left out" not in r.stderr


def test_evaluate_reads_openings_and_writes_values(small_room, tmp_path):
    openings = tmp_path / "openings.json"
    openings.write_text(json.dumps({"openings": [{"corners": [[1, 0, 1], [2, 0, 1], [2, 0, 2], [1, 0, 2]]}]}))
    out = tmp_path / "eval.json"
    r = run("evaluate", small_room, "--openings", openings, "-o", out, "--paths", 512, "--quiet")
    assert r.returncode == 0, r.stderr
    sensors = json.loads(out.read_text())["sensors"]
    assert len(sensors) == 3
    assert all(s["value"] > 0 and s["stderr"] > 0 for s in sensors)


def test_reference_room_example_runs(tmp_path):
    scene = os.path.join(EXAMPLES, "reference_room", "scene.json")
    window = os.path.join(EXAMPLES, "reference_room", "window.json")
    r = run("evaluate", scene, "--openings", window, "-o", tmp_path / "e.json", "--paths", 256, "--quiet")
    assert r.returncode == 0, r.stderr


def test_reference_room_with_its_sky_in_closed_form_runs(tmp_path):
    # The reference's sky as a uniform sky over a uniform ground: the same light as the image.
    values = {}
    for scene_file in ("scene.json", "scene_uniform.json"):
        scene = os.path.join(EXAMPLES, "reference_room", scene_file)
        window = os.path.join(EXAMPLES, "reference_room", "window.json")
        out = tmp_path / (scene_file + ".values.json")
        r = run("evaluate", scene, "--openings", window, "-o", out, "--paths", 4096, "--quiet")
        assert r.returncode == 0, r.stderr
        values[scene_file] = [(s["value"], s["stderr"]) for s in json.loads(out.read_text())["sensors"]]
    for (a, sa), (b, sb) in zip(values["scene.json"], values["scene_uniform.json"]):
        assert abs(a - b) <= 5.5 * (sa * sa + sb * sb) ** 0.5, (a, b)  # t(15) quantile of a normal 4 sigma


def test_the_program_loads_openimageio_only_to_read_or_write_images():
    # OpenImageIO and its ~250 libraries live in the image module (fenestra_images.so), loaded on
    # first use: the program itself does not link them.
    linked = subprocess.run(["ldd", CLI], capture_output=True, text=True).stdout
    assert "libfenestra" not in linked and "OpenImageIO" not in linked, linked
    module = os.path.join(EXAMPLES, "..", "addon", "fenestra", "fenestra_images.so")
    assert os.path.exists(module)
    assert "OpenImageIO" in subprocess.run(["ldd", module], capture_output=True, text=True).stdout


@pytest.mark.parametrize("content, fragment", [
    ("{", "not valid JSON"),
    ('{"fenestra": 1}', "materials"),
    ('{"fenestra": 2}', "version"),
])
def test_bad_scene_fails_cleanly_without_output(tmp_path, content, fragment):
    scene = tmp_path / "bad.json"
    scene.write_text(content)
    out = tmp_path / "out.npz"
    r = run("contributions", scene, "-o", out, "--quiet")
    assert r.returncode == 1
    assert fragment in r.stderr and "bad.json" in r.stderr
    assert list(tmp_path.iterdir()) == [scene]  # nothing half-written


def test_bad_openings_fail_cleanly(small_room, tmp_path):
    openings = tmp_path / "openings.json"
    openings.write_text(json.dumps({"openings": [{"corners": [[1, 3, 1], [2, 3, 1], [2, 3, 2], [1, 3, 2]]}]}))
    out = tmp_path / "eval.json"
    r = run("evaluate", small_room, "--openings", openings, "-o", out, "--quiet")
    assert r.returncode == 1 and "opening 0" in r.stderr
    assert not out.exists()
    r = run("evaluate", small_room, "--openings", tmp_path / "missing.json", "-o", out, "--quiet")
    assert r.returncode == 1 and "missing.json" in r.stderr


def test_missing_output_directory_is_an_error(small_room, tmp_path):
    r = run("contributions", small_room, "-o", tmp_path / "no" / "such" / "dir" / "c.npz", "--paths", 8, "--quiet")
    assert r.returncode == 1 and "does not exist" in r.stderr


@pytest.mark.parametrize("args", [[], ["frobnicate", "x"], ["contributions"], ["contributions", "s.json"],
                                  ["evaluate", "s.json", "-o", "x.json"], ["contributions", "s", "-o", "x", "--paths", "-3"]])
def test_usage_errors_exit_2(args):
    r = run(*args)
    assert r.returncode == 2 and "usage" in r.stderr


def test_contributions_report_what_the_tracer_dropped(tmp_path):
    scene = write_stacked_panels(tmp_path)
    out = tmp_path / "contrib.npz"
    r = run("contributions", scene, "-o", out, "--quiet")
    assert r.returncode == 0, r.stderr
    dropped = json.loads((tmp_path / "contrib.json").read_text())["dropped"]
    assert dropped["truncated_conditions"] > 0 and dropped["non_finite"] == 0
    assert "fenestra: warning: the tracer left out %d light values or sub-paths that met more than 32 " \
           "elements" % dropped["truncated_conditions"] in r.stderr


def test_a_solve_that_dropped_light_says_so_among_its_warnings(tmp_path):
    """The warning travels in the result's "warnings" (what the Python API and Blender show), and is
    printed once."""
    scene_path = write_stacked_panels(tmp_path)
    scene = json.loads(scene_path.read_text())
    scene["sensors"]["goals"] = [0.3]  # a uniform sky: in normalized units
    scene["solver"] = {"generations": 5, "population": 8, "verify": False, "tradeoffs": False}
    scene_path.write_text(json.dumps(scene))
    out = tmp_path / "result.json"
    r = run("solve", scene_path, "-o", out, "--quiet")
    assert r.returncode == 0, r.stderr
    result = json.loads(out.read_text())
    assert result["dropped"]["truncated_conditions"] > 0
    said = [w for w in result["warnings"] if w.startswith("the tracer left out")]
    assert len(said) == 1 and str(result["dropped"]["truncated_conditions"]) in said[0]
    assert r.stderr.count("fenestra: warning: the tracer left out") == 1
    # Its summary line counts in words: "1 opening", "3 openings".
    openings, opened = len(result["openings"]), len(result["open_elements"])
    assert r.stdout.startswith("solve: %d opening%s, %d open element%s;" % (
        openings, "" if openings == 1 else "s", opened, "" if opened == 1 else "s")), r.stdout
