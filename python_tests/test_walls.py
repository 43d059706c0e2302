"""Walls behind the opening domain: thickness measured from a modelled solid or given, refused when
the two disagree or the model is ambiguous (the message names the panel and the values, nothing is
written), and carried to the result's openings as their depth."""

import json
import os
import subprocess

import pytest

from conftest import CLI

import fenestra


def solid_south_wall(folder, thickness, outer_fraction=1.0, step=0.0):
    """The small room's south wall as a solid: its outer face `thickness` m behind the inner face
    (y = -thickness), covering `outer_fraction` of the wall's width (the rest one `step` m deeper)."""
    t = -thickness
    w = 3.0 * outer_fraction
    lines = []
    quads = [("outer", [(0, t, 0), (0, t, 2.5), (w, t, 2.5), (w, t, 0)])]
    if outer_fraction < 1.0:
        quads.append(("outer_rest", [(w, t - step, 0), (w, t - step, 2.5), (3, t - step, 2.5), (3, t - step, 0)]))
    text = (folder / "room.obj").read_text()
    n = text.count("\nv ") + (1 if text.startswith("v ") else 0)
    for name, quad in quads:
        lines += ["o %s" % name, "usemtl grey"] + ["v %g %g %g" % p for p in quad]
        lines.append("f %d %d %d %d" % (n + 1, n + 2, n + 3, n + 4))
        n += 4
    (folder / "room.obj").write_text(text + "\n".join(lines) + "\n")


def with_domain(scene_path, **domain):
    scene = json.loads(scene_path.read_text())
    scene["opening_domain"].update(domain)
    for key, value in domain.items():
        if value is None:
            del scene["opening_domain"][key]
    scene_path.write_text(json.dumps(scene))
    return scene_path


def refused(scene_path, fragments):
    folder = scene_path.parent
    before = sorted(os.listdir(folder))
    r = subprocess.run([CLI, "contributions", str(scene_path), "-o", str(folder / "out.npz"), "--quiet",
                        "--paths", "16"], capture_output=True, text=True, timeout=120)
    assert r.returncode == 1, r.stderr
    for fragment in fragments:
        assert fragment in r.stderr, r.stderr
    assert sorted(os.listdir(folder)) == before
    with pytest.raises(ValueError) as error:
        fenestra.load_scene(str(scene_path))
    for fragment in fragments:
        assert fragment in str(error.value)


def test_thickness_is_measured_from_a_modelled_solid(small_room):
    solid_south_wall(small_room.parent, 0.3)
    result = fenestra.solve(scene_with_goal(small_room))
    assert result["openings"], result
    for opening in result["openings"]:
        assert opening["depth"] == pytest.approx(0.3, abs=1e-5)


def scene_with_goal(scene_path):
    scene = json.loads(scene_path.read_text())
    scene["sensors"]["goals"] = [0.4, 0.4, 0.4]
    scene["render"]["paths_per_sensor"] = 256
    scene["solver"] = {"generations": 20, "population": 16, "verify": False}
    path = scene_path.parent / "goal.json"
    path.write_text(json.dumps(scene))
    return fenestra.load_scene(str(path))


def test_given_thickness_on_a_single_face_wall_reaches_the_openings(small_room):
    with_domain(small_room, thickness=0.25)
    result = fenestra.solve(scene_with_goal(small_room))
    assert result["openings"] and all(o["depth"] == pytest.approx(0.25, abs=1e-6) for o in result["openings"])


def test_zero_thickness_wall_measures_zero(small_room):
    result = fenestra.solve(scene_with_goal(small_room))
    assert result["openings"] and all(o["depth"] == 0.0 for o in result["openings"])


def test_thickness_disagreeing_with_the_model_is_refused(small_room):
    solid_south_wall(small_room.parent, 0.3)
    with_domain(small_room, thickness=0.2)
    refused(small_room, ["opening_domain", "0.2 m", "0.3 m", "material 'facade'"])
    with_domain(small_room, thickness=0.0)
    refused(small_room, ["opening_domain", "0 m", "0.3 m"])


def test_a_wall_modelled_under_part_of_the_panel_is_refused(small_room):
    # The outer face behind 40 % of the wall's width, nothing behind the rest.
    solid_south_wall(small_room.parent, 0.3, outer_fraction=0.4, step=5.0)
    refused(small_room, ["opening_domain", "in part only", "material 'facade'"])


def test_outer_faces_of_two_thicknesses_are_refused(small_room):
    solid_south_wall(small_room.parent, 0.3, outer_fraction=0.6, step=0.1)
    refused(small_room, ["opening_domain", "not of one thickness", "material 'facade'"])


@pytest.mark.parametrize("value", [-0.1, float("nan"), float("inf"), "0.3", True])
def test_thickness_must_be_a_non_negative_number(small_room, value):
    scene = json.loads(small_room.read_text())
    scene["opening_domain"]["thickness"] = value
    # NaN and infinity are not JSON: write them as Python's json does, which the loader refuses too.
    small_room.write_text(json.dumps(scene))
    refused(small_room, ["opening_domain.thickness"])
