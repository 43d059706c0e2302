"""The opening solver through the documented interfaces: `fenestra solve`, fenestra.solve()."""

import json
import subprocess

import numpy as np
import pytest

import fenestra
import solve_stages
from conftest import CLI, box_obj


def run(*args):
    return subprocess.run([CLI, *map(str, args)], capture_output=True, text=True)


def with_goals(small_room, goals, units="lux", solver=None, **extra):
    scene = json.loads(small_room.read_text())
    scene["sensors"]["goals"] = goals
    scene["sensors"]["goal_units"] = units
    scene["solver"] = solver or {"generations": 100, "population": 32, "seed": 2}
    scene.update(extra)
    small_room.write_text(json.dumps(scene))
    return small_room


def test_cli_solve_writes_openings_that_evaluate_reads(small_room, tmp_path):
    scene = with_goals(small_room, [0.5, 0.3, None], units="normalized")
    out = tmp_path / "result.json"
    r = run("solve", scene, "-o", out, "--paths", 512, "--quiet")
    assert r.returncode == 0, r.stderr
    result = json.loads(out.read_text())
    assert {"openings", "sensors", "error", "open_elements", "timings_s", "stages", "genetic"} <= set(result)
    assert result["dropped"] == {"non_finite": 0, "truncated_conditions": 0}  # what tracing the records dropped
    assert len(result["sensors"]) == 3
    assert result["sensors"][2]["goal"] is None
    assert all(s["predicted"] >= 0 for s in result["sensors"])
    assert 0 <= result["error"]["relative_rms"] < 1
    history = [g["best"] for g in result["genetic"]["history"]]
    assert history == sorted(history, reverse=True)
    for o in result["openings"]:
        assert np.array(o["corners"]).shape == (4, 3)
    # The result file is an openings file.
    evaluated = tmp_path / "eval.json"
    r = run("evaluate", scene, "--openings", out, "-o", evaluated, "--paths", 256, "--quiet")
    assert r.returncode == 0, r.stderr
    assert len(json.loads(evaluated.read_text())["sensors"]) == 3


def scene_without_edge_refinement(scene, small_room):
    data = json.loads(with_goals(small_room, [400.0, 150.0, 250.0]).read_text())
    data.setdefault("solver", {})["refine_edges"] = False
    path = small_room.parent / "grid_only.json"
    path.write_text(json.dumps(data))
    grid = fenestra.load_scene(str(path))
    grid.render.paths_per_sensor = scene.render.paths_per_sensor
    return grid


def test_python_solve_reuses_contributions_and_is_reproducible(small_room):
    scene = fenestra.load_scene(with_goals(small_room, [400.0, 150.0, 250.0]))
    scene.render.paths_per_sensor = 512
    c = fenestra.contributions(scene)
    a = fenestra.solve(scene, contributions=c)
    b = fenestra.solve(scene, contributions=c)
    assert a["open_elements"] == b["open_elements"]
    assert a["error"] == b["error"]
    # What the user sees is the exact evaluation of the chosen openings from the same paths.
    exact, _ = c.evaluate_openings(scene, fenestra.openings_array(a["openings"]))
    assert [s["predicted"] for s in a["sensors"]] == pytest.approx(exact.tolist(), rel=1e-9)
    # On the element grid, that is the evaluation of the open elements.
    grid = fenestra.solve(scene_without_edge_refinement(scene, small_room), contributions=c)
    mask = np.zeros(scene.element_count, dtype=np.uint8)
    mask[grid["open_elements"]] = 1
    exact, _ = c.evaluate(mask)
    assert [s["predicted"] for s in grid["sensors"]] == pytest.approx(exact.tolist(), rel=1e-9)
    assert [s["goal"] for s in a["sensors"]] == pytest.approx([400.0, 150.0, 250.0])


def test_verify_paths_sets_the_checks_paths_only(small_room):
    """solver.verify_paths: the check with real cutters traces that many paths per sensor (its
    standard error grows as 1/sqrt(paths)); the solve itself does not change."""
    def solve_with(verify_paths):
        data = json.loads(with_goals(small_room, [400.0, 150.0, 250.0]).read_text())
        if verify_paths:
            data["solver"]["verify_paths"] = verify_paths
        path = small_room.parent / ("verify_%d.json" % verify_paths)
        path.write_text(json.dumps(data))
        scene = fenestra.load_scene(str(path))
        scene.render.paths_per_sensor = 2048
        return fenestra.solve(scene, contributions=fenestra.contributions(scene))

    full, quarter = solve_with(0), solve_with(512)
    assert quarter["settings"]["verify_paths"] == 512 and full["settings"]["verify_paths"] == 0
    assert quarter["openings"] == full["openings"]
    noise = quarter["error"]["verified"]["noise_rms"] / full["error"]["verified"]["noise_rms"]
    assert 1.6 < noise < 2.5  # the check's noise, in the error's terms, doubles too
    assert [s["predicted"] for s in quarter["sensors"]] == [s["predicted"] for s in full["sensors"]]
    for a, b in zip(full["sensors"], quarter["sensors"]):
        # The standard error of the check: sqrt(2048 / 512) = 2 times larger, or more (stratified
        # paths converge faster), up to the spread of two standard errors estimated from 16
        # replicate groups each (15 degrees of freedom: their ratio lies in 0.5-2 times the true
        # one with probability 0.99, F(15, 15)).
        assert 1.0 < b["verified_stderr"] / a["verified_stderr"] < 8.0
        assert abs(a["verified"] - b["verified"]) < 4.0 * np.hypot(a["verified_stderr"], b["verified_stderr"])


@pytest.mark.parametrize("goals, units, needle", [
    ([0.5, -0.1, 0.2], "normalized", "goals[1]"),
    ([0.5, 1.2, 0.2], "normalized", "goals[1]"),
    ([None, None, None], "lux", "no sensor has a goal"),
])
def test_bad_goals_are_refused(small_room, tmp_path, goals, units, needle):
    scene = with_goals(small_room, goals, units=units)
    out = tmp_path / "result.json"
    r = run("solve", scene, "-o", out, "--paths", 64, "--quiet")
    assert r.returncode == 1
    assert needle in r.stderr
    assert not out.exists()


def test_constraints_shape_every_opening(small_room, tmp_path):
    constraints = {"min_width": 1.0, "max_width": 1.5, "min_height": 1.0, "max_height": 1.5, "max_openings": 2,
                   "margin": 0.25, "sill_min": 0.5}
    scene = with_goals(small_room, [0.6, 0.4, 0.5], units="normalized",
                       solver={"generations": 100, "population": 32, "seed": 2, "constraints": constraints})
    out = tmp_path / "result.json"
    r = run("solve", scene, "-o", out, "--paths", 512, "--quiet")
    assert r.returncode == 0, r.stderr
    result = json.loads(out.read_text())
    openings = result["openings"]
    assert 1 <= len(openings) <= 2
    for o in openings:
        corners = np.array(o["corners"])
        assert 1.0 - 1e-6 <= o["width"] <= 1.5 + 1e-6 and 1.0 - 1e-6 <= o["height"] <= 1.5 + 1e-6
        assert np.allclose(corners.mean(axis=0), o["centre"], atol=1e-5)
        assert np.allclose(corners[:, 1], 0.0, atol=1e-5)           # on the south wall
        assert corners[:, 2].min() >= 0.5 - 1e-6                      # sill
        assert corners[:, 0].min() >= 0.25 - 1e-6 and corners[:, 0].max() <= 2.75 + 1e-6  # margin
        assert np.allclose(o["normal"], [0, -1, 0], atol=1e-6)       # outward, away from the sensors
    assert result["settings"]["constraints"]["max_openings"] == 2
    assert result["error"]["verified"] is not None
    assert all("verified" in s for s in result["sensors"])


def test_infeasible_constraints_are_refused(small_room, tmp_path):
    scene = with_goals(small_room, [0.6, 0.4, 0.5], units="normalized",
                       solver={"constraints": {"min_area": 4.0, "max_area": 2.0}})
    r = run("solve", scene, "-o", tmp_path / "result.json", "--paths", 64, "--quiet")
    assert r.returncode == 1
    assert "min_area" in r.stderr and "max_area" in r.stderr
    assert not (tmp_path / "result.json").exists()


def test_a_solve_lists_its_stages_in_order_with_their_seconds_and_why_each_stopped(small_room):
    scene = fenestra.load_scene(with_goals(small_room, [400.0, 150.0, 250.0]))
    result = fenestra.solve(scene)
    why = solve_stages.check(result["stages"], climate=False)
    assert why["contributions"] == "done"
    assert why["linear start"] in ("converged", "iteration limit")
    assert why["genetic"] == "generation limit"  # no time budget
    assert result["genetic"]["generations"] >= 100  # the first run's, and the linearisation's
    assert why["successive linearisation"] in ("no improvement", "round limit")
    assert why["rectangles"] == why["exact evaluation"] == why["verification"] == "done"
    for stage in ("climate openings", "least glazing", "climate figures"):
        assert why[stage] == "skipped: no climate goals"
    # The stages that change the openings say what they gained: errors before and after, and the
    # search over whole openings never leaves the answer worse.
    by_name = {s["name"]: s for s in result["stages"]}
    assert why["opening search"] in ("no improvement", "evaluation limit")
    for name in ("rectangles", "local search", "opening search"):
        assert 0.0 <= by_name[name]["error_after"] and 0.0 <= by_name[name]["error_before"], by_name[name]
    assert by_name["opening search"]["error_after"] <= by_name["opening search"]["error_before"] + 1e-12
    if not result["second_start"]["kept"]:  # else the search starts from the second start's openings
        assert by_name["opening search"]["error_before"] == pytest.approx(by_name["local search"]["error_after"])
    assert result["opening_search"]["run"] and result["opening_search"]["evaluations"] > 0
    assert "error_before" not in by_name["genetic"]
    assert why["thick-wall openings"] == "skipped: no edge in a thick wall can leave the grid"  # a thin wall
    assert not result["thick_wall_openings"]["run"]
    # Given contributions, the solve lists the same stages but the tracing.
    again = fenestra.solve(scene, contributions=fenestra.contributions(scene))
    assert solve_stages.check(again["stages"], climate=False, traced=False) == {
        name: reason for name, reason in why.items() if name != "contributions"}


def test_every_reason_a_stage_can_stop_for_is_documented():
    assert solve_stages.in_the_code() == solve_stages.documented()[1]


LIMITED = [
    ({"time_budget_s": 1e-9}, {"genetic": "time budget"}),
    ({"generations": 0, "coarse_to_fine": False, "improve_iterations": 0, "verify": False, "tradeoffs": False,
      "refine_edges": False},
     {"genetic": "generation limit", "successive linearisation": "skipped: solver.generations is 0",
      "coarse grids": "skipped: solver.coarse_to_fine is off",
      "local search": "skipped: solver.improve_iterations is 0", "verification": "skipped: solver.verify is off",
      "trade-offs": "skipped: solver.tradeoffs is off", "edges off the grid": "skipped: solver.refine_edges is off",
      "thick-wall edges": "skipped: solver.refine_edges is off", "catalogue sizes": "skipped: no catalogue",
      "thick-wall joint edges": "skipped: solver.refine_edges is off",
      "thick-wall openings": "skipped: solver.refine_edges is off",
      "composition": "skipped: no facade has two openings to align"}),
]


@pytest.mark.parametrize("limits, expected", LIMITED, ids=["time budget", "settings off"])
def test_a_limited_solve_names_what_stopped_or_skipped_each_stage(small_room, limits, expected):
    solver = {"generations": 100, "population": 32, "seed": 2, **limits}
    result = fenestra.solve(fenestra.load_scene(with_goals(small_room, [400.0, 150.0, 250.0], solver=solver)))
    why = solve_stages.check(result["stages"], climate=False)
    assert {name: why[name] for name in expected} == expected
    if "time_budget_s" in limits:
        assert result["genetic"]["generations"] == 0  # the budget was out before the first generation


def test_solve_can_be_cancelled(small_room):
    scene = fenestra.load_scene(with_goals(small_room, [0.5, 0.3, 0.4], units="normalized"))
    scene.render.paths_per_sensor = 1 << 16  # long enough to be stopped on the way
    with pytest.raises(fenestra.Cancelled):
        fenestra.solve(scene, callback=lambda fraction, status: False)


def test_panel_constraints_apply_to_their_own_panels(tmp_path):
    from conftest import box_obj
    (tmp_path / "room.obj").write_text(box_obj(
        (0, 0, 0), (4, 4, 2.5), lambda f: {"south": "south", "east": "east"}.get(f, "grey")))
    scene = {
        "fenestra": 1, "geometry": "room.obj",
        "materials": {"grey": {"reflectance": 0.6}, "south": {"reflectance": 0.5}, "east": {"reflectance": 0.5}},
        "opening_domain": {"materials": ["south", "east"], "element_size": 0.5},
        "sensors": {"points": [[x, y, 0.8] for x in (1, 2, 3) for y in (1, 2, 3)], "normals": [0, 0, 1],
                    "goals": [0.5] * 9},
        "sky": {"type": "cie_overcast"},
        "render": {"paths_per_sensor": 512},
        "solver": {"generations": 100, "population": 32,
                   "constraints": {"max_height": 1.5},
                   "panel_constraints": [{"materials": ["south"], "constraints": {"max_width": 1.0}},
                                         {"groups": ["east"], "constraints": {"min_width": 1.5}}]},
    }
    path = tmp_path / "scene.json"
    path.write_text(json.dumps(scene))
    out = tmp_path / "result.json"
    r = run("solve", path, "-o", out, "--quiet")
    assert r.returncode == 0, r.stderr
    result = json.loads(out.read_text())
    assert result["openings"]
    for o in result["openings"]:
        corners = np.array(o["corners"])
        assert o["height"] <= 1.5 + 1e-6                   # the global limit holds everywhere
        if np.allclose(corners[:, 1], 0.0, atol=1e-5):      # south wall
            assert o["width"] <= 1.0 + 1e-6
        else:                                               # east wall
            assert np.allclose(corners[:, 0], 4.0, atol=1e-5)
            assert o["width"] >= 1.5 - 1e-6
    # An entry that names nothing is an error.
    scene["solver"]["panel_constraints"] = [{"materials": ["glass"], "constraints": {"max_width": 1.0}}]
    path.write_text(json.dumps(scene))
    r = run("solve", path, "-o", out, "--quiet")
    assert r.returncode == 1 and "panel_constraints[0]" in r.stderr


def test_cli_solve_with_too_few_paths_for_its_elements_says_so(small_room, tmp_path):
    # 0.1 m elements: 750 on the wall; 64 paths per sensor send 256 direct samples.
    scene = with_goals(small_room, [0.5, 0.3, 0.6], units="normalized",
                       solver={"generations": 20, "population": 16, "seed": 2},
                       opening_domain={"materials": ["facade"], "element_size": 0.1})
    out = tmp_path / "result.json"
    r = run("solve", scene, "-o", out, "--paths", 64, "--quiet")
    assert r.returncode == 0, r.stderr
    result = json.loads(out.read_text())
    assert any("direct samples for 750 elements" in w for w in result["warnings"]), result["warnings"]
    assert "warning: 64 paths per sensor" in r.stderr
    assert "checked with real cutters" in r.stdout


def test_cli_solve_with_enough_paths_has_no_warning(small_room, tmp_path):
    # Without the automatic constraints, whose cost for these goals is itself a warning.
    scene = with_goals(small_room, [0.5, 0.3, 0.6], units="normalized",
                       solver={"generations": 20, "population": 16, "seed": 2,
                               "constraints": {"automatic": False}})
    out = tmp_path / "result.json"
    r = run("solve", scene, "-o", out, "--paths", 2048, "--quiet")
    assert r.returncode == 0, r.stderr
    assert json.loads(out.read_text())["warnings"] == []


def test_records_refuse_edges_between_grid_lines_in_a_thick_wall(tmp_path):
    """In a thick wall the records follow the elements' tubes: an opening with an edge between the
    element grid's lines gets a clear error from evaluate_openings, not a wrong value; on the
    lines it is evaluated."""
    (tmp_path / "room.obj").write_text(
        box_obj((0, 0, 0), (3, 3, 2.5), lambda f: "facade" if f == "south" else "grey"))
    d = {"fenestra": 1, "geometry": "room.obj",
         "materials": {"grey": {"reflectance": 0.5}, "facade": {"reflectance": 0.5}},
         "opening_domain": {"materials": ["facade"], "element_size": 0.25, "thickness": 0.3},
         "sensors": {"points": [[1.5, 1.5, 0.8]]}, "sky": {"type": "uniform", "radiance": 100},
         "render": {"paths_per_sensor": 256, "seed": 3}}
    scene = fenestra.scene_from_dict(d, tmp_path)
    c = fenestra.contributions(scene)
    on_grid = [{"panel": 0, "parameter_rectangle": {"u0": 1.0, "u1": 2.0, "v0": 0.75, "v1": 1.75}}]
    value, _ = c.evaluate_openings(scene, json.dumps({"openings": on_grid}))
    assert value[0] > 0
    off_grid = [{"panel": 0, "parameter_rectangle": {"u0": 1.1, "u1": 2.0, "v0": 0.75, "v1": 1.75}}]
    with pytest.raises(ValueError, match=r"opening 0 has an edge between the element grid's lines.*0\.3 m thick"):
        c.evaluate_openings(scene, json.dumps({"openings": off_grid}))
