"""The cost model (docs/cost.md): work that will not fit in memory, or would take too long, is
refused before it starts, with a message naming the figure and the setting; --max-memory and
max_memory override the detected limit; an address-space limit (ulimit -v) is respected."""

import json
import os
import re
import shlex
import shutil
import subprocess
import sys

import pytest

import fenestra
from conftest import CLI, EXAMPLES, ROOT, box_obj

REFERENCE = os.path.join(EXAMPLES, "reference_room", "scene.json")
SIZE = re.compile(r"\d[\d.]* [kMGTPE]B\b")  # a figure such as "11.5 GB"


def run(*args, timeout=120):
    return subprocess.run([CLI, *map(str, args)], capture_output=True, text=True, timeout=timeout)


def run_limited(kb, *args, timeout=300):
    """The CLI under `ulimit -v kb` (an address-space limit, as a memory-capped shell sets)."""
    command = "ulimit -v %d; exec %s" % (kb, " ".join(shlex.quote(str(a)) for a in [CLI, *args]))
    return subprocess.run(["bash", "-c", command], capture_output=True, text=True, timeout=timeout)


def outputs(directory):
    return sorted(p.name for p in directory.iterdir() if p.name.startswith("out"))


def assert_refused(r, *fragments):
    assert r.returncode == 1, (r.returncode, r.stderr)
    assert r.stderr.startswith("fenestra: error: "), r.stderr
    assert "bad_alloc" not in r.stderr and "out of memory" not in r.stderr, r.stderr
    for fragment in fragments:
        assert fragment in r.stderr, (fragment, r.stderr)


def write_room(tmp_path, scale=1.0, element_size=0.5, sky=None, solver=None, sensors=4):
    """A 4 x 3 x 2.6 m room (times `scale`: 1000 is an OBJ exported in millimetres), its south wall
    the opening domain."""
    (tmp_path / "room.obj").write_text(
        box_obj((0, 0, 0), (4 * scale, 3 * scale, 2.6 * scale), lambda f: "facade" if f == "south" else "grey"))
    scene = {
        "fenestra": 1, "geometry": "room.obj",
        "materials": {"grey": {"reflectance": 0.5}, "facade": {"reflectance": 0.5}},
        "opening_domain": {"materials": ["facade"], "element_size": element_size},
        "sensors": {"points": [[0.5 + i * 3.0 / max(1, sensors - 1), 1.5, 0.8] for i in range(sensors)]},
        "goals": {"uniform": [{"level": 0.5}]},
        "sky": sky or {"type": "uniform", "radiance": 100},
        "render": {"paths_per_sensor": 256},
    }
    if solver:
        scene["solver"] = solver
    path = tmp_path / "scene.json"
    path.write_text(json.dumps(scene))
    return path


def test_tiny_elements_are_refused_quickly(tmp_path):
    scene = write_room(tmp_path, element_size=0.001)
    for command in ("contributions", "solve"):
        r = run(command, scene, "-o", tmp_path / "out.npz", "--quiet", timeout=60)  # finishes at all: not diced
        assert_refused(r, "element_size 0.001 m gives about 10 400 000 elements", "matrix T", "larger element_size",
                       "--max-memory")
        assert SIZE.search(r.stderr), r.stderr
    assert outputs(tmp_path) == []


def test_huge_path_counts_are_refused(tmp_path):
    r = run("contributions", REFERENCE, "-o", tmp_path / "out.npz", "--paths", 2 ** 30, "--quiet", timeout=60)
    assert_refused(r, "1 073 741 824 paths per sensor", "path records", "--paths", "--max-memory")
    assert re.search(r"\d[\d.]* [TP]B", r.stderr), r.stderr
    r = run("solve", REFERENCE, "-o", tmp_path / "out.json", "--paths", 2 ** 30, "--quiet", timeout=60)
    assert_refused(r, "1 073 741 824 paths per sensor")
    assert outputs(tmp_path) == []


def test_lying_hdr_header_is_refused_before_reading_its_pixels(tmp_path):
    (tmp_path / "sky.hdr").write_bytes(b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 15000 +X 30000\n"
                                       + bytes([2, 2, 0x75, 0x30]) + bytes(range(16)))
    scene = write_room(tmp_path, sky={"type": "envmap", "file": "sky.hdr"})
    for command in ("sky", "contributions"):
        out = tmp_path / ("out.exr" if command == "sky" else "out.npz")
        r = run(command, scene, "-o", out, "--quiet", timeout=60)
        assert_refused(r, "sky.file", "30000 x 15000 pixels", "at most 134 217 728")
        assert SIZE.search(r.stderr), r.stderr
    assert outputs(tmp_path) == []
    with pytest.raises(ValueError, match="30000 x 15000"):
        fenestra.load_scene(scene)


def test_millimetre_obj_is_refused(tmp_path):
    scene = write_room(tmp_path, scale=1000.0, element_size=0.25)
    for command in ("contributions", "sky"):  # sky does not use the elements; the dicing alone is refused
        out = tmp_path / ("out.exr" if command == "sky" else "out.npz")
        r = run(command, scene, "-o", out, "--quiet", timeout=60)
        assert_refused(r, "millimetres", "element_size")
    assert outputs(tmp_path) == []


def test_max_memory_lowers_the_limit(tmp_path):
    r = run("contributions", REFERENCE, "-o", tmp_path / "out.npz", "--paths", 4096, "--quiet", "--max-memory", "10M")
    assert_refused(r, "10.0 MB allowed by --max-memory", "4 096 paths per sensor")
    assert outputs(tmp_path) == []
    r = run("contributions", REFERENCE, "-o", tmp_path / "out.npz", "--paths", 256, "--quiet", "--max-memory", "1G")
    assert r.returncode == 0, r.stderr
    for bad in ("1X", "-1G", "G", "0"):
        r = run("contributions", REFERENCE, "-o", tmp_path / "bad.npz", "--max-memory", bad)
        assert r.returncode == 2 and "--max-memory expects a size" in r.stderr, r.stderr


def test_a_refusal_names_the_paths_that_fit_and_the_estimate_is_printed_first(tmp_path):
    r = run("contributions", REFERENCE, "-o", tmp_path / "out.npz", "--paths", 4096, "--quiet", "--max-memory", "10M")
    fit = re.search(r"at most ([\d ]+) per sensor fit", r.stderr)
    assert r.returncode == 1 and fit, r.stderr
    n = int(fit.group(1).replace(" ", ""))
    assert 1 <= n < 4096
    # The figure is the largest that fits: it runs, one more path per sensor is refused.
    r = run("contributions", REFERENCE, "-o", tmp_path / "out.npz", "--paths", n, "--max-memory", "10M")
    assert r.returncode == 0, r.stderr
    assert re.search(r"estimated memory: path records [\d.]+ [kMG]B \(%s paths per sensor x \d+ sensors\), "
                     r"[\d.]+ [kMG]B at the peak; 10.0 MB allowed by --max-memory" % fit.group(1), r.stderr), r.stderr
    r = run("contributions", REFERENCE, "-o", tmp_path / "more.npz", "--paths", n + 1, "--quiet", "--max-memory", "10M")
    assert r.returncode == 1 and "at most %s per sensor fit" % fit.group(1) in r.stderr, r.stderr


def test_max_memory_overrides_an_address_space_limit(tmp_path):
    # What is left under `ulimit -v 1000000` (about 1 GB, minus what the program maps at start):
    # read from the refusal of a run that cannot fit. Threads create their malloc arenas (64 MB of
    # address space each) when they first allocate, so it varies from run to run: the most of a few.
    lefts = []
    for _ in range(4):
        r = run_limited(1000000, "contributions", REFERENCE, "-o", tmp_path / "out.npz", "--paths", 2 ** 24, "--quiet")
        assert_refused(r, "left under the address-space limit (ulimit -v)")
        found = re.search(r"([\d.]+) (MB|GB) left under", r.stderr)
        lefts.append(float(found.group(1)) * (1e6 if found.group(2) == "MB" else 1e9))
    left = max(lefts)
    # A run whose estimate is well above it (by two arenas at least: a run's own reading can be an
    # arena above the most of those; the estimate is fixed bytes and bytes per path): refused ...
    scene = fenestra.load_scene(REFERENCE)
    totals = []
    for n in (1024, 2048):
        scene.render.paths_per_sensor = n
        totals.append(fenestra.estimate_cost(scene, "contributions")["total_bytes"])
    per_path = (totals[1] - totals[0]) / 1024
    fixed = totals[0] - 1024 * per_path
    paths = int((max(1.6 * left, left + 2 * 64e6) - fixed) / per_path)
    r = run_limited(1000000, "contributions", REFERENCE, "-o", tmp_path / "out.npz", "--paths", paths, "--quiet")
    assert_refused(r, "left under the address-space limit", "%s paths per sensor" % format(paths, ",").replace(",", " "))
    # ... and with --max-memory the cost model lets it run (the model is conservative: it fits, or
    # the allocation fails with a clean message, never a signal).
    r = run_limited(1000000, "contributions", REFERENCE, "-o", tmp_path / "out.npz", "--paths", paths, "--quiet",
                    "--max-memory", "100G")
    assert r.returncode in (0, 1), (r.returncode, r.stderr)
    assert "left under the address-space limit" not in r.stderr, r.stderr
    if r.returncode == 1:
        assert "out of memory" in r.stderr, r.stderr


def test_memory_cap_gives_a_clear_message_not_a_signal(tmp_path):
    """Under `ulimit -v 2000000` (2 GB of address space), work that needs more is refused with rc 1."""
    for command, args in (("contributions", ("--paths", 2 ** 22)), ("solve", ("--paths", 2 ** 22)),
                          ("evaluate", ("--openings", os.path.join(EXAMPLES, "reference_room", "window.json"),
                                        "--paths", 64))):
        r = run_limited(2000000, command, REFERENCE, "-o", tmp_path / "out.json", "--quiet", *args)
        if command == "evaluate":  # small: runs within the cap
            assert r.returncode == 0, r.stderr
            continue
        assert_refused(r, "left under the address-space limit (ulimit -v)", "4 194 304 paths per sensor")
        assert SIZE.search(r.stderr)
    scene = write_room(tmp_path, element_size=0.05)  # 80 x 52 elements: T alone 138 MB
    r = run_limited(2000000, "contributions", scene, "-o", tmp_path / "t.npz", "--quiet", "--paths", 64)
    assert r.returncode == 0, r.stderr


def test_genetic_and_local_search_budgets_are_bounded(tmp_path):
    scene = write_room(tmp_path, solver={"generations": 10000000})
    r = run("solve", scene, "-o", tmp_path / "out.json", "--quiet", timeout=60)
    assert_refused(r, "genetic algorithm would take about", "solver.generations (10 000 000)", "solver.time_budget_s")
    scene = write_room(tmp_path, solver={"improve_iterations": 100000000}, sensors=100)
    r = run("solve", scene, "-o", tmp_path / "out.json", "--quiet", timeout=60)
    assert_refused(r, "local search", "solver.improve_iterations (100 000 000)")
    assert outputs(tmp_path) == []


def test_long_daylight_interval_is_refused_when_read(tmp_path):
    sky = {"type": "preetham", "latitude": 48.85, "longitude": 2.35, "utc_offset": 1, "date": "2020-01-01",
           "date_end": "2024-12-31", "start": "09:00", "end": "17:00", "step_minutes": 15}
    scene = write_room(tmp_path, sky=sky)
    r = run("sky", scene, "-o", tmp_path / "out.exr", "--quiet", timeout=120)
    assert_refused(r, "58 464 time steps", "min", "sky.step_minutes")
    assert outputs(tmp_path) == []
    sky["step_minutes"] = 60  # a quarter of the steps: about 2.5 min of build (not run here)
    with pytest.raises(ValueError, match="58 464 time steps"):
        fenestra.scene_from_dict(dict(json.loads(scene.read_text()), sky=dict(sky, step_minutes=15)), tmp_path)


def test_python_estimate_and_check(tmp_path):
    scene = fenestra.load_scene(REFERENCE)
    scene.render.paths_per_sensor = 1024
    e = fenestra.estimate_cost(scene, "contributions")
    S, N = 16, 192
    assert e["sensors"] == S and e["elements"] == N and e["fits"] and e["problem"] is None
    assert e["memory"]["E"] == e["memory"]["A"] == e["memory"]["E_stderr"] == 8 * S * N
    assert e["memory"]["T"] == 8 * N * N
    assert e["total_bytes"] >= e["kept_bytes"] > 0 and e["available_bytes"] > 0
    c = fenestra.contributions(scene)
    assert c.memory_bytes <= e["kept_bytes"] <= 2 * c.memory_bytes
    small = fenestra.estimate_cost(scene, "contributions", max_memory="1M")
    assert not small["fits"] and "1.0 MB allowed by max_memory" in small["problem"]
    with pytest.raises(ValueError, match="path records"):
        fenestra.check_cost(scene, "contributions", max_memory=1_000_000)
    fenestra.check_cost(scene, "solve", max_memory="64G")
    for bad in ("lots", -5, 0, True, [1], float("nan"), 1e39, 2 ** 70):
        with pytest.raises(ValueError):
            fenestra.check_cost(scene, "solve", max_memory=bad)
    with pytest.raises(ValueError, match="unknown command"):
        fenestra.estimate_cost(scene, "render")
    available = fenestra.available_memory()
    assert available["bytes"] > 0 and available["source"]


def test_python_functions_refuse_before_any_work(tmp_path):
    scene = fenestra.load_scene(REFERENCE)
    scene.render.paths_per_sensor = 2 ** 30
    calls = []
    for call in (lambda: fenestra.contributions(scene, callback=lambda f, s: calls.append(f)),
                 lambda: fenestra.solve(scene, callback=lambda f, s: calls.append(f))):
        with pytest.raises(ValueError, match="1 073 741 824 paths per sensor"):
            call()
    assert calls == []  # refused before the worker thread started
    scene.render.paths_per_sensor = 256
    with pytest.raises(ValueError, match="allowed by max_memory"):
        fenestra.contributions(scene, max_memory="100k")
    assert fenestra.evaluate(scene, [], max_memory="1G")[0].shape == (16,)
    with pytest.raises(ValueError, match="element_size 0.001 m"):
        fenestra.load_scene(write_room(tmp_path, element_size=0.001))
    with pytest.raises(ValueError, match="allowed by --max-memory"):
        fenestra.load_scene(REFERENCE, max_memory=1000)
    # The limit applies to that call only.
    assert fenestra.load_scene(REFERENCE).element_count == 192


def test_solve_estimate_counts_the_thick_walls_edge_cuts(tmp_path):
    """A solve in a thick wall places its openings' edges with real cutters (docs/solver.md,
    step 7), searching them by pairs only with a catalogue, tries a panel's several openings as one
    and moves every side at once: their time is in the estimate, for as many openings as the
    constraints allow, and not without a thickness or with refine_edges off."""
    path = write_room(tmp_path)
    d = json.loads(path.read_text())
    d["opening_domain"]["thickness"] = 0.3
    d["solver"] = {"constraints": {"max_openings": 1}}
    path.write_text(json.dumps(d))
    one = fenestra.estimate_cost(fenestra.load_scene(str(path)), "solve")
    assert one["seconds"]["thick_wall_edges"] > 0
    assert "verification_scene" in one["memory"]
    d["solver"] = {"constraints": {"max_openings": 3}}
    path.write_text(json.dumps(d))
    three = fenestra.estimate_cost(fenestra.load_scene(str(path)), "solve")
    # Free sizes are only placed: two cuts, however many openings.
    assert three["seconds"]["thick_wall_edges"] == pytest.approx(one["seconds"]["thick_wall_edges"])
    # One panel can hold several of three openings: it is tried with one (the thick-wall merges).
    assert "thick_wall_merges" not in one["seconds"]
    assert three["seconds"]["thick_wall_merges"] > three["seconds"]["thick_wall_edges"]
    # Every side moved at once: two cuts per side per step, and the judged cuts of each step.
    assert 0 < one["seconds"]["thick_wall_joint_edges"] < three["seconds"]["thick_wall_joint_edges"]
    assert three["seconds"]["thick_wall_joint_edges"] > three["seconds"]["thick_wall_edges"]
    # A catalogue's openings slide by pairs of edges: about 130 cuts each, against the placement's two.
    catalogue = [[0.9, 1.2], [1.2, 1.5]]
    searched = {}
    for n in (1, 3):
        d["solver"] = {"constraints": {"max_openings": n, "catalogue": catalogue}}
        path.write_text(json.dumps(d))
        searched[n] = fenestra.estimate_cost(fenestra.load_scene(str(path)), "solve")["seconds"]["thick_wall_edges"]
    assert searched[3] == pytest.approx(3 * searched[1])
    assert searched[1] == pytest.approx(65 * one["seconds"]["thick_wall_edges"])
    d["solver"] = {"refine_edges": False}
    path.write_text(json.dumps(d))
    off = fenestra.estimate_cost(fenestra.load_scene(str(path)), "solve")
    assert "thick_wall_edges" not in off["seconds"] and "thick_wall_joint_edges" not in off["seconds"]
    thin = fenestra.estimate_cost(fenestra.load_scene(str(write_room(tmp_path))), "solve")
    assert "thick_wall_edges" not in thin["seconds"]


def test_thick_wall_cuts_follow_the_solves_paths(tmp_path):
    """The thick-wall stages cut with a sixteenth of the solve's paths per sensor, from 128 to
    1 024 (docs/solver.md, step 7): a preview's 2 048 paths cut with 128, a final solve's 16 384
    and more with 1 024; the estimate follows, in proportion."""
    path = write_room(tmp_path)
    d = json.loads(path.read_text())
    d["opening_domain"]["thickness"] = 0.3
    seconds = {}
    for paths in (2048, 16384, 65536):
        d["solver"] = {"paths": paths, "constraints": {"max_openings": 1}}
        path.write_text(json.dumps(d))
        estimate = fenestra.estimate_cost(fenestra.load_scene(str(path)), "solve")
        seconds[paths] = estimate["seconds"]["thick_wall_edges"]
    assert seconds[2048] == pytest.approx(seconds[16384] / 8)
    assert seconds[65536] == pytest.approx(seconds[16384])


def test_solve_estimate_counts_the_edge_search_index(tmp_path):
    """The edge search indexes where the paths met the domain (docs/cost.md): 2 x the path
    records while solving, unless refine_edges is off; the contributions alone have none."""
    path = write_room(tmp_path)
    scene = fenestra.load_scene(str(path))
    e = fenestra.estimate_cost(scene, "solve")
    assert e["memory"]["edge_search_index"] == pytest.approx(2.0 * e["memory"]["path_records"])
    assert "edge_search_index" not in fenestra.estimate_cost(scene, "contributions")["memory"]
    d = json.loads(path.read_text())
    d["solver"] = {"refine_edges": False}
    path.write_text(json.dumps(d))
    assert "edge_search_index" not in fenestra.estimate_cost(fenestra.load_scene(str(path)), "solve")["memory"]


def test_solve_estimate_counts_the_exact_values_index(tmp_path):
    """The exact evaluation indexes the elements each path met and keeps two references' values
    and the last sample's path values (docs/cost.md): half the path records and 11 bytes per path
    while solving; the contributions
    alone have none."""
    scene = fenestra.load_scene(str(write_room(tmp_path)))
    e = fenestra.estimate_cost(scene, "solve")
    paths = scene.sensor_count * scene.render.paths_per_sensor
    assert e["memory"]["exact_values_index"] == pytest.approx(0.5 * e["memory"]["path_records"] + 11 * paths)
    assert "exact_values_index" not in fenestra.estimate_cost(scene, "contributions")["memory"]


def test_solve_estimate_counts_the_flip_effects_kept(tmp_path):
    """The solver keeps up to 16 flip-effect matrices (8 bytes per sensor and element), at most
    128 MiB in all, and none when one matrix alone is larger (docs/cost.md)."""
    budget = 128 * 2**20
    for element_size, sensors, kept in ((0.5, 4, "16"), (0.05, 400, "budget"), (0.05, 5000, "none")):
        scene = fenestra.load_scene(str(write_room(tmp_path, element_size=element_size, sensors=sensors)))
        one = 8.0 * scene.sensor_count * scene.element_count
        expected = {"16": 16 * one, "budget": budget, "none": 0.0}[kept]
        assert {"16": 16 * one <= budget, "budget": one <= budget < 16 * one, "none": one > budget}[kept]
        assert fenestra.estimate_cost(scene, "solve")["memory"]["flip_effects_kept"] == pytest.approx(expected)
    assert "flip_effects_kept" not in fenestra.estimate_cost(scene, "contributions")["memory"]


def test_solve_estimate_counts_the_search_over_whole_openings(tmp_path):
    """Each set the search over whole openings scores keeps its exact values and open mask, and
    re-evaluates the paths that met the elements it changes (docs/cost.md): both in proportion to
    solver.search_evaluations, none without the search."""
    path = write_room(tmp_path)
    scene = fenestra.load_scene(str(path))
    e = fenestra.estimate_cost(scene, "solve")
    sensors, elements = scene.sensor_count, scene.element_count
    assert e["memory"]["opening_search_values"] == pytest.approx(3000 * (16 * sensors + elements + 96))
    paths = scene.render.paths_per_sensor
    assert e["seconds"]["opening_search"] == pytest.approx(3000 * sensors * paths * 40e-9)
    assert "thick_wall_openings" not in e["seconds"] and "change_reach" not in e["memory"]  # a thin wall
    d = json.loads(path.read_text())
    d["opening_domain"]["thickness"] = 0.3
    path.write_text(json.dumps(d))
    e = fenestra.estimate_cost(fenestra.load_scene(str(path)), "solve")
    assert e["memory"]["thick_wall_openings_values"] == pytest.approx(3000 * (24 * sensors + elements + 160))
    assert e["memory"]["change_reach"] == pytest.approx(sensors * elements)  # the thick-wall cuts' reach
    assert e["seconds"]["thick_wall_openings"] == pytest.approx(3000 * sensors * paths * 40e-9)
    d["solver"] = {"search_evaluations": 0}
    path.write_text(json.dumps(d))
    e = fenestra.estimate_cost(fenestra.load_scene(str(path)), "solve")
    assert e["memory"]["opening_search_values"] == 0 and e["seconds"]["opening_search"] == 0
    assert e["memory"]["thick_wall_openings_values"] == 0 and e["seconds"]["thick_wall_openings"] == 0


def test_daylight_steps_cost_their_own_time(tmp_path):
    """Each step with the sun up creates its sky (about 2 ms, whatever the map's size): at 64 x 32 a
    year of 1-minute steps would take about 6 minutes and is refused; 5 years of 15-minute steps
    are refused at the default resolution (docs/cost.md, "Time limits")."""
    sky = {"type": "preetham", "latitude": 48.85, "longitude": 2.35, "utc_offset": 1, "date": "2021-01-01",
           "date_end": "2021-12-31", "start": "09:00", "end": "17:00", "step_minutes": 1, "resolution": [64, 32]}
    scene = write_room(tmp_path, sky=sky)
    r = run("sky", scene, "-o", tmp_path / "out.exr", "--quiet", timeout=120)
    assert_refused(r, "175 200 time steps", "at 64 x 32 pixels", "about 6 min", "sky.step_minutes")
    assert outputs(tmp_path) == []
    five_years = dict(sky, date="2020-01-01", date_end="2024-12-31", step_minutes=15, resolution=[1024, 512])
    with pytest.raises(ValueError, match="58 464 time steps"):
        fenestra.scene_from_dict(dict(json.loads(scene.read_text()), sky=five_years), tmp_path)


ANNUAL_PEAK = r"""
import json, sys
import fenestra
scene_path, openings_path, paths, limit = sys.argv[1], sys.argv[2], int(sys.argv[3]), sys.argv[4]
scene = fenestra.load_scene(scene_path)
openings = fenestra.read_openings(openings_path)
estimate = fenestra.estimate_cost(scene, "annual_cutters", max_memory=limit, paths=paths)
def status(key):
    return next(int(l.split()[1]) * 1024 for l in open("/proc/self/status") if l.startswith(key))
fenestra.annual(scene, openings, cutters=True, paths=16)  # threads, the ray scene, the sources once
with open("/proc/self/clear_refs", "w") as f:
    f.write("5")  # the peak resident size from here on
before = status("VmRSS")
fenestra.annual(scene, openings, cutters=True, paths=paths, max_memory=limit)
print(json.dumps({"grown": status("VmHWM") - before, "estimate": estimate}))
"""


def test_annual_with_cutters_is_checked_before_any_work(small_room, tmp_path):
    """`annual --cutters --paths 1073741824` would hold the replicate sums of 8.4 million tasks per
    sensor and their rows of coefficients: refused at once, naming the paths that fit. The largest
    accepted run under a limit runs, its measured peak within the estimate; one path more is refused."""
    from test_annual import climate_room
    scene_path = climate_room(small_room)
    window = tmp_path / "window.json"
    r = run("annual", scene_path, "--openings", window, "-o", tmp_path / "out", "--cutters", "--paths", 2 ** 30,
            "--quiet")
    assert_refused(r, "1 073 741 824 paths per sensor for 3 sensors, in tasks of 128 paths",
                   "fewer paths (render.paths_per_sensor, --paths): at most")
    assert outputs(tmp_path) == []
    scene = fenestra.load_scene(scene_path)
    calls = []
    with pytest.raises(ValueError, match="1 073 741 824 paths per sensor"):
        fenestra.annual(scene, fenestra.read_openings(str(window)), cutters=True, paths=2 ** 30,
                        callback=lambda *a: calls.append(a))
    assert calls == []

    limit = "12M"  # a few of the year's sources' rows at most: about 60 000 paths per sensor fit
    refused = fenestra.estimate_cost(scene, "annual_cutters", max_memory=limit, paths=2 ** 30)
    fit = re.search(r"at most ([\d ]+) per sensor fit", refused["problem"])
    assert not refused["fits"] and fit, refused["problem"]
    n = int(fit.group(1).replace(" ", ""))
    assert fenestra.estimate_cost(scene, "annual_cutters", max_memory=limit, paths=n)["fits"]
    with pytest.raises(ValueError, match="at most %s per sensor fit" % fit.group(1)):
        fenestra.check_cost(scene, "annual_cutters", max_memory=limit, paths=n + 1)
    env = dict(os.environ, PYTHONPATH=os.path.join(ROOT, "addon"))
    r = subprocess.run([sys.executable, "-c", ANNUAL_PEAK, str(scene_path), str(window), str(n), limit],
                       capture_output=True, text=True, timeout=600, env=env)
    assert r.returncode == 0, r.stderr
    measured = json.loads(r.stdout)
    estimate = measured["estimate"]
    # The estimate bounds what the run added at its peak, and is not loose: the rows dominate.
    assert measured["grown"] <= estimate["total_bytes"] <= 12e6, (measured["grown"], estimate["memory"])
    assert measured["grown"] >= 0.5 * estimate["total_bytes"], (measured["grown"], estimate["memory"])
