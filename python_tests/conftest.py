import json
import os
import sys

import numpy as np
import pytest

import blenders

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "addon"))

EXAMPLES = os.path.join(ROOT, "examples")
BLENDERS = blenders.blenders()
CLI = os.environ.get("FENESTRA_CLI", os.path.join(ROOT, "build", "fenestra"))


def box_obj(lo, hi, material_of):
    """OBJ text of an axis-aligned box, one group per face, faces wound toward the inside."""
    (x0, y0, z0), (x1, y1, z1) = lo, hi
    faces = {
        "floor": [(x0, y0, z0), (x0, y1, z0), (x1, y1, z0), (x1, y0, z0)],
        "ceiling": [(x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)],
        "south": [(x0, y0, z0), (x1, y0, z0), (x1, y0, z1), (x0, y0, z1)],
        "north": [(x0, y1, z0), (x0, y1, z1), (x1, y1, z1), (x1, y1, z0)],
        "west": [(x0, y0, z0), (x0, y0, z1), (x0, y1, z1), (x0, y1, z0)],
        "east": [(x1, y0, z0), (x1, y1, z0), (x1, y1, z1), (x1, y0, z1)],
    }
    lines, n = [], 0
    for name, quad in faces.items():
        lines += ["o %s" % name, "usemtl %s" % material_of(name)]
        lines += ["v %g %g %g" % p for p in quad]
        lines.append("f %d %d %d %d" % (n + 1, n + 2, n + 3, n + 4))
        n += 4
    return "\n".join(lines) + "\n"


def write_small_room(folder, offset=(0.0, 0.0, 0.0), paths=4096, seed=3):
    """A grey 3 x 3 x 2.5 m room whose south wall (y = offset's y) is the opening domain, moved by
    `offset` (meters, written with every digit: site coordinates); writes room.obj and scene.json
    in folder and returns the scene file's path."""
    offset = np.asarray(offset, float)
    obj = box_obj((0, 0, 0), (3, 3, 2.5), lambda f: "facade" if f == "south" else "grey")
    if offset.any():
        obj = "\n".join("v " + " ".join(repr(float(x) + o) for x, o in zip(line.split()[1:], offset))
                        if line.startswith("v ") else line for line in obj.splitlines()) + "\n"
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "room.obj").write_text(obj)
    points = np.array([[1.5, 1.0, 0.8], [0.5, 2.5, 0.8], [2.5, 0.5, 1.2]]) + offset
    scene = {
        "fenestra": 1,
        "geometry": "room.obj",
        "materials": {"grey": {"type": "diffuse", "reflectance": 0.6},
                      "facade": {"type": "diffuse", "reflectance": 0.5}},
        "opening_domain": {"materials": ["facade"], "element_size": 0.5},
        "sensors": {"points": points.tolist(), "normals": [0, 0, 1]},
        "sky": {"type": "uniform", "radiance": 1000 / np.pi},
        "render": {"paths_per_sensor": paths, "max_bounces": 8, "seed": seed},
    }
    path = folder / "scene.json"
    path.write_text(json.dumps(scene))
    return path


def write_stacked_panels(folder, panels=40):
    """A sensor under `panels` stacked horizontal panels of the opening domain, 5 cm apart: a ray
    to the sky crosses more elements than an event's conditions hold."""
    lines = ["o floor", "usemtl grey", "v -5 -5 0", "v 5 -5 0", "v 5 5 0", "v -5 5 0", "f 1 2 3 4"]
    for i in range(panels):
        z, n = 1.0 + 0.05 * i, 4 * (i + 1)
        lines += ["o louvre%d" % i, "usemtl screen"] + ["v %g %g %g" % (x, y, z) for x, y in
                                                        ((-1, -1), (1, -1), (1, 1), (-1, 1))]
        lines.append("f %d %d %d %d" % (n + 1, n + 2, n + 3, n + 4))
    (folder / "stack.obj").write_text("\n".join(lines) + "\n")
    scene = {"fenestra": 1, "geometry": "stack.obj",
             "materials": {"grey": {"reflectance": 0.5}, "screen": {"reflectance": 0.5}},
             "opening_domain": {"materials": ["screen"], "element_size": 2.0},
             "sensors": {"points": [[0, 0, 0.5]], "normals": [0, 0, 1]},
             "sky": {"type": "uniform", "radiance": 100},
             "render": {"paths_per_sensor": 64, "max_bounces": 3, "seed": 1}}
    path = folder / "scene.json"
    path.write_text(json.dumps(scene))
    return path


@pytest.fixture
def small_room(tmp_path):
    """A grey 3 x 3 x 2.5 m room whose south wall (y = 0) is the opening domain; writes scene.json."""
    return write_small_room(tmp_path)


@pytest.fixture(params=BLENDERS, ids=[b.name for b in BLENDERS])
def blender(request):
    """Each Blender the headless add-on suite runs in (blenders.py): .run(tmp_path, script, *args)."""
    if request.param.program is None:
        pytest.skip(request.param.missing)
    return request.param
