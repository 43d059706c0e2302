"""The setup checks outside Blender (docs/outputs.md, "Setup warnings"): `fenestra solve`,
`contributions`, `evaluate` and `annual` print each warning on stderr and record it in the output's
`warnings`; fenestra.solve() and fenestra.contributions() issue RuntimeWarnings and keep them in the
result; --strict / strict=True make them errors before any work; a solve without goals is refused
before tracing."""

import json
import subprocess
import warnings

import numpy as np
import pytest

import fenestra
from conftest import CLI, box_obj
from test_annual import climate_room

SOLVER = {"paths": 64, "generations": 4, "population": 8, "improve_iterations": 100, "verify": False}


def cli(*args):
    return subprocess.run([CLI, *map(str, args)], capture_output=True, text=True, timeout=300)


def edit(path, change):
    scene = json.loads(path.read_text())
    change(scene)
    path.write_text(json.dumps(scene))
    return path


def without_ceiling(path):
    """The room's OBJ with its ceiling face left out (its vertices stay, unused)."""
    lines, skip = [], False
    for line in box_obj((0, 0, 0), (3, 3, 2.5), lambda f: "facade" if f == "south" else "grey").splitlines():
        if line.startswith("o "):
            skip = line == "o ceiling"
        if skip and not line.startswith("v "):
            continue
        lines.append(line)
    (path.parent / "room.obj").write_text("\n".join(lines) + "\n")
    return path


def zero_goals(scene):
    scene["goals"] = {"uniform": [{"level": 0}]}
    scene["solver"] = SOLVER


def facing_down(scene):
    scene["sensors"]["normals"] = [0, 0, -1]


def test_each_check_names_its_sensors(small_room):
    scene = fenestra.load_scene(small_room)
    assert fenestra.check_setup(scene, "solve") == [] and fenestra.check_setup(scene, "evaluate") == []

    def outdoors(s):
        s["sensors"]["points"].append([5.0, 1.5, 0.8])
    found = fenestra.check_setup(fenestra.load_scene(edit(small_room, outdoors)), "contributions")
    assert [f["kind"] for f in found] == ["outdoors"]
    assert found[0]["sensors"] == [3] and found[0]["total"] == 4
    assert found[0]["message"].startswith("1 of 4 sensors is outdoors"), found[0]["message"]
    assert "sensor 3 at (5.00, 1.50, 0.80)" in found[0]["message"]

    found = fenestra.check_setup(fenestra.load_scene(without_ceiling(edit(small_room, lambda s: s["sensors"]["points"].pop()))),
                                 "contributions")
    assert [f["kind"] for f in found] == ["open_room"]
    assert found[0]["sensors"] == [0, 1, 2] and found[0]["direction"][2] > 0.5 and "mostly upward" in found[0]["message"]

    found = fenestra.check_setup(fenestra.load_scene(edit(small_room, facing_down)), "evaluate")
    assert [f["kind"] for f in found] == ["downward"]
    assert found[0]["sensors"] == [0, 1, 2]
    with pytest.raises(ValueError, match="unknown command 'annual' \\(solve, contributions or evaluate\\)"):
        fenestra.check_setup(scene, "annual")


def test_cli_solve_warns_records_and_strict_refuses(small_room, tmp_path):
    edit(small_room, zero_goals)
    out = tmp_path / "result.json"
    r = cli("solve", small_room, "-o", out, "--quiet")
    assert r.returncode == 0, r.stderr
    message = "all 3 sensor goals are 0 (goals.uniform): the solve opens nothing"
    assert "fenestra: warning: " + message in r.stderr
    assert r.stderr.count(message) == 1, r.stderr  # printed once, before the work
    result = json.loads(out.read_text())
    assert result["warnings"][0].startswith(message), result["warnings"]
    out.unlink()
    r = cli("solve", small_room, "-o", out, "--quiet", "--strict")
    assert r.returncode == 1, r.stderr
    assert r.stderr.startswith("fenestra: error: scene '%s': the setup checks found 1 problem (strict); %s"
                               % (small_room, message)), r.stderr
    assert not out.exists()


def test_cli_contributions_evaluate_and_annual_record_theirs(small_room, tmp_path):
    without_ceiling(edit(small_room, facing_down))
    r = cli("contributions", small_room, "-o", tmp_path / "c", "--paths", 64, "--quiet")
    assert r.returncode == 0, r.stderr
    recorded = json.loads((tmp_path / "c.json").read_text())["warnings"]
    assert [w.split(" (")[0].split(":")[0] for w in recorded] == [
        "3 of 3 sensors see the sky through gaps that are not opening domain", "3 of 3 sensors face downward"]
    for w in recorded:
        assert "fenestra: warning: " + w in r.stderr
    (tmp_path / "window.json").write_text(json.dumps(
        {"openings": [{"corners": [[0.5, 0, 1.0], [2.5, 0, 1.0], [2.5, 0, 2.0], [0.5, 0, 2.0]]}]}))
    r = cli("evaluate", small_room, "--openings", tmp_path / "window.json", "-o", tmp_path / "e.json", "--paths", 64,
            "--quiet")
    assert r.returncode == 0, r.stderr
    assert json.loads((tmp_path / "e.json").read_text())["warnings"] == recorded[1:]  # an open room is measured
    for command, extra in (("contributions", ()), ("evaluate", ("--openings", tmp_path / "window.json"))):
        r = cli(command, small_room, *extra, "-o", tmp_path / "strict.json", "--paths", 64, "--quiet", "--strict")
        assert r.returncode == 1 and "(strict); " in r.stderr, r.stderr
    assert not list(tmp_path.glob("strict*"))
    r = cli("sky", small_room, "-o", tmp_path / "sky.exr", "--strict")
    assert r.returncode == 2 and "--strict belongs to" in r.stderr

    climate = climate_room(small_room)
    for extra in ((), ("--cutters",)):
        r = cli("annual", climate, "--openings", tmp_path / "window.json", "-o", tmp_path / "year", "--paths", 64,
                "--quiet", *extra)
        assert r.returncode == 0, r.stderr
        assert json.loads((tmp_path / "year.json").read_text())["warnings"] == recorded[1:]


def test_python_solve_and_contributions_warn_and_strict_refuses(small_room):
    scene = fenestra.load_scene(edit(small_room, lambda s: (zero_goals(s), facing_down(s))))
    with pytest.warns(RuntimeWarning) as caught:
        result = fenestra.solve(scene)
    setup = [f["message"] for f in fenestra.check_setup(scene, "solve")]
    assert [f["kind"] for f in fenestra.check_setup(scene, "solve")] == ["zero_goals", "downward"]
    assert result["warnings"][:2] == setup
    assert [str(w.message) for w in caught][:2] == setup
    with pytest.warns(RuntimeWarning, match="3 of 3 sensors face downward"):
        c = fenestra.contributions(scene)
    assert c.warnings == setup[1:]
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert fenestra.contributions(scene, checks=False).warnings == []
    calls = []
    for call in (lambda: fenestra.solve(scene, strict=True, callback=lambda *a: calls.append(a)),
                 lambda: fenestra.contributions(scene, strict=True, callback=lambda *a: calls.append(a))):
        with pytest.raises(ValueError, match=r"the setup checks found \d problems? \(strict\); "):
            call()
    assert calls == []  # refused before any work


def test_a_solve_without_goals_is_refused_before_tracing(small_room, tmp_path):
    scene = fenestra.load_scene(small_room)  # sensors without goals
    calls = []
    with pytest.raises(ValueError, match="no sensor has a goal"):
        fenestra.solve(scene, callback=lambda *a: calls.append(a))
    assert calls == []
    r = cli("solve", small_room, "-o", tmp_path / "out.json", "--quiet")
    assert r.returncode == 1 and "no sensor has a goal" in r.stderr, r.stderr
    assert not (tmp_path / "out.json").exists()
    # Weights 0 leave no goal either; a climate goal is one.
    edit(small_room, lambda s: (s.update(goals={"uniform": [{"level": 0.5}]}),
                                s["sensors"].update(weights=[0, 0, 0])))
    with pytest.raises(ValueError, match="no sensor has a goal"):
        fenestra.solve(fenestra.load_scene(small_room))


def test_a_solve_on_a_cluster_runs_the_same_checks(small_room, tmp_path):
    edit(small_room, lambda s: (zero_goals(s), facing_down(s)))
    out = tmp_path / "result.json"
    r = cli("solve", small_room, "-o", out, "--workers", 1, "--quiet", "--strict")
    assert r.returncode == 1 and "the setup checks found 2 problems (strict)" in r.stderr, r.stderr
    assert not out.exists()
    r = cli("solve", small_room, "-o", out, "--workers", 1, "--quiet")
    assert r.returncode == 0, r.stderr
    setup = [f["message"] for f in fenestra.check_setup(fenestra.load_scene(small_room), "solve")]
    assert json.loads(out.read_text())["warnings"][:2] == setup
    assert all(r.stderr.count(m) == 1 for m in setup), r.stderr
