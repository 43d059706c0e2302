"""Writes the bundled example scenes (run from anywhere; needs the built fenestra module).

    /usr/bin/python3 examples/make_examples.py

reference_room: the grey 4 x 4 x 3 m room of ../shared/reference/radiance-scene-b.md, its south
    wall the opening domain, under the reference's sky (upper hemisphere 1000/pi cd/m^2, lower
    0.2 x 1000/pi), with that reference's window in window.json.
paper_scale: the benchmark scene of the size the paper reports (100 sensors, 200 elements,
    a few thousand triangles): a grey room with furniture on a ground plane, uniform sky.
"""

import json
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "addon"))
import fenestra  # noqa: E402


class Obj:
    """Minimal OBJ writer: quads split into a grid of cells, grouped, with materials."""

    def __init__(self):
        self.lines = []
        self.count = 0

    def quad(self, group, material, p0, p1, p3, nu=1, nv=1):
        """Quad with corners p0, p1 = p0 + U, p3 = p0 + V, split into nu x nv cells."""
        p0, p1, p3 = (np.asarray(p, float) for p in (p0, p1, p3))
        u, v = p1 - p0, p3 - p0
        self.lines.append("o %s\nusemtl %s" % (group, material))
        base = self.count
        for j in range(nv + 1):
            for i in range(nu + 1):
                p = p0 + u * i / nu + v * j / nv
                self.lines.append("v %.6f %.6f %.6f" % tuple(p))
        self.count += (nu + 1) * (nv + 1)
        for j in range(nv):
            for i in range(nu):
                a = base + j * (nu + 1) + i + 1
                self.lines.append("f %d %d %d %d" % (a, a + 1, a + nu + 2, a + nu + 1))

    def box(self, group, material, lo, hi):
        x0, y0, z0 = lo
        x1, y1, z1 = hi
        self.quad(group, material, (x0, y0, z1), (x1, y0, z1), (x0, y1, z1))
        self.quad(group, material, (x0, y0, z0), (x0, y1, z0), (x1, y0, z0))
        self.quad(group, material, (x0, y0, z0), (x1, y0, z0), (x0, y0, z1))
        self.quad(group, material, (x0, y1, z0), (x0, y1, z1), (x1, y1, z0))
        self.quad(group, material, (x0, y0, z0), (x0, y0, z1), (x0, y1, z0))
        self.quad(group, material, (x1, y0, z0), (x1, y1, z0), (x1, y0, z1))

    def write(self, path):
        with open(path, "w") as f:
            f.write("# written by examples/make_examples.py\n" + "\n".join(self.lines) + "\n")


def room(obj, w, d, h, south_material, n=1, south_group="wall_south"):
    """Closed room [0,w] x [0,d] x [0,h], faces wound to face inward; south wall at y = 0."""
    obj.quad("floor", "floor", (0, 0, 0), (0, d, 0), (w, 0, 0), n * int(d), n * int(w))
    obj.quad("ceiling", "ceiling", (0, 0, h), (w, 0, h), (0, d, h), n * int(w), n * int(d))
    obj.quad(south_group, south_material, (w, 0, 0), (0, 0, 0), (w, 0, h))
    obj.quad("wall_north", "wall", (0, d, 0), (w, d, 0), (0, d, h), n * int(w), n * int(h))
    obj.quad("wall_west", "wall", (0, 0, 0), (0, 0, h), (0, d, 0), n * int(h), n * int(d))
    obj.quad("wall_east", "wall", (w, 0, 0), (w, d, 0), (w, 0, h), n * int(d), n * int(h))


def reference_room():
    out = os.path.join(HERE, "reference_room")
    os.makedirs(out, exist_ok=True)
    obj = Obj()
    room(obj, 4, 4, 3, "wall_south")
    obj.write(os.path.join(out, "room.obj"))
    sky = np.zeros((32, 64, 3), np.float32)
    sky[:16] = 1000.0 / np.pi
    sky[16:] = 0.2 * 1000.0 / np.pi
    fenestra.write_image(os.path.join(out, "sky.exr"), sky)
    grid = [0.5, 1.5, 2.5, 3.5]
    scene = {
        "fenestra": 1,
        "geometry": "room.obj",
        "materials": {
            "wall": {"type": "diffuse", "reflectance": 0.5},
            "wall_south": {"type": "diffuse", "reflectance": 0.5},
            "floor": {"type": "diffuse", "reflectance": 0.5},
            "ceiling": {"type": "diffuse", "reflectance": 0.5},
        },
        "opening_domain": {"materials": ["wall_south"], "element_size": 0.25, "thickness": 0.0},
        "sensors": {"points": [[x, y, 0.8] for y in grid for x in grid], "normals": [0, 0, 1]},
        "sky": {"type": "envmap", "file": "sky.exr"},
        "render": {"paths_per_sensor": 4096, "max_bounces": 16, "seed": 1, "threads": 0},
    }
    with open(os.path.join(out, "scene.json"), "w") as f:
        json.dump(scene, f, indent=2)
    window = {"openings": [{"corners": [[1, 0, 0.9], [3, 0, 0.9], [3, 0, 2.1], [1, 0, 2.1]]}]}
    with open(os.path.join(out, "window.json"), "w") as f:
        json.dump(window, f, indent=2)


def paper_scale():
    out = os.path.join(HERE, "paper_scale")
    os.makedirs(out, exist_ok=True)
    obj = Obj()
    room(obj, 6, 6, 3, "wall_south", n=4)
    obj.box("table", "furniture", (1.5, 2.0, 0.0), (4.5, 3.2, 0.72))
    # Behind the last sensor row (y = 5.7): a sensor inside a solid sees only back faces.
    obj.box("shelf", "furniture", (0.2, 5.75, 0.0), (2.6, 5.98, 2.0))
    obj.box("neighbour", "facade", (-4.0, -14.0, -0.05), (10.0, -10.0, 7.0))
    obj.quad("ground", "ground", (-60, -60, -0.05), (60, -60, -0.05), (-60, 60, -0.05), 40, 40)
    obj.write(os.path.join(out, "scene.obj"))
    xs = np.linspace(0.3, 5.7, 10)
    scene = {
        "fenestra": 1,
        "geometry": "scene.obj",
        "materials": {
            "wall": {"type": "diffuse", "reflectance": 0.6},
            "wall_south": {"type": "diffuse", "reflectance": 0.6},
            "floor": {"type": "diffuse", "reflectance": 0.3},
            "ceiling": {"type": "diffuse", "reflectance": 0.8},
            "furniture": {"type": "diffuse", "reflectance": [0.45, 0.35, 0.25]},
            "facade": {"type": "diffuse", "reflectance": 0.35},
            "ground": {"type": "diffuse", "reflectance": 0.2},
        },
        "opening_domain": {"materials": ["wall_south"], "element_size": 0.3, "thickness": 0.0},
        "sensors": {"points": [[float(x), float(y), 0.8] for y in xs for x in xs], "normals": [0, 0, 1]},
        "sky": {"type": "uniform", "radiance": 1000.0 / np.pi},
        "render": {"paths_per_sensor": 1024, "max_bounces": 8, "seed": 1, "threads": 0},
    }
    with open(os.path.join(out, "scene.json"), "w") as f:
        json.dump(scene, f, indent=2)


if __name__ == "__main__":
    reference_room()
    paper_scale()
    print("examples written under", HERE)
