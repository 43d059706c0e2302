"""The add-on's translation of the core's messages (addon/fenestra/blender/com/user_messages.py), on
the messages the core really gives for studies written as the add-on writes them: the OBJ groups
are `<object>` and `<object>.domain`, the settings are fields of the Fenestra tab. The translated
message names objects, vertices and fields, never a scene-file key, an option or a path.
(user_messages.py imports no bpy, so it is loaded here on its own, without Blender.)"""

import copy
import importlib.util
import json
import os
import re

import numpy as np

import pytest

import fenestra

from conftest import ROOT

spec = importlib.util.spec_from_file_location(
    "user_messages", os.path.join(ROOT, "addon", "fenestra", "blender", "com", "user_messages.py"))
user_messages = importlib.util.module_from_spec(spec)
spec.loader.exec_module(user_messages)

KEY = re.compile(r"\b[a-z]+_[a-z_]+\b|\b[a-z_]+\.[a-z_]+|\[\d+\]|--[a-z]")
PATH = re.compile(r"(?<![\w.])/\w|scene\.json|\.obj\b")

ROOM = """v 0 0 0\nv 4 0 0\nv 4 4 0\nv 0 4 0\nv 0 0 2.7\nv 4 0 2.7\nv 4 4 2.7\nv 0 4 2.7
g Room\nusemtl Plaster\nf 2 3 7\nf 2 7 6\nf 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8\nf 1 4 3\nf 1 3 2\nf 5 6 7\nf 5 7 8
g Room.domain\nusemtl Plaster\nf 1 2 6\nf 1 6 5
"""
# The south wall as a 0.3 m solid: its outer face in another object.
OUTER = "v 0 -0.3 0\nv 4 -0.3 0\nv 4 -0.3 2.7\nv 0 -0.3 2.7\ng South_wall\nusemtl Plaster\nf 9 10 11\nf 9 11 12\n"
# An L of 0.3 m wide arms whose bounding box is 8 m x 9 m, on the plane y = 0.
L_SHAPE = """v 0 0 0\nv 8 0 0\nv 8 0 0.3\nv 0.3 0 0.3\nv 0.3 0 9\nv 0 0 9
g Wall.domain\nusemtl default\nf 1 2 3\nf 1 3 4\nf 1 4 5\nf 1 5 6
"""
# A domain face of no area.
FLAT = ROOM.replace("g Room.domain\nusemtl Plaster\nf 1 2 6\nf 1 6 5", "g Room.domain\nusemtl Plaster\nf 1 2 2")


class Study:
    """What user_messages reads of export.Study: the objects behind groups and sensors."""
    group_objects = {"Room": "Room", "Room.domain": "Room", "Wall.domain": "Wall", "South_wall": "South wall"}
    sensor_objects = [("Sensors", 2), ("Floor grid", 2)]


BASE = {
    "fenestra": 1, "geometry": "scene.obj",
    "materials": {"Plaster": {"type": "diffuse", "reflectance": [0.6, 0.6, 0.6]},
                  "default": {"type": "diffuse", "reflectance": 0.5}},
    "opening_domain": {"groups": ["Room.domain"], "element_size": 0.5},
    "sensors": {"points": [[1, 1, 0.8], [2, 2, 0.8], [3, 3, 0.8], [2, 3, 0.8]], "normals": [[0, 0, 1]] * 4},
    "sky": {"type": "uniform", "radiance": 1000},
    "render": {"paths_per_sensor": 256, "seed": 1},
    "solver": {"paths": 256, "generations": 10, "population": 16, "seed": 1},
    "goals": {"units": "normalized", "uniform": [{"sensors": "all", "level": 0.5}]},
}


def core_message(tmp_path, edit=None, obj=ROOM, then=None):
    """The core's message for the add-on's study with `edit` applied, loaded (and `then(scene)`)."""
    scene = copy.deepcopy(BASE)
    if edit:
        edit(scene)
    (tmp_path / "scene.obj").write_text(obj)
    path = tmp_path / "scene.json"
    path.write_text(json.dumps(scene))
    with pytest.raises(ValueError) as failure:
        loaded = fenestra.load_scene(path)
        if then:
            then(loaded)
    return str(failure.value)


def translated(message, *words, absent=()):
    text = user_messages.for_user(message, Study(), ["Fenestra Opening 001"])
    assert not KEY.search(text), (message, text)
    assert not PATH.search(text), (message, text)
    for word in words:
        assert word in text, (message, text)
    for word in absent:
        assert word not in text, (message, text)
    return text


def test_element_size_larger_than_the_wall(tmp_path):
    message = core_message(tmp_path, lambda s: s["opening_domain"].update(element_size=50))
    assert "opening_domain.element_size" in message and "group 'Room.domain'" in message  # the core's
    translated(message, "Element Size 50 m is too large", "the domain faces of 'Room'", "smaller Element Size")


def test_element_size_on_an_l_shaped_panel(tmp_path):
    """The core gives the panel's bounding box (8 m x 9 m), which no element fails to fit: left out."""
    message = core_message(tmp_path, lambda s: s["opening_domain"].update(groups=["Wall.domain"]), obj=L_SHAPE)
    assert "8 m x 9 m" in message
    translated(message, "Element Size 0.5 m is too large", "the domain faces of 'Wall'", absent=["8 m", "9 m"])


def test_a_domain_face_without_area(tmp_path):
    """The core counts the OBJ group's triangles; the add-on names the object."""
    message = core_message(tmp_path, obj=FLAT)
    assert "face 1 of group 'Room.domain' is degenerate" in message
    translated(message, "A face of 'Room' (one of its domain faces) has no area", "Degenerate Dissolve",
               absent=["face 1"])


@pytest.mark.parametrize("units, level, words", [
    ("normalized", 1.5, ["Goal 1.5 is too high", "at most 1"]),
    ("daylight_factor", 150, ["Goal 150 is too high", "daylight factor", "at most 100 %"]),
])
def test_goal_above_its_units_range(tmp_path, units, level, words):
    message = core_message(tmp_path, lambda s: s.update(goals={"units": units,
                                                               "uniform": [{"sensors": "all", "level": level}]}))
    assert "goals.uniform[0].level" in message
    translated(message, *words)


def test_goal_outside_its_bounds(tmp_path):
    message = core_message(tmp_path, lambda s: s["goals"]["uniform"][0].update(min=0.6))
    translated(message, "Minimum", "Goal", "Maximum")


@pytest.mark.parametrize("goal, words", [
    ({"metric": "ase", "max_area_fraction": 2}, ["Climate goal 2", "must lie in [0, 1]", "got 2"]),
    ({"metric": "sda", "sensors": "front"}, ["Climate goal 2", "no sensor group named 'front'"]),
])
def test_a_climate_goal_is_named_by_its_place_in_the_list(tmp_path, goal, words):
    message = core_message(tmp_path, lambda s: s["goals"].update(climate=[{"metric": "sda"}, goal]))
    assert "goals.climate[1]" in message  # the core's
    translated(message, *words)


def test_painted_goal_names_the_object_and_vertex(tmp_path):
    def painted(s):
        del s["goals"]
        s["sensors"].update(goals=[0.5, 0.5, 1.25, 0.5], goal_units="normalized")
    message = core_message(tmp_path, painted)
    assert "goals[2]" in message
    translated(message, "The painted goal of vertex 0 of 'Floor grid' is 1.25", "Scale")


def test_wall_thickness_disagrees_with_the_model(tmp_path):
    message = core_message(tmp_path, lambda s: s["opening_domain"].update(thickness=0.2),
                           obj=ROOM.replace("g Room.domain", OUTER + "g Room.domain"))
    translated(message, "Wall Thickness 0.2 m disagrees", "the domain faces of 'Room'", "Set Wall Thickness to 0")


def test_setting_out_of_range(tmp_path):
    translated(core_message(tmp_path, lambda s: s["solver"].update(population=10 ** 6)),
               "Population: expected a whole number")


def test_cost_model_refusals(tmp_path):
    def too_many_paths(scene):  # 64 sensors at the most paths a scene takes: far past any machine's memory
        scene["solver"].update(paths=2 ** 24)
        scene["sensors"] = {"points": [[1 + 0.1 * (i % 8), 1 + 0.1 * (i // 8), 0.8] for i in range(64)],
                            "normals": [[0, 0, 1]] * 64}

    memory = core_message(tmp_path, too_many_paths, then=lambda scene: fenestra.check_cost(scene, "solve"))
    assert "--max-memory" in memory
    translated(memory, "fewer paths", "Quality", absent=["max-memory", "MemAvailable"])
    time = core_message(tmp_path, lambda s: s["solver"].update(generations=10 ** 7),
                        then=lambda scene: fenestra.check_cost(scene, "solve"))
    assert "solver.time_budget_s" in time
    translated(time, "fewer Generations", "smaller Population")


def test_night_sky(tmp_path):
    sky = {"type": "preetham", "latitude": 48, "longitude": 2, "utc_offset": 1, "date": "2024-06-21",
           "start": "01:00", "end": "02:00", "step_minutes": 15}
    message = core_message(tmp_path, lambda s: s.update(sky=sky), then=fenestra.solve)
    translated(message, "The sky: the sun is below the horizon", absent=["EnvironmentMap"])


def test_opening_off_the_domain_names_the_cutter(tmp_path):
    off = [[[10, 0, 1], [11, 0, 1], [11, 0, 2], [10, 0, 2]]]
    message = core_message(tmp_path, then=lambda scene: fenestra.evaluate(scene, off))
    translated(message, "'Fenestra Opening 001' does not lie flat on the opening domain")


def test_a_message_without_keys_is_left_as_it_is():
    text = "No sensors: mark an object as sensors (Sensors > Sensor Object) or add a sensor grid"
    assert user_messages.for_user(text) == text


def test_counts_read_as_words():
    from fenestra.wording import counted

    assert counted(1, "opening") == "1 opening"
    assert [counted(n, "face") for n in (0, 2, 11)] == ["0 faces", "2 faces", "11 faces"]
    assert counted(1, "open element") == "1 open element" and counted(3, "open element") == "3 open elements"
    assert counted(2, "child", "children") == "2 children" and counted(1, "child", "children") == "1 child"


def test_a_constraint_cost_warning_names_the_constraints_by_their_labels():
    """The Results panel shows the solve's warnings in the tab's words: the constraints by the
    Constraints panel's labels, never as keys of the result."""
    warning = ("the openings within the constraints meet the goals at 10.3 % on the element grid, the free answer at "
               "0.6 %; without min_width, min_height, margin, sill_min, head_clearance, min_gap, "
               "panel_width_per_opening it would be 2.0 % (constraint_costs in the result)")
    text = user_messages.for_user(warning)
    assert "without Min Width, Min Height, Margin, Min Sill, Head Clearance, Min Gap, Width per Opening it would be " \
           "2.0 %" in text, text
    assert not re.search(r"\b[a-z]+_[a-z_]+\b", text), text  # no snake_case key left
    assert "(constraint_costs" not in text and text.endswith("2.0 %"), text


def _goal_errors():
    spec = importlib.util.spec_from_file_location(
        "goal_errors", os.path.join(ROOT, "addon", "fenestra", "blender", "com", "goal_errors.py"))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_a_goal_far_below_the_others_is_judged_in_lux():
    """A dark zone painted at 1 lx among goals of 300 lx: 2 367 lx there is not "277 193 %" but
    2 366 lx off its goal; goals of the usual size keep their relative error."""
    ge = _goal_errors()
    goal = np.array([300.0, 300.0, 320.0, 1.0, -1.0])
    achieved = np.array([330.0, 240.0, 320.0, 2367.0, 500.0])
    floor = ge.goal_floor(goal)
    assert floor == pytest.approx(0.1 * 300.0)  # a tenth of the median positive goal
    error = ge.scaled_errors(goal, achieved)
    np.testing.assert_allclose(error[:3], [0.1, 0.2, 0.0])
    assert error[3] == pytest.approx(2366.0 / floor) and error[4] == -1.0  # no goal: last
    assert ge.describe(300.0, 240.0, floor) == ("20.0 %", "goal 300 lx, got 240 lx")
    assert ge.describe(1.0, 2367.0, floor) == ("2366 lx off", "goal 1 lx, got 2367 lx")
    assert ge.goal_floor(np.array([-1.0, 0.0])) == 0.0
    assert list(ge.scaled_errors([0.0, -1.0], [5.0, 5.0])) == [0.0, -1.0]  # goals 0 or none: no division
