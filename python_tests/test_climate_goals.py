"""Climate goals (docs/scene-format.md, "Climate goals"; docs/solver.md): a solve on sDA and ASE
through the command line and Python, what a goal that cannot be met says, and seeded mutations of
the goals section that must each end in a result or a clear error naming the key."""

import copy
import json
import os
import random
import subprocess
import warnings

import numpy as np
import pytest

from conftest import CLI, EXAMPLES, box_obj

import fenestra
import solve_stages

CHICAGO = os.path.join(EXAMPLES, "weather", "USA_IL_Chicago-OHare.Intl.AP.725300_TMY3.epw")


def short_wea(path, days=(1, 2, 3, 15, 16, 17)):
    """A Radiance .wea of some days of each month of the Chicago TMY3 year (fast to build)."""
    rows = []
    with open(CHICAGO) as f:
        for line in f.readlines()[8:]:
            v = line.split(",")
            month, day, hour = int(v[1]), int(v[2]), int(v[3])
            if day in days:
                rows.append("%d %d %.1f %s %s" % (month, day, hour - 0.5, v[14], v[15]))
    header = ["place Chicago_OHare", "latitude 41.98", "longitude 87.92", "time_zone 90", "site_elevation 201.0",
              "weather_data_file_units 1"]
    path.write_text("\n".join(header + rows) + "\n")


def climate_room(tmp_path, goals, paths=1024, groups=None):
    """A 3 x 4 x 2.5 m room lit by its south wall (0.5 m elements), six floor sensors, a year of 72 days."""
    (tmp_path / "room.obj").write_text(
        box_obj((0, 0, 0), (3, 4, 2.5), lambda f: "facade" if f == "south" else "floor" if f == "floor" else "grey"))
    short_wea(tmp_path / "chicago.wea")
    sensors = {"points": [[0.75, y, 0.8] for y in (0.75, 2.0, 3.25)] + [[2.25, y, 0.8] for y in (0.75, 2.0, 3.25)],
               "normals": [0, 0, 1]}
    if groups is not None:
        sensors["groups"] = groups
    scene = {
        "fenestra": 1, "geometry": "room.obj",
        "materials": {"grey": {"reflectance": 0.5}, "floor": {"reflectance": 0.2}, "facade": {"reflectance": 0.5}},
        "opening_domain": {"materials": ["facade"], "element_size": 0.5},
        "sensors": sensors,
        "sky": {"type": "climate", "weather": "chicago.wea", "resolution": [64, 32]},
        "goals": goals,
        "render": {"paths_per_sensor": paths, "max_bounces": 6, "seed": 2},
        "solver": {"population": 16, "generations": 40, "improve_iterations": 200, "tradeoffs": False},
    }
    path = tmp_path / "scene.json"
    path.write_text(json.dumps(scene))
    return path, scene


SDA_ASE = {"climate": [{"metric": "sda", "min_area_fraction": 0.5}, {"metric": "ase", "hours": 40, "max_area_fraction": 0.2}],
           "least_glazing": True}


def test_cli_solves_for_sda_and_ase_with_the_least_glazing(tmp_path):
    scene, _ = climate_room(tmp_path, SDA_ASE)
    out = tmp_path / "result.json"
    run = subprocess.run([CLI, "solve", str(scene), "-o", str(out), "--quiet"], capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    assert "climate goal sDA300/50% >= 50 %:" in run.stdout and "glazing" in run.stdout, run.stdout
    result = json.loads(out.read_text())
    climate = result["climate"]
    # The climate stages in place of the per-sensor ones, each saying what ended it.
    why = solve_stages.check(result["stages"], climate=True)
    assert why["linear start"] == "skipped: no per-sensor goals"
    assert why["climate model"] == "done" and why["climate search"] == "generation limit"
    assert why["climate linearisation"] in ("no improvement", "round limit")
    assert why["climate openings"] in ("goals met", "round limit")
    assert why["constraint costs"] == "skipped: the climate figures tell what the constraints cost"
    assert why["least glazing"] == "skipped: solver.tradeoffs is off"
    assert why["climate figures"] == "done"
    sda, ase = climate["goals"]
    assert (sda["metric"], sda["sense"], sda["unit"], sda["required"]) == ("sda", "at_least", "area fraction", 0.5)
    assert (ase["metric"], ase["sense"]) == ("ase", "at_most")
    assert sda["met"] and ase["met"] and climate["all_met"] and not climate["unmet"], climate["goals"]
    assert sda["achieved"] >= 0.5 and ase["achieved"] <= 0.2
    # Real cutters and independent paths: within one sensor (a sixth) of the records, or as many as
    # sit within 0.1 of the 50 % threshold in the records (a least-glazing design seeks that edge, and
    # a sensor's daylight autonomy moves by up to 0.08 between independent sets of 1024 paths).
    at_edge = sum(abs(da - 0.5) < 0.1 for da in climate["per_sensor"]["daylight_autonomy"])
    assert sda["verified"] is not None
    assert abs(sda["verified"] - sda["achieved"]) <= max(1, at_edge) / 6 + 1e-9, climate["per_sensor"]
    # Least glazing: less than half of the wall; every element open over-lights (ASE above the goal).
    assert 0 < climate["glazing_area_m2"] < 0.5 * climate["domain_area_m2"]
    assert ase["all_open"] > 0.2
    per = climate["per_sensor"]
    assert len(per["daylight_autonomy"]) == 6 and all(0 <= x <= 1 for x in per["daylight_autonomy"])
    assert np.mean(np.asarray(per["daylight_autonomy"]) >= 0.5) == pytest.approx(sda["achieved"])
    assert climate["space"]["spatial_daylight_autonomy"] == pytest.approx(sda["achieved"])


def test_goals_per_room_report_each_rooms_figures_and_the_floors(tmp_path):
    """Sensor groups as rooms, goals per room: the result gives each room's figures of the final
    openings' year (as `fenestra annual` gives a space's), and `space` the whole floor's, as LEED
    counts sDA and ASE over every sensor; the command line prints one line per room."""
    goals = {"climate": [{"metric": "sda", "sensors": "front", "min_area_fraction": 0.5},
                         {"metric": "sda", "sensors": "back", "min_area_fraction": 0.5},
                         {"metric": "ase", "sensors": "front", "hours": 40, "max_area_fraction": 0.5},
                         {"metric": "udi", "sensors": [0, 1], "min_area_fraction": 0.1}],
             "least_glazing": True}
    path, scene = climate_room(tmp_path, goals, paths=256, groups={"front": [0, 3], "back": [1, 2, 4, 5]})
    scene["solver"].update(generations=10, population=10, verify=False)
    path.write_text(json.dumps(scene))
    out = tmp_path / "result.json"
    run = subprocess.run([CLI, "solve", str(path), "-o", str(out), "--quiet"], capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    climate = json.loads(out.read_text())["climate"]
    rooms = climate["rooms"]
    assert [r["name"] for r in rooms] == ["front", "back"]  # a list of sensors is no room
    assert [r["sensors"] for r in rooms] == [[0, 3], [1, 2, 4, 5]]
    per = climate["per_sensor"]
    da, ase_hours = np.asarray(per["daylight_autonomy"]), np.asarray(per["ase_hours"])
    for room in rooms:
        at = room["sensors"]
        assert room["space"]["spatial_daylight_autonomy"] == pytest.approx(np.mean(da[at] >= 0.5))
        assert room["space"]["annual_sunlight_exposure"] == pytest.approx(np.mean(ase_hours[at] > 250))
        assert room["space"]["daylight_autonomy"] == pytest.approx(np.mean(da[at]))
        line = "room %s (%d sensors): sDA %.1f %%, ASE %.1f %%" % (room["name"], len(at),
                                                                  100 * room["space"]["spatial_daylight_autonomy"],
                                                                  100 * room["space"]["annual_sunlight_exposure"])
        assert line in run.stdout, run.stdout
    # Each room's sDA is its goal's figure; the floor's is over every sensor.
    assert rooms[0]["space"]["spatial_daylight_autonomy"] == pytest.approx(climate["goals"][0]["achieved"])
    assert rooms[1]["space"]["spatial_daylight_autonomy"] == pytest.approx(climate["goals"][1]["achieved"])
    assert climate["space"]["spatial_daylight_autonomy"] == pytest.approx(np.mean(da >= 0.5))
    assert climate["space"]["annual_sunlight_exposure"] == pytest.approx(np.mean(ase_hours > 250))


def test_least_glazing_in_a_thick_wall_answers_with_the_least_passing_glass_and_shows_the_cutters_year(tmp_path):
    """A 0.3 m wall: no trade-off beside the answer meets the goals with less glass, and the figures
    shown are the real cutters' wherever the two years disagree beyond the noise, with a warning."""
    path, scene = climate_room(tmp_path, SDA_ASE, paths=512)
    scene["opening_domain"]["thickness"] = 0.3
    scene["solver"].update({"tradeoffs": True, "verify": True, "generations": 30})
    path.write_text(json.dumps(scene))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)  # the cutters' year may disagree: checked below
        result = fenestra.solve(fenestra.load_scene(str(path)))
    climate = result["climate"]
    answer = [t for t in result["tradeoffs"] if t["answer"]]
    assert len(answer) == 1 and answer[0]["openings"] == result["openings"]
    assert answer[0]["glazing_area_m2"] == pytest.approx(climate["glazing_area_m2"])
    for entry in result["tradeoffs"]:
        if entry["climate"] and entry["climate"]["all_met"] and not entry["answer"]:
            assert entry["glazing_area_m2"] >= climate["glazing_area_m2"] - 1e-9, result["tradeoffs"]
    assert climate["headline"] in ("path records", "real cutters")
    apart = [g for g in climate["goals"] if abs(g["records"] - g["verified"]) > 0.02]
    if apart:
        assert climate["headline"] == "real cutters"
        assert any("disagree beyond the noise" in w for w in result["warnings"]), result["warnings"]
    shown = "verified" if climate["headline"] == "real cutters" else "records"
    for goal in climate["goals"]:
        assert goal["achieved"] == goal[shown] and goal["met"] == goal[shown + "_met"]
    assert climate["space"] == (climate["verified_space"] if shown == "verified" else climate["records_space"])


def least_glazing_study(folder, seed):
    """The reported study's shape: a 5 x 4 x 2.8 m room, a 0.3 m south wall, sDA >= 55 % and ASE <=
    10 % with the least glazing, trade-offs checked with real cutters."""
    (folder / "room.obj").write_text(
        box_obj((0, 0, 0), (5, 4, 2.8), lambda f: "facade" if f == "south" else "floor" if f == "floor" else "grey"))
    short_wea(folder / "chicago.wea")
    scene = {
        "fenestra": 1, "geometry": "room.obj",
        "materials": {"grey": {"reflectance": 0.6}, "floor": {"reflectance": 0.2}, "facade": {"reflectance": 0.5}},
        "opening_domain": {"materials": ["facade"], "element_size": 0.25, "thickness": 0.3},
        "sensors": {"points": [[x + 0.5, y + 0.5, 0.8] for x in range(5) for y in range(4)], "normals": [0, 0, 1]},
        "sky": {"type": "climate", "weather": "chicago.wea", "resolution": [64, 32]},
        "goals": {"climate": [{"metric": "sda", "min_area_fraction": 0.55},
                              {"metric": "ase", "max_area_fraction": 0.10}], "least_glazing": True},
        "render": {"paths_per_sensor": 512, "max_bounces": 6, "seed": seed},
        "solver": {"tradeoffs": True, "verify": True},
    }
    path = folder / "scene.json"
    path.write_text(json.dumps(scene))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        return fenestra.solve(fenestra.load_scene(str(path)))


def test_least_glazing_lists_no_passing_design_with_less_glass_beside_the_answer(tmp_path):
    """Where the records say a trade-off with less glass meets the goals, real cutters decide: it is
    either the answer or listed with the cutters' figures, never shown as a passing design with less
    glass. Which seed's records make that case depends on the random numbers, so seeds are tried
    until one does; the rules hold at every seed tried."""
    exercised = False
    for seed in range(1, 13):
        result = least_glazing_study(tmp_path, seed)
        climate = result["climate"]
        answer = next(t for t in result["tradeoffs"] if t["answer"])
        for entry in result["tradeoffs"]:
            if entry["climate"] and entry["climate"]["all_met"] and not entry["answer"]:
                assert entry["glazing_area_m2"] >= answer["glazing_area_m2"] - 1e-9, (seed, result["tradeoffs"])
        # The answer's figures are the headline's, labelled as the headline is.
        headline_by = {"path records": "records", "real cutters": "cutters"}[climate["headline"]]
        assert answer["climate"]["figures_by"] == headline_by, (seed, climate["headline"], answer)
        assert answer["climate"]["achieved"] == [g["achieved"] for g in climate["goals"]], (seed, answer)
        cheaper = [t for t in result["tradeoffs"] if t["glazing_area_m2"] < answer["glazing_area_m2"] - 1e-9]
        if climate["answer_from_tradeoffs"] or any(t["climate"]["figures_by"] == "cutters" for t in cheaper):
            exercised = True
            break
    assert exercised, "no seed in 1..12 had a trade-off with less glass that the records say meets the goals"


def test_python_solve_reports_a_goal_that_cannot_be_met(tmp_path):
    goals = {"climate": [{"metric": "sda", "sensors": "back", "illuminance_lux": 5000, "min_area_fraction": 1.0}]}
    path, _ = climate_room(tmp_path, goals, paths=256, groups={"back": [2, 5]})
    with pytest.warns(RuntimeWarning, match="cannot be met here"):
        result = fenestra.solve(fenestra.load_scene(str(path)))
    climate = result["climate"]
    assert climate["goals"][0]["met"] is False and climate["all_met"] is False
    assert len(climate["unmet"]) == 1
    assert "sDA5000/50% >= 100 % (back) is not met" in climate["unmet"][0]
    assert "cannot be met" in climate["unmet"][0]
    assert any("climate goals: sDA5000" in w for w in result["warnings"])


@pytest.mark.parametrize("goal,key", [
    ({"metric": "sda", "min_area_fraction": 2}, "goals.climate[0].min_area_fraction"),
    ({"metric": "ase", "hours": 1e6}, "goals.climate[0].hours"),
    ({"metric": "udi", "lower_lux": 3000, "upper_lux": 100}, "lower_lux < upper_lux"),
    ({"metric": "en17037", "level": 3}, "goals.climate[0].level"),
    ({"metric": "sda", "sensors": "nowhere"}, "no sensor group named 'nowhere'"),
    ({"metric": "sda", "sensors": [6]}, "goals.climate[0].sensors"),
    ({"metric": "sda", "illuminance_lux": -300}, "goals.climate[0].illuminance_lux"),
])
def test_bad_climate_goals_are_refused_with_their_key(tmp_path, goal, key):
    path, _ = climate_room(tmp_path, {"climate": [goal]})
    out = tmp_path / "result.json"
    run = subprocess.run([CLI, "solve", str(path), "-o", str(out), "--quiet"], capture_output=True, text=True)
    assert run.returncode == 1
    assert key in run.stderr and "scene.json" in run.stderr
    assert not out.exists()
    with pytest.raises(ValueError, match="goals|sensors"):
        fenestra.load_scene(str(path))


NASTY = [0, -1, 1, 0.5, 1.5, 1e-300, 1e39, -1e39, 2 ** 64 + 5, 8760, 8785, "x", "", None, True, [], {}, [0, 99],
         "all", "sda", "minimum"]
KEYS = ["metric", "sensors", "weight", "illuminance_lux", "time_fraction", "min_area_fraction", "hours",
        "max_area_fraction", "lower_lux", "upper_lux", "level", "area_fraction"]
METRICS = ["sda", "ase", "en17037", "udi", "mean"]


def mutate_goals(rng):
    goals = []
    for _ in range(rng.randint(0, 3)):
        g = {"metric": rng.choice(METRICS)}
        if g["metric"] == "mean":
            g["illuminance_lux"] = 300
        for _ in range(rng.randint(1, 3)):
            g[rng.choice(KEYS)] = rng.choice(NASTY)
        goals.append(g)
    section = {"climate": goals}
    if rng.random() < 0.3:
        section["least_glazing"] = rng.choice(NASTY)
    if rng.random() < 0.1:
        section["climate"] = rng.choice(NASTY)
    return section


def test_seeded_mutations_of_climate_goals_end_in_a_scene_or_a_clear_error(tmp_path):
    """Only loading (the goals are read before the sky, so a refusal is immediate); every case
    either loads or raises ValueError naming a key of goals or sensors."""
    climate_room(tmp_path, SDA_ASE)
    base = json.loads((tmp_path / "scene.json").read_text())
    rng = random.Random(17)
    loaded = refused = 0
    for case in range(60):
        scene = copy.deepcopy(base)
        scene["goals"] = mutate_goals(rng)
        if rng.random() < 0.2:
            scene["sensors"]["groups"] = {"g": rng.choice(NASTY)}
        try:
            fenestra.scene_from_dict(scene, base_dir=str(tmp_path))
            loaded += 1
        except ValueError as e:
            refused += 1
            assert "scene" in str(e) and ("goals" in str(e) or "sensors.groups" in str(e)), (case, scene["goals"], e)
    assert refused > 20 and loaded > 3  # the mutations reach both sides
