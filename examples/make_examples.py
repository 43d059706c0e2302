"""Writes the bundled example scenes (run from anywhere; needs the built fenestra module).

    /usr/bin/python3 examples/make_examples.py

reference_room: the grey 4 x 4 x 3 m room of ../shared/reference/radiance-scene-b.md, its south
    wall the opening domain, under the reference's sky (upper hemisphere 1000/pi cd/m^2, lower
    0.2 x 1000/pi) as an image (scene.json) and in closed form (scene_uniform.json), with that
    reference's window in window.json.
paper_scale: the benchmark scene of the size the paper reports (100 sensors, 200 elements,
    a few thousand triangles): a grey room with furniture on a ground plane, uniform sky.

Ground-truth scenes (scripts/validate.py), each with truth.json, openings aligned with the
element grid whose light becomes the sensors' goals:
window_room: a 5 x 4 x 2.8 m room on a ground plane, its south wall the opening domain (0.35 m
    elements), 30 sensors at 0.8 m, CIE overcast sky; two windows.
apartment: two rooms side by side sharing a wall with a door, the south wall of the west room and
    the east wall of the east room the opening domain (0.4 m elements), 36 sensors in both rooms,
    Preetham sky and sun on a spring morning; a window in each domain wall.
atrium: a 6 x 6 x 9 m hall with a gallery, its flat roof the opening domain (0.5 m elements),
    25 sensors on the floor and 5 on the gallery, uniform sky; two skylights.
solid_wall_room: window_room's room with its south wall modelled as a 0.3 m solid (inner face the
    opening domain, outer face and edge strips modelled, the thickness measured), 0.25 m
    elements, Preetham sky and sun on a spring morning (the sun oblique to the wall); two windows.
annual_room: a side-lit 4 x 6 x 3 m room in Chicago (O'Hare's latitude, longitude and time zone), its
    south wall the opening domain with one 2.4 x 1.5 m window (sill 0.9 m) in window.json, 96 sensors
    on a 0.5 m grid at 0.76 m; the same room written for Radiance (room.rad, sensors.pts), whose
    annual daylight-coefficient reference is python_tests/data/radiance_annual_room/. design.json is
    the same room under the Chicago weather file with climate goals instead of openings (sDA300/50%
    at least 55 %, ASE1000,250 at most 10 %, the least glazing): `make demo-annual` solves it.
deep_room: a deep side-lit 4 x 8 x 3 m room in Chicago, its south wall the opening domain (0.25 m
    elements), 128 sensors on a 0.5 m grid at 0.76 m, climate sky; climate.json asks for
    sDA300/50 % >= 55 % and ASE1000,250 <= 10 % with the least glazing (scripts/validate.py,
    "Designing for the year"; docs/validation-climate.md).
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
    # The same sky in closed form (a uniform sky over a uniform ground): no image to read, for
    # forward checks whose start-up time counts.
    scene["sky"] = {"type": "uniform", "radiance": 1000.0 / np.pi, "ground_radiance": 0.2 * 1000.0 / np.pi}
    with open(os.path.join(out, "scene_uniform.json"), "w") as f:
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


def grid_rectangle(scene, panel, rows, columns):
    """Corners (meters) of the rectangle covering elements rows[0]..rows[1] x columns[0]..columns[1]
    (inclusive) of a panel of the scene's element grid."""
    grid, corners = scene.element_grid, scene.element_corners

    def element(r, c):
        hit = np.flatnonzero((grid[:, 0] == panel) & (grid[:, 1] == r) & (grid[:, 2] == c))
        if hit.size != 1:
            raise ValueError("panel %d has no element at row %d, column %d" % (panel, r, c))
        return corners[hit[0]]

    (r0, r1), (c0, c1) = rows, columns
    quad = [element(r0, c0)[0], element(r0, c1)[1], element(r1, c1)[2], element(r1, c0)[3]]
    return [[round(float(x), 6) for x in p] for p in quad]


def panel_facing(scene, normal):
    """Index of the panel whose elements face along normal (either way) -- unique in these scenes."""
    normal = np.asarray(normal, float)
    grid, corners = scene.element_grid, scene.element_corners
    found = set()
    for k in range(len(grid)):
        c = corners[k]
        n = np.cross(c[1] - c[0], c[3] - c[0])
        if abs(np.dot(n / np.linalg.norm(n), normal)) > 0.999:
            found.add(int(grid[k, 0]))
    if len(found) != 1:
        raise ValueError("expected one panel facing %s, found %s" % (normal, sorted(found)))
    return found.pop()


def write_scene(out, scene, openings):
    """Writes scene.json and truth.json (openings given as (normal, rows, columns) on the grid)."""
    with open(os.path.join(out, "scene.json"), "w") as f:
        json.dump(scene, f, indent=2)
    loaded = fenestra.load_scene(os.path.join(out, "scene.json"))
    truth = {"openings": [{"corners": grid_rectangle(loaded, panel_facing(loaded, n), rows, columns)}
                          for n, rows, columns in openings]}
    with open(os.path.join(out, "truth.json"), "w") as f:
        json.dump(truth, f, indent=2)


GREY = {
    "wall": {"type": "diffuse", "reflectance": 0.6},
    "facade": {"type": "diffuse", "reflectance": 0.6},
    "floor": {"type": "diffuse", "reflectance": 0.3},
    "ceiling": {"type": "diffuse", "reflectance": 0.8},
    "ground": {"type": "diffuse", "reflectance": 0.2},
}


def window_room():
    out = os.path.join(HERE, "window_room")
    os.makedirs(out, exist_ok=True)
    obj = Obj()
    room(obj, 5, 4, 2.8, "facade")
    obj.quad("ground", "ground", (-20, -20, -0.05), (20, -20, -0.05), (-20, 20, -0.05))
    obj.write(os.path.join(out, "scene.obj"))
    xs, ys = np.linspace(0.5, 4.5, 6), np.linspace(0.5, 3.5, 5)
    scene = {
        "fenestra": 1,
        "geometry": "scene.obj",
        "materials": GREY,
        "opening_domain": {"materials": ["facade"], "element_size": 0.35, "thickness": 0.0},
        "sensors": {"points": [[float(x), float(y), 0.8] for y in ys for x in xs], "normals": [0, 0, 1]},
        "sky": {"type": "cie_overcast", "horizontal_illuminance": 10000.0, "ground_reflectance": 0.2,
                "resolution": [256, 128]},
        "render": {"paths_per_sensor": 4096, "max_bounces": 8, "seed": 1, "threads": 0},
    }
    # 14 columns (from x = 4.95 toward x = 0) x 8 rows (from the floor up).
    write_scene(out, scene, [((0, 1, 0), (2, 6), (1, 4)), ((0, 1, 0), (2, 6), (8, 11))])


def apartment():
    out = os.path.join(HERE, "apartment")
    os.makedirs(out, exist_ok=True)
    w1, w2, d, h = 5.0, 4.0, 4.0, 2.8
    door = (2.6, 3.5, 2.1)  # y from, y to, height
    w = w1 + w2
    obj = Obj()
    obj.quad("floor", "floor", (0, 0, 0), (0, d, 0), (w, 0, 0), 4, 9)
    obj.quad("ceiling", "ceiling", (0, 0, h), (w, 0, h), (0, d, h), 9, 4)
    obj.quad("west_room_south", "facade", (w1, 0, 0), (0, 0, 0), (w1, 0, h))
    obj.quad("east_room_south", "wall", (w, 0, 0), (w1, 0, 0), (w, 0, h), 4, 3)
    obj.quad("wall_north", "wall", (0, d, 0), (w, d, 0), (0, d, h), 9, 3)
    obj.quad("wall_west", "wall", (0, 0, 0), (0, 0, h), (0, d, 0), 3, 4)
    obj.quad("east_room_east", "facade", (w, 0, 0), (w, d, 0), (w, 0, h))
    # The shared wall (both faces of one surface), with the door between the rooms.
    obj.quad("partition", "wall", (w1, 0, 0), (w1, door[0], 0), (w1, 0, h), 3, 3)
    obj.quad("partition", "wall", (w1, door[1], 0), (w1, d, 0), (w1, door[1], h), 1, 3)
    obj.quad("partition", "wall", (w1, door[0], door[2]), (w1, door[1], door[2]), (w1, door[0], h))
    obj.quad("ground", "ground", (-20, -20, -0.05), (30, -20, -0.05), (-20, 30, -0.05))
    obj.write(os.path.join(out, "scene.obj"))
    ys = np.linspace(0.5, 3.5, 4)
    points = [[float(x), float(y), 0.8] for y in ys for x in np.linspace(0.5, 4.5, 5)]
    points += [[float(x), float(y), 0.8] for y in ys for x in np.linspace(5.5, 8.5, 4)]
    scene = {
        "fenestra": 1,
        "geometry": "scene.obj",
        "materials": GREY,
        "opening_domain": {"materials": ["facade"], "element_size": 0.4, "thickness": 0.0},
        "sensors": {"points": points, "normals": [0, 0, 1]},
        "sky": {"type": "preetham", "latitude": 48.85, "longitude": 2.35, "timezone": "Europe/Paris",
                "date": "2026-03-21", "time": "10:00", "turbidity": 3.0, "ground_reflectance": 0.2,
                "resolution": [256, 128]},
        "render": {"paths_per_sensor": 4096, "max_bounces": 8, "seed": 1, "threads": 0},
    }
    # South wall: 12 columns (from x = 4.9 toward x = 0) x 7 rows; east wall: 10 columns x 7 rows.
    write_scene(out, scene, [((0, 1, 0), (2, 5), (3, 7)), ((1, 0, 0), (2, 5), (2, 5))])


def atrium():
    out = os.path.join(HERE, "atrium")
    os.makedirs(out, exist_ok=True)
    w, h, gallery = 6.0, 9.0, 4.5
    obj = Obj()
    obj.quad("floor", "floor", (0, 0, 0), (0, w, 0), (w, 0, 0), 6, 6)
    obj.quad("roof", "roof", (0, 0, h), (w, 0, h), (0, w, h))
    obj.quad("wall_south", "wall", (w, 0, 0), (0, 0, 0), (w, 0, h), 6, 9)
    obj.quad("wall_north", "wall", (0, w, 0), (w, w, 0), (0, w, h), 6, 9)
    obj.quad("wall_west", "wall", (0, 0, 0), (0, 0, h), (0, w, 0), 9, 6)
    obj.quad("wall_east", "wall", (w, 0, 0), (w, w, 0), (w, 0, h), 6, 9)
    obj.box("gallery", "floor", (0.0, 4.5, gallery - 0.25), (w, w, gallery))
    obj.write(os.path.join(out, "scene.obj"))
    xs = np.linspace(0.6, 5.4, 5)
    points = [[float(x), float(y), 0.1] for y in np.linspace(0.6, 3.8, 5) for x in xs]
    points += [[float(x), 5.25, gallery + 0.8] for x in xs]
    materials = dict(GREY, roof={"type": "diffuse", "reflectance": 0.7})
    scene = {
        "fenestra": 1,
        "geometry": "scene.obj",
        "materials": materials,
        "opening_domain": {"materials": ["roof"], "element_size": 0.5, "thickness": 0.0},
        "sensors": {"points": points, "normals": [0, 0, 1]},
        "sky": {"type": "uniform", "radiance": 1000.0 / np.pi},
        "render": {"paths_per_sensor": 4096, "max_bounces": 8, "seed": 1, "threads": 0},
    }
    # 12 x 12 elements, rows along +X.
    write_scene(out, scene, [((0, 0, 1), (2, 4), (2, 8)), ((0, 0, 1), (7, 9), (4, 6))])


def solid_wall_room():
    out = os.path.join(HERE, "solid_wall_room")
    os.makedirs(out, exist_ok=True)
    w, d, h, t = 5.0, 4.0, 2.8, 0.3
    obj = Obj()
    room(obj, w, d, h, "facade")
    # The south wall's body: outer face at y = -t and the strips closing it.
    obj.quad("wall_south_outer", "wall", (0, -t, 0), (w, -t, 0), (0, -t, h))
    obj.quad("wall_south_bottom", "wall", (0, -t, 0), (0, 0, 0), (w, -t, 0))
    obj.quad("wall_south_top", "wall", (0, -t, h), (w, -t, h), (0, 0, h))
    obj.quad("wall_south_west", "wall", (0, -t, 0), (0, -t, h), (0, 0, 0))
    obj.quad("wall_south_east", "wall", (w, -t, 0), (w, 0, 0), (w, -t, h))
    obj.quad("ground", "ground", (-20, -20, -0.05), (20, -20, -0.05), (-20, 20, -0.05))
    obj.write(os.path.join(out, "scene.obj"))
    xs, ys = np.linspace(0.5, 4.5, 6), np.linspace(0.5, 3.5, 5)
    scene = {
        "fenestra": 1,
        "geometry": "scene.obj",
        "materials": GREY,
        "opening_domain": {"materials": ["facade"], "element_size": 0.25},
        "sensors": {"points": [[float(x), float(y), 0.8] for y in ys for x in xs], "normals": [0, 0, 1]},
        "sky": {"type": "preetham", "latitude": 48.85, "longitude": 2.35, "timezone": "Europe/Paris",
                "date": "2026-03-21", "time": "10:00", "turbidity": 3.0, "ground_reflectance": 0.2,
                "resolution": [256, 128]},
        "render": {"paths_per_sensor": 4096, "max_bounces": 8, "seed": 1, "threads": 0},
    }
    # 20 columns (from x = 5 toward x = 0) x 11 rows (from the floor up).
    write_scene(out, scene, [((0, 1, 0), (3, 8), (3, 7)), ((0, 1, 0), (3, 8), (12, 16))])


def fan(obj, group, material, centre, points):
    """Triangles from centre to each pair of consecutive points (a sector floor, a gable)."""
    obj.lines.append("o %s\nusemtl %s" % (group, material))
    base = obj.count
    for p in [centre] + list(points):
        obj.lines.append("v %.6f %.6f %.6f" % tuple(p))
    obj.count += 1 + len(points)
    for i in range(len(points) - 1):
        obj.lines.append("f %d %d %d" % (base + 1, base + 2 + i, base + 3 + i))


def strip(obj, group, material, lower, upper):
    """Quads between two polylines of equal length (a faceted curved surface)."""
    obj.lines.append("o %s\nusemtl %s" % (group, material))
    base = obj.count
    for p in list(lower) + list(upper):
        obj.lines.append("v %.6f %.6f %.6f" % tuple(p))
    n = len(lower)
    obj.count += 2 * n
    for i in range(n - 1):
        a = base + 1 + i
        obj.lines.append("f %d %d %d %d" % (a, a + 1, a + n + 1, a + n))


def write_parameter_truth(out, scene, openings):
    """Writes scene.json and truth.json with openings on panel 0 given as parameter rectangles
    (rows, columns) of its element grid (inclusive), in meters of its chart."""
    with open(os.path.join(out, "scene.json"), "w") as f:
        json.dump(scene, f, indent=2)
    loaded = fenestra.load_scene(os.path.join(out, "scene.json"))
    a = loaded.element_size
    truth = {"openings": [{"panel": 0, "parameter_rectangle": {"u0": round(c0 * a, 6), "u1": round((c1 + 1) * a, 6),
                                                               "v0": round(r0 * a, 6), "v1": round((r1 + 1) * a, 6)}}
                          for (r0, r1), (c0, c1) in openings]}
    with open(os.path.join(out, "truth.json"), "w") as f:
        json.dump(truth, f, indent=2)


def overcast_scene(materials, domain_material, element_size, points):
    """A scene file of scene.obj under a CIE overcast sky, horizontal work-plane sensors at points."""
    return {
        "fenestra": 1,
        "geometry": "scene.obj",
        "materials": materials,
        "opening_domain": {"materials": [domain_material], "element_size": element_size, "thickness": 0.0},
        "sensors": {"points": points, "normals": [0, 0, 1]},
        "sky": {"type": "cie_overcast", "horizontal_illuminance": 10000.0, "ground_reflectance": 0.2,
                "resolution": [256, 128]},
        "render": {"paths_per_sensor": 4096, "max_bounces": 8, "seed": 1, "threads": 0},
    }


def curved_wall_room():
    """A quarter-circle room (radius 4 m): two straight walls along +X and +Y from the centre, and
    90 degrees of a cylinder between them, 16 facets, the opening domain (unrolled: no UV map)."""
    out = os.path.join(HERE, "curved_wall_room")
    os.makedirs(out, exist_ok=True)
    r, h, facets = 4.0, 3.0, 16
    angles = np.linspace(0.0, np.pi / 2, facets + 1)
    arc = [(r * np.cos(t), r * np.sin(t)) for t in angles]
    obj = Obj()
    fan(obj, "floor", "floor", (0, 0, 0), [(x, y, 0) for x, y in arc])
    fan(obj, "ceiling", "ceiling", (0, 0, h), [(x, y, h) for x, y in reversed(arc)])
    obj.quad("wall_x", "wall", (0, 0, 0), (0, 0, h), (r, 0, 0))
    obj.quad("wall_y", "wall", (0, 0, 0), (0, r, 0), (0, 0, h))
    strip(obj, "wall_curved", "facade", [(x, y, 0) for x, y in arc], [(x, y, h) for x, y in arc])
    obj.quad("ground", "ground", (-20, -20, -0.05), (20, -20, -0.05), (-20, 20, -0.05))
    obj.write(os.path.join(out, "scene.obj"))
    points = [[float(x), float(y), 0.8] for y in np.linspace(0.5, 3.3, 5) for x in np.linspace(0.5, 3.3, 5)
              if np.hypot(x, y) < r - 0.5]
    scene = overcast_scene(GREY, "facade", 0.3, points)
    # 20 columns along the arc x 10 rows (from the floor up); each opening spans several facets.
    write_parameter_truth(out, scene, [((3, 7), (2, 6)), ((2, 8), (12, 15))])


def vault_room():
    """A 6 x 4 m room with 2.5 m walls under a barrel vault (a half cylinder of radius 2 m along X,
    16 facets), the opening domain; gables close its ends."""
    out = os.path.join(HERE, "vault_room")
    os.makedirs(out, exist_ok=True)
    w, d, h, r, facets = 6.0, 4.0, 2.5, 2.0, 16
    angles = np.linspace(0.0, np.pi, facets + 1)
    arch = [(d / 2 + r * np.cos(t), h + r * np.sin(t)) for t in angles]  # (y, z), from y = 4 to y = 0
    obj = Obj()
    obj.quad("floor", "floor", (0, 0, 0), (0, d, 0), (w, 0, 0), 4, 6)
    obj.quad("wall_south", "wall", (w, 0, 0), (0, 0, 0), (w, 0, h))
    obj.quad("wall_north", "wall", (0, d, 0), (w, d, 0), (0, d, h))
    obj.quad("wall_west", "wall", (0, 0, 0), (0, 0, h), (0, d, 0))
    obj.quad("wall_east", "wall", (w, 0, 0), (w, d, 0), (w, 0, h))
    fan(obj, "gable_west", "wall", (0, d / 2, h), [(0, y, z) for y, z in arch])
    fan(obj, "gable_east", "wall", (w, d / 2, h), [(w, y, z) for y, z in reversed(arch)])
    strip(obj, "vault", "roof", [(w, y, z) for y, z in arch], [(0, y, z) for y, z in arch])
    obj.quad("ground", "ground", (-20, -20, -0.05), (20, -20, -0.05), (-20, 20, -0.05))
    obj.write(os.path.join(out, "scene.obj"))
    points = [[float(x), float(y), 0.8] for y in np.linspace(0.5, 3.5, 4) for x in np.linspace(0.5, 5.5, 6)]
    materials = dict(GREY, roof={"type": "diffuse", "reflectance": 0.7})
    scene = overcast_scene(materials, "roof", 0.4, points)
    # 15 columns along the vault's axis x 15 rows around the arch.
    write_parameter_truth(out, scene, [((3, 5), (2, 4)), ((8, 10), (9, 12))])


# The annual reference room: Chicago O'Hare (examples/weather), as the EPW's LOCATION gives it.
CHICAGO = {"latitude": 41.98, "longitude": -87.92, "elevation": 201.0, "utc_offset": -6.0}
ANNUAL_ROOM = {"width": 4.0, "depth": 6.0, "height": 3.0,
               "window": (0.8, 3.2, 0.9, 2.4),   # x0, x1, z0, z1 in the south wall y = 0
               "reflectance": {"floor": 0.2, "wall": 0.5, "wall_south": 0.5, "ceiling": 0.7},
               "sensor_height": 0.76, "sensor_spacing": 0.5}


def annual_room_sensors():
    """Cell centres of a 0.5 m grid over the floor at 0.76 m, x fastest (8 x 12 = 96)."""
    r = ANNUAL_ROOM
    a = r["sensor_spacing"]
    xs = np.arange(a / 2, r["width"], a)
    ys = np.arange(a / 2, r["depth"], a)
    return [[float(x), float(y), r["sensor_height"]] for y in ys for x in xs]


def annual_room_rad():
    """The same room for Radiance: Lambertian plastic, zero-thickness walls, the window a hole."""
    r = ANNUAL_ROOM
    w, d, h = r["width"], r["depth"], r["height"]
    x0, x1, z0, z1 = r["window"]
    rho = r["reflectance"]
    lines = ["# written by examples/make_examples.py: the annual_room of scene.json for Radiance.",
             "# Meters; +X east, +Y north, +Z up. Lambertian (plastic, no specularity), grey.",
             "# The window x in [%g, %g], z in [%g, %g] of the south wall y = 0 is a hole." % (x0, x1, z0, z1),
             ""]
    for name in ("floor", "wall", "ceiling"):
        v = rho[name]
        lines += ["void plastic %s_mat\n0\n0\n5 %g %g %g 0 0\n" % (name, v, v, v)]

    def polygon(material, name, points):
        lines.append("%s polygon %s\n0\n0\n%d" % (material, name, 3 * len(points)))
        for p in points[::-1]:  # counter-clockwise seen from inside: the normal faces the room
            lines.append("    %g %g %g" % tuple(p))
        lines.append("")

    # Each list runs clockwise seen from inside the room (written reversed).
    polygon("floor_mat", "floor", [(0, 0, 0), (0, d, 0), (w, d, 0), (w, 0, 0)])
    polygon("ceiling_mat", "ceiling", [(0, 0, h), (w, 0, h), (w, d, h), (0, d, h)])
    polygon("wall_mat", "wall_north", [(0, d, 0), (0, d, h), (w, d, h), (w, d, 0)])
    polygon("wall_mat", "wall_west", [(0, 0, 0), (0, 0, h), (0, d, h), (0, d, 0)])
    polygon("wall_mat", "wall_east", [(w, 0, 0), (w, d, 0), (w, d, h), (w, 0, h)])
    # South wall (normal +Y) around the window hole.
    polygon("wall_mat", "wall_south_below", [(0, 0, 0), (w, 0, 0), (w, 0, z0), (0, 0, z0)])
    polygon("wall_mat", "wall_south_above", [(0, 0, z1), (w, 0, z1), (w, 0, h), (0, 0, h)])
    polygon("wall_mat", "wall_south_west", [(0, 0, z0), (x0, 0, z0), (x0, 0, z1), (0, 0, z1)])
    polygon("wall_mat", "wall_south_east", [(x1, 0, z0), (w, 0, z0), (w, 0, z1), (x1, 0, z1)])
    return "\n".join(lines)


def annual_room():
    out = os.path.join(HERE, "annual_room")
    os.makedirs(out, exist_ok=True)
    r = ANNUAL_ROOM
    obj = Obj()
    room(obj, r["width"], r["depth"], r["height"], "wall_south")
    obj.write(os.path.join(out, "scene.obj"))
    sensors = annual_room_sensors()
    rho = r["reflectance"]
    scene = {
        "fenestra": 1,
        "geometry": "scene.obj",
        "materials": {name: {"type": "diffuse", "reflectance": v} for name, v in rho.items()},
        "opening_domain": {"materials": ["wall_south"], "element_size": 0.25, "thickness": 0.0},
        "sensors": {"points": sensors, "normals": [0, 0, 1]},
        # The place and clock of the Chicago weather file; the annual study takes its skies from
        # examples/weather (see annual_room/README.md), this day's sky only pins the place.
        "sky": dict({"type": "preetham", "date": "2026-03-21", "start": "08:00", "end": "18:00",
                     "step_minutes": 30, "ground_reflectance": 0.2}, **CHICAGO),
        "render": {"paths_per_sensor": 4096, "max_bounces": 16, "seed": 1, "threads": 0},
    }
    with open(os.path.join(out, "scene.json"), "w") as f:
        json.dump(scene, f, indent=2)
    x0, x1, z0, z1 = r["window"]
    window = {"openings": [{"corners": [[x0, 0, z0], [x1, 0, z0], [x1, 0, z1], [x0, 0, z1]]}]}
    with open(os.path.join(out, "window.json"), "w") as f:
        json.dump(window, f, indent=2)
    with open(os.path.join(out, "room.rad"), "w") as f:
        f.write(annual_room_rad())
    with open(os.path.join(out, "sensors.pts"), "w") as f:
        f.write("".join("%g %g %g 0 0 1\n" % tuple(p) for p in sensors))


def annual_room_design():
    """annual_room's scene under its weather file with climate goals (docs/scene-format.md): the
    openings that give sDA300/50% >= 55 % and ASE1000,250 <= 10 % with the least glazing. Paths and
    generations keep `make demo-annual` to about a minute on two cores."""
    out = os.path.join(HERE, "annual_room")
    with open(os.path.join(out, "scene.json")) as f:
        scene = json.load(f)
    scene["sky"] = {"type": "climate", "weather": "../weather/USA_IL_Chicago-OHare.Intl.AP.725300_TMY3.epw",
                    "occupied": ["08:00", "18:00"], "patches": 1, "ground_reflectance": 0.2}
    scene["goals"] = {"climate": [{"metric": "sda", "sensors": "all", "illuminance_lux": 300, "time_fraction": 0.5,
                                   "min_area_fraction": 0.55},
                                  {"metric": "ase", "sensors": "all", "illuminance_lux": 1000, "hours": 250,
                                   "max_area_fraction": 0.10}],
                      "least_glazing": True}
    scene["render"] = {"paths_per_sensor": 2048, "max_bounces": 16, "seed": 1, "threads": 0}
    scene["solver"] = {"generations": 100, "seed": 1}
    with open(os.path.join(out, "design.json"), "w") as f:
        json.dump(scene, f, indent=2)


# A deep side-lit room for designing to the year's standards (scripts/validate.py): the climate
# goals of LEED v4 option 1 (sDA300/50 % >= 55 %, ASE1000,250 <= 10 %) with the least glazing.
DEEP_ROOM = {"width": 4.0, "depth": 8.0, "height": 3.0, "element_size": 0.25,
             "reflectance": {"floor": 0.2, "wall": 0.5, "wall_south": 0.5, "ceiling": 0.7},
             "sensor_height": 0.76, "sensor_spacing": 0.5}


def deep_room_sensors():
    """Cell centres of a 0.5 m grid over the floor at 0.76 m, x fastest (8 x 16 = 128)."""
    r = DEEP_ROOM
    a = r["sensor_spacing"]
    return [[float(x), float(y), r["sensor_height"]]
            for y in np.arange(a / 2, r["depth"], a) for x in np.arange(a / 2, r["width"], a)]


def deep_room():
    out = os.path.join(HERE, "deep_room")
    os.makedirs(out, exist_ok=True)
    r = DEEP_ROOM
    obj = Obj()
    room(obj, r["width"], r["depth"], r["height"], "wall_south")
    obj.write(os.path.join(out, "scene.obj"))
    scene = {
        "fenestra": 1,
        "geometry": "scene.obj",
        "materials": {name: {"type": "diffuse", "reflectance": v} for name, v in r["reflectance"].items()},
        "opening_domain": {"materials": ["wall_south"], "element_size": r["element_size"], "thickness": 0.0},
        "sensors": {"points": deep_room_sensors(), "normals": [0, 0, 1]},
        "sky": {"type": "climate", "weather": "../weather/USA_IL_Chicago-OHare.Intl.AP.725300_TMY3.epw",
                "occupied": ["08:00", "18:00"], "patches": 1, "ground_reflectance": 0.2},
        "goals": {"climate": [
            {"metric": "sda", "sensors": "all", "illuminance_lux": 300, "time_fraction": 0.5, "min_area_fraction": 0.55},
            {"metric": "ase", "sensors": "all", "illuminance_lux": 1000, "hours": 250, "max_area_fraction": 0.10}],
            "least_glazing": True},
        "render": {"paths_per_sensor": 2048, "max_bounces": 16, "seed": 1, "threads": 0},
        "solver": {"paths": 2048, "population": 64, "generations": 250, "seed": 1, "verify_paths": 8192},
    }
    with open(os.path.join(out, "climate.json"), "w") as f:
        json.dump(scene, f, indent=2)


if __name__ == "__main__":
    reference_room()
    paper_scale()
    window_room()
    apartment()
    atrium()
    solid_wall_room()
    curved_wall_room()
    vault_room()
    annual_room()
    annual_room_design()
    deep_room()
    print("examples written under", HERE)
