import json
import os
import sys

import numpy as np
import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "addon"))

EXAMPLES = os.path.join(ROOT, "examples")
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


@pytest.fixture
def small_room(tmp_path):
    """A grey 3 x 3 x 2.5 m room whose south wall (y = 0) is the opening domain; writes scene.json."""
    (tmp_path / "room.obj").write_text(
        box_obj((0, 0, 0), (3, 3, 2.5), lambda f: "facade" if f == "south" else "grey"))
    scene = {
        "fenestra": 1,
        "geometry": "room.obj",
        "materials": {"grey": {"type": "diffuse", "reflectance": 0.6},
                      "facade": {"type": "diffuse", "reflectance": 0.5}},
        "opening_domain": {"materials": ["facade"], "element_size": 0.5},
        "sensors": {"points": [[1.5, 1.0, 0.8], [0.5, 2.5, 0.8], [2.5, 0.5, 1.2]], "normals": [0, 0, 1]},
        "sky": {"type": "uniform", "radiance": 1000 / np.pi},
        "render": {"paths_per_sensor": 4096, "max_bounces": 8, "seed": 3},
    }
    path = tmp_path / "scene.json"
    path.write_text(json.dumps(scene))
    return path
