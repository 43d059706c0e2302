"""Curved opening domains through the command line and Python: a faceted cylindrical wall is one
panel diced along its surface (unrolled, or in its UV map scaled to meters); openings on it are
given by "panel" and "parameter_rectangle", and the solver's result describes them by their
surface grid; bad curved domains and bad parameter rectangles are refused with a message, nothing
written, never a crash.

The scenes are small: a quarter-circle room (radius 2.5 m, 2 m high) whose curved wall, 90 degrees
of a cylinder in 16 flat facets, is the opening domain; three sensors; a uniform sky."""

import concurrent.futures
import json
import math
import os
import random
import re
import subprocess

import numpy as np
import pytest

import fenestra
from conftest import CLI

RADIUS, HEIGHT, FACETS = 2.5, 2.0, 16
ARC = math.pi / 2
CHORD = 2 * RADIUS * math.sin(ARC / FACETS / 2)  # a facet's width, m
UNROLLED = FACETS * CHORD  # the wall's width along its facets, m
SENSORS = [[0.6, 0.6, 0.8], [1.3, 0.4, 0.8], [0.4, 1.4, 0.8]]
WINDOW = {"u0": 1.0, "u1": 2.5, "v0": 0.5, "v1": 1.5}  # on the curved wall, 0.5 m elements


def run(*args, timeout=120):
    return subprocess.run([CLI, *map(str, args)], capture_output=True, text=True, errors="replace",
                          timeout=timeout)


class Obj:
    """OBJ text: vertices, texture coordinates and faces, in groups with materials."""

    def __init__(self):
        self.lines, self.v, self.vt = [], 0, 0

    def vertices(self, points):
        """Appends the points; returns the OBJ index of the first."""
        self.lines += ["v %.9f %.9f %.9f" % tuple(p) for p in points]
        self.v += len(points)
        return self.v - len(points) + 1

    def texcoords(self, points):
        self.lines += ["vt %.9f %.9f" % tuple(p) for p in points]
        self.vt += len(points)
        return self.vt - len(points) + 1

    def group(self, name, material):
        self.lines += ["o %s" % name, "usemtl %s" % material]

    def face(self, vertices, texcoords=None):
        if texcoords is None:
            self.lines.append("f " + " ".join(map(str, vertices)))
        else:
            self.lines.append("f " + " ".join("%d/%d" % vt for vt in zip(vertices, texcoords)))

    def text(self):
        return "\n".join(self.lines) + "\n"


def arc_point(k, radius=RADIUS):
    """The curved wall's k-th vertical edge (0..FACETS) at floor height."""
    angle = k * ARC / FACETS
    return np.array([radius * math.cos(angle), radius * math.sin(angle), 0.0])


def curved_room(uv=None, behind=None, flat_material="grey", notch=None):
    """The closed quarter-circle room; its curved wall (material "facade") has the UV map uv(k, z)
    at edge k and height z when given, and a second wall `behind` meters outside it when given.
    The flat wall along the x axis (y = 0) has `flat_material`. With notch = (first, last, z), the
    wall's facets are split at height z, and facets first..last are grey above it."""
    obj = Obj()
    arc = [arc_point(k) for k in range(FACETS + 1)]
    up = np.array([0.0, 0.0, HEIGHT])
    obj.group("floor", "grey")
    c = obj.vertices([np.zeros(3)] + arc)
    for k in range(FACETS):
        obj.face([c, c + k + 2, c + k + 1])
    obj.group("ceiling", "grey")
    c = obj.vertices([up] + [p + up for p in arc])
    for k in range(FACETS):
        obj.face([c, c + k + 1, c + k + 2])
    obj.group("wall_x", flat_material)
    c = obj.vertices([np.zeros(3), arc[0], arc[0] + up, up])
    obj.face([c, c + 1, c + 2, c + 3])
    obj.group("wall_y", "grey")
    c = obj.vertices([np.zeros(3), up, arc[-1] + up, arc[-1]])
    obj.face([c, c + 1, c + 2, c + 3])
    obj.group("wall_curved", "facade")
    bottom = obj.vertices(arc)
    top = obj.vertices([p + up for p in arc])
    if notch is not None:
        first, last, z = notch
        middle = obj.vertices([p + np.array([0.0, 0.0, z]) for p in arc])
        upper = [[middle + k, middle + k + 1, top + k + 1, top + k] for k in range(FACETS)]
        for k in range(FACETS):
            obj.face([bottom + k, bottom + k + 1, middle + k + 1, middle + k])
            if not first <= k <= last:
                obj.face(upper[k])
        obj.group("wall_notch", "grey")
        for k in range(first, last + 1):
            obj.face(upper[k])
    else:
        if uv is not None:
            tb = obj.texcoords([uv(k, 0.0) for k in range(FACETS + 1)])
            tt = obj.texcoords([uv(k, HEIGHT) for k in range(FACETS + 1)])
        for k in range(FACETS):
            quad = [bottom + k, bottom + k + 1, top + k + 1, top + k]
            obj.face(quad, None if uv is None else [tb + k, tb + k + 1, tt + k + 1, tt + k])
    if behind is not None:
        obj.group("wall_curved_outer", "grey")
        outer = [arc_point(k, RADIUS + behind) for k in range(FACETS + 1)]
        b = obj.vertices(outer)
        t = obj.vertices([p + up for p in outer])
        for k in range(FACETS):
            obj.face([b + k, t + k, t + k + 1, b + k + 1])
    return obj.text()


def dome(radius=2.0, sectors=16, bands=6):
    """A faceted hemisphere (material "facade") on a round floor; no UV map."""
    obj = Obj()

    def ring(latitude):
        return [radius * np.array([math.cos(latitude) * math.cos(2 * math.pi * k / sectors),
                                   math.cos(latitude) * math.sin(2 * math.pi * k / sectors),
                                   math.sin(latitude)]) for k in range(sectors)]

    obj.group("floor", "grey")
    c = obj.vertices([np.zeros(3)] + ring(0.0))
    for k in range(sectors):
        obj.face([c, c + 1 + (k + 1) % sectors, c + 1 + k])
    obj.group("dome", "facade")
    starts = [obj.vertices(ring(0.5 * math.pi * i / bands)) for i in range(bands)]
    apex = obj.vertices([np.array([0.0, 0.0, radius])])
    for a, b in zip(starts, starts[1:]):
        for k in range(sectors):
            k1 = (k + 1) % sectors
            obj.face([a + k, a + k1, b + k1, b + k])
    for k in range(sectors):
        obj.face([starts[-1] + k, starts[-1] + (k + 1) % sectors, apex])
    return obj.text()


def closed_cylinder(radius=2.0, sectors=16):
    """A whole cylinder of 16 facets (material "facade"), with floor and ceiling; no UV map."""
    obj = Obj()
    ring = [np.array([radius * math.cos(2 * math.pi * k / sectors), radius * math.sin(2 * math.pi * k / sectors), 0.0])
            for k in range(sectors)]
    up = np.array([0.0, 0.0, HEIGHT])
    obj.group("floor", "grey")
    c = obj.vertices([np.zeros(3)] + ring)
    for k in range(sectors):
        obj.face([c, c + 1 + (k + 1) % sectors, c + 1 + k])
    obj.group("ceiling", "grey")
    c = obj.vertices([up] + [p + up for p in ring])
    for k in range(sectors):
        obj.face([c, c + 1 + k, c + 1 + (k + 1) % sectors])
    obj.group("drum", "facade")
    bottom = obj.vertices(ring)
    top = obj.vertices([p + up for p in ring])
    for k in range(sectors):
        k1 = (k + 1) % sectors
        obj.face([bottom + k, bottom + k1, top + k1, top + k])
    return obj.text()


def scene_dict(element_size=0.25, domain=("facade",), **extra):
    scene = {
        "fenestra": 1,
        "geometry": "room.obj",
        "materials": {"grey": {"type": "diffuse", "reflectance": 0.6},
                      "facade": {"type": "diffuse", "reflectance": 0.5},
                      "facade_flat": {"type": "diffuse", "reflectance": 0.5}},
        "opening_domain": {"materials": list(domain), "element_size": element_size},
        "sensors": {"points": SENSORS, "normals": [0, 0, 1]},
        "sky": {"type": "uniform", "radiance": 1000 / math.pi},
        "render": {"paths_per_sensor": 256, "max_bounces": 6, "seed": 3},
    }
    scene.update(extra)
    return scene


def write_scene(folder, obj_text, **scene):
    """Writes folder/room.obj and folder/scene.json; returns the scene file's path."""
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "room.obj").write_text(obj_text)
    path = folder / "scene.json"
    path.write_text(json.dumps(scene_dict(**scene)))
    return path


def write_openings(path, openings):
    path.write_text(json.dumps({"openings": openings}))
    return path


def facet_distance(points):
    """Distance of each point to the nearest facet of the curved wall (flat rectangles between
    consecutive edges, from the floor to HEIGHT)."""
    points = np.asarray(points, float).reshape(-1, 3)
    best = np.full(len(points), np.inf)
    for k in range(FACETS):
        a, b = arc_point(k), arc_point(k + 1)
        along = (b - a) / np.linalg.norm(b - a)
        d = points - a
        x = np.clip(d @ along, 0.0, np.linalg.norm(b - a))
        z = np.clip(points[:, 2], 0.0, HEIGHT)
        nearest = a + x[:, None] * along + z[:, None] * np.array([0.0, 0.0, 1.0])
        best = np.minimum(best, np.linalg.norm(points - nearest, axis=1))
    return best


def summary_panels(scene_path, folder, cli=False):
    """The panels of the contributions summary, written by `fenestra contributions` or by
    Contributions.save() (a few paths: only the layout is used)."""
    folder.mkdir(parents=True, exist_ok=True)
    out = folder / "summary"
    if cli:
        r = run("contributions", scene_path, "-o", out, "--paths", 8, "--quiet")
        assert r.returncode == 0, r.stderr
    else:
        scene = fenestra.load_scene(scene_path)
        scene.render.paths_per_sensor = 8
        fenestra.contributions(scene).save(scene, str(out))
    return json.loads((folder / "summary.json").read_text())["panels"]


def elements_by_cell(scene):
    grid, corners = scene.element_grid, scene.element_corners
    return {(int(p), int(r), int(c)): corners[k] for k, (p, r, c) in enumerate(grid)}


# 1. A curved wall without UVs: unrolled.

def test_curved_wall_without_uv_is_one_panel_diced_along_its_facets(tmp_path):
    size = 0.25
    path = write_scene(tmp_path, curved_room(), element_size=size)
    scene = fenestra.load_scene(path)
    grid, corners = scene.element_grid, scene.element_corners
    assert set(grid[:, 0]) == {0}, "the 16 facets must form one panel"
    columns, rows = math.floor(UNROLLED / size), math.floor(HEIGHT / size)
    # 15 x 8 here; the straight chord of the whole arc (3.54 m) would give 14 columns.
    assert (columns, rows) == (15, 8)
    assert scene.element_count == columns * rows
    assert set(grid[:, 1]) == set(range(rows)) and set(grid[:, 2]) == set(range(columns))
    # Every corner lies on the faceted wall, not on a chord across it.
    assert facet_distance(corners).max() < 1e-4
    # Neighbours share their corners: the elements tile the surface without gaps.
    cells = elements_by_cell(scene)
    shared = 0
    for (p, r, c), q in cells.items():
        if (p, r, c + 1) in cells:
            right = cells[(p, r, c + 1)]
            assert np.allclose(q[1], right[0], atol=1e-5) and np.allclose(q[2], right[3], atol=1e-5)
            shared += 1
        if (p, r + 1, c) in cells:
            above = cells[(p, r + 1, c)]
            assert np.allclose(q[3], above[0], atol=1e-5) and np.allclose(q[2], above[1], atol=1e-5)
            shared += 1
    assert shared == rows * (columns - 1) + (rows - 1) * columns
    # Elements are size x size patches of the surface: a row's corners, followed along the wall,
    # are `size` apart (a chord across a facet edge is a hair shorter), and each element's sides are.
    for r in range(rows):
        row = [cells[(0, r, c)] for c in range(columns)]
        path_points = np.array([row[0][0]] + [q[1] for q in row])
        steps = np.linalg.norm(np.diff(path_points, axis=0), axis=1)
        assert np.all(steps <= size + 1e-5) and np.all(steps > 0.998 * size), steps
    heights = np.linalg.norm(corners[:, 3] - corners[:, 0], axis=1)
    assert np.allclose(heights, size, atol=1e-5)
    # Consistently oriented (no element mirrored): every element's normal on the same side.
    radial = corners.mean(axis=1) * np.array([1.0, 1.0, 0.0])
    normals = np.cross(corners[:, 1] - corners[:, 0], corners[:, 3] - corners[:, 0])
    side = np.sign(np.einsum("ij,ij->i", normals, radial))
    assert abs(side.sum()) == len(side)
    # The grid is centred: equal margins at both ends of the wall.
    panel, = summary_panels(path, tmp_path, cli=True)
    assert panel["parameterisation"] == "unrolled"
    assert (panel["rows"], panel["cols"]) == (rows, columns)
    domain = panel["parameter_domain"]
    assert domain["u1"] - domain["u0"] == pytest.approx(UNROLLED, abs=1e-4)
    assert domain["v1"] - domain["v0"] == pytest.approx(HEIGHT, abs=1e-4)
    margin = (UNROLLED - columns * size) / 2
    assert domain["u0"] == pytest.approx(-margin, abs=1e-4)
    assert domain["u1"] == pytest.approx(columns * size + margin, abs=1e-4)
    assert panel["area_m2"] == pytest.approx(UNROLLED * HEIGHT, rel=1e-5)


# 2. The same wall with a UV map.

def test_uniformly_scaled_uv_map_gives_the_unrolled_elements(tmp_path):
    size = 0.25
    unrolled = fenestra.load_scene(write_scene(tmp_path / "unrolled", curved_room(), element_size=size))
    # UVs in [0, 1] along the wall, the same scale up it: meters once scaled to the surface's area.
    mapped_path = write_scene(tmp_path / "uv", curved_room(uv=lambda k, z: (k * CHORD / UNROLLED, z / UNROLLED)),
                              element_size=size)
    mapped = fenestra.load_scene(mapped_path)
    assert set(mapped.element_grid[:, 0]) == {0}
    assert mapped.element_count == unrolled.element_count == 15 * 8
    # Same chart up to its direction: the same corners (the grid is centred).
    a = np.unique(np.round(unrolled.element_corners.reshape(-1, 3), 4), axis=0)
    b = np.unique(np.round(mapped.element_corners.reshape(-1, 3), 4), axis=0)
    assert a.shape == b.shape and np.abs(a - b).max() < 2e-4
    panel, = summary_panels(mapped_path, tmp_path / "uv")
    assert panel["parameterisation"] == "uv_map"
    domain = panel["parameter_domain"]
    assert domain["u1"] - domain["u0"] == pytest.approx(UNROLLED, abs=1e-3)
    assert domain["v1"] - domain["v0"] == pytest.approx(HEIGHT, abs=1e-3)


def test_uv_map_with_unequal_scales_is_scaled_to_the_surface_area(tmp_path):
    size = 0.25
    # u: meters along the wall / 6.28, v: height / 3: another unit on each axis.
    path = write_scene(tmp_path, curved_room(uv=lambda k, z: (k * CHORD / 6.28, z / 3.0)), element_size=size)
    scene = fenestra.load_scene(path)
    assert set(scene.element_grid[:, 0]) == {0} and scene.element_count > 0
    assert facet_distance(scene.element_corners).max() < 1e-4
    panel, = summary_panels(path, tmp_path)
    assert panel["parameterisation"] == "uv_map"
    domain = panel["parameter_domain"]
    width, height = domain["u1"] - domain["u0"], domain["v1"] - domain["v0"]
    assert width * height == pytest.approx(UNROLLED * HEIGHT, rel=1e-4)  # chart area = surface area
    assert width / height == pytest.approx((UNROLLED / 6.28) / (HEIGHT / 3.0), rel=1e-4)  # the map's shape
    assert scene.element_count == math.floor(width / size + 1e-4) * math.floor(height / size + 1e-4)


def test_python_save_summary_names_the_parameterisation(tmp_path):
    path = write_scene(tmp_path, curved_room(uv=lambda k, z: (k * CHORD, z), flat_material="facade_flat"),
                       domain=("facade", "facade_flat"), element_size=0.5)
    scene = fenestra.load_scene(path)
    scene.render.paths_per_sensor = 8
    _, summary = fenestra.contributions(scene).save(scene, str(tmp_path / "c"))
    panels = json.loads(open(summary).read())["panels"]
    assert sorted(p["parameterisation"] for p in panels) == ["plane", "uv_map"]
    flat = next(p for p in panels if p["parameterisation"] == "plane")
    domain = flat["parameter_domain"]
    assert domain["u1"] - domain["u0"] == pytest.approx(RADIUS, abs=1e-4)
    assert domain["v1"] - domain["v0"] == pytest.approx(HEIGHT, abs=1e-4)


# 3. Round trip: truth -> goals -> solve -> result -> evaluate.

@pytest.fixture(scope="module")
def solved(tmp_path_factory):
    """A solved curved scene: goals from evaluating WINDOW on the wall; returns (scene path,
    result, result path)."""
    tmp_path = tmp_path_factory.mktemp("solved")
    path = write_scene(tmp_path, curved_room(), element_size=0.5)
    truth = write_openings(tmp_path / "truth.json", [{"panel": 0, "parameter_rectangle": WINDOW}])
    r = run("evaluate", path, "--openings", truth, "-o", tmp_path / "truth_values.json", "--paths", 1024, "--quiet")
    assert r.returncode == 0, r.stderr
    goals = [s["value"] for s in json.loads((tmp_path / "truth_values.json").read_text())["sensors"]]
    assert all(g > 0 for g in goals)
    scene = json.loads(path.read_text())
    scene["sensors"].update(goals=goals, goal_units="lux")
    scene["solver"] = {"generations": 40, "population": 16, "seed": 2, "improve_iterations": 2000}
    path.write_text(json.dumps(scene))
    r = run("solve", path, "-o", tmp_path / "result.json", "--paths", 512, "--seed", 5, "--quiet")
    assert r.returncode == 0, r.stderr
    return path, json.loads((tmp_path / "result.json").read_text()), tmp_path / "result.json"


def test_solve_describes_curved_openings_by_their_surface(solved, tmp_path):
    path, result, _ = solved
    assert result["openings"], result
    panel, = summary_panels(path, tmp_path / "layout")
    domain = panel["parameter_domain"]
    sensors = np.array(SENSORS)
    for o in result["openings"]:
        assert o["curved"] is True and o["panel"] == 0 and o["depth"] == 0
        rect = o["parameter_rectangle"]
        assert domain["u0"] - 1e-3 <= rect["u0"] < rect["u1"] <= domain["u1"] + 1e-3
        assert domain["v0"] - 1e-3 <= rect["v0"] < rect["v1"] <= domain["v1"] + 1e-3
        assert o["width"] == pytest.approx(rect["u1"] - rect["u0"], abs=1e-6)
        assert o["height"] == pytest.approx(rect["v1"] - rect["v0"], abs=1e-6)
        grid = o["surface_grid"]
        rows, columns = grid["rows"], grid["columns"]
        points = np.array(grid["points"], float)
        normals = np.array(grid["normals"], float)
        assert rows >= 2 and columns >= 2 and points.shape == normals.shape == (rows * columns, 3)
        # On the wall, its corners the opening's.
        assert facet_distance(points).max() < 1e-4
        assert facet_distance(o["corners"]).max() < 1e-4
        quad = points.reshape(rows, columns, 3)
        assert np.allclose([quad[0, 0], quad[0, -1], quad[-1, -1], quad[-1, 0]], o["corners"], atol=1e-4)
        # Evenly spaced along the surface: a step of width / (columns - 1) (a chord across a facet
        # edge a hair shorter), height / (rows - 1) up it.
        du = np.linalg.norm(np.diff(quad, axis=1), axis=2)
        assert np.all(du <= o["width"] / (columns - 1) + 1e-4) and np.all(du > 0.995 * o["width"] / (columns - 1))
        dv = np.linalg.norm(np.diff(quad, axis=0), axis=2)
        assert np.allclose(dv, o["height"] / (rows - 1), atol=1e-4)
        # Unit normals of the facets (horizontal, radial to within half a facet's angle), away from
        # every sensor.
        assert np.allclose(np.linalg.norm(normals, axis=1), 1.0, atol=1e-4)
        radial = points * np.array([1.0, 1.0, 0.0])
        radial /= np.linalg.norm(radial, axis=1)[:, None]
        assert np.all(np.einsum("ij,ij->i", normals, radial) > math.cos(ARC / FACETS / 2) - 1e-4)
        away = np.einsum("pk,psk->ps", normals, points[:, None, :] - sensors[None, :, :])
        assert np.all(away > 0)
        assert np.dot(o["normal"], np.array(o["centre"]) - sensors.mean(axis=0)) > 0


def test_solve_result_is_an_openings_file_for_curved_openings(solved, tmp_path):
    path, result, result_path = solved
    sensors = result["sensors"]
    assert all("verified" in s for s in sensors), "verification is on by default"
    verified = np.array([s["verified"] for s in sensors])
    verified_err = np.array([s["verified_stderr"] for s in sensors])
    predicted = np.array([s["predicted"] for s in sensors])
    predicted_err = np.array([s["predicted_stderr"] for s in sensors])
    # With the solve's paths and seed, evaluate traces the verification's paths through the
    # same cutters, read back from the result's parameter rectangles.
    out = tmp_path / "check.json"
    r = run("evaluate", path, "--openings", result_path, "-o", out, "--paths", 512, "--seed", 5, "--quiet")
    assert r.returncode == 0, r.stderr
    values = np.array([s["value"] for s in json.loads(out.read_text())["sensors"]])
    assert np.allclose(values, verified, rtol=1e-6), (values, verified)
    # Independent paths: within a few standard errors of the verification and of the prediction.
    out = tmp_path / "check_more.json"
    r = run("evaluate", path, "--openings", result_path, "-o", out, "--paths", 2048, "--seed", 11, "--quiet")
    assert r.returncode == 0, r.stderr
    more = json.loads(out.read_text())["sensors"]
    more_values, more_err = np.array([s["value"] for s in more]), np.array([s["stderr"] for s in more])
    assert np.all(np.abs(more_values - verified) <= 4 * np.hypot(more_err, verified_err)), (more_values, verified)
    assert np.all(np.abs(more_values - predicted) <= 4 * np.hypot(more_err, predicted_err)), (more_values, predicted)
    # Python: the result dict and read_openings() of the file are accepted as they are.
    scene = fenestra.load_scene(path)
    scene.render.paths_per_sensor = 512
    scene.render.seed = 5
    py_values, _ = fenestra.evaluate(scene, result)
    assert np.allclose(py_values, verified, rtol=1e-6)
    listed = fenestra.read_openings(str(result_path))
    assert [o["parameter_rectangle"] for o in listed] == [o["parameter_rectangle"] for o in result["openings"]]
    assert np.allclose(fenestra.evaluate(scene, listed)[0], verified, rtol=1e-6)
    # The contributions' exact evaluation takes the same openings.
    c = fenestra.contributions(scene)
    exact, exact_err = c.evaluate_openings(scene, fenestra.api.openings_argument(result))
    assert np.all(np.abs(exact - verified) <= 4 * np.hypot(exact_err, verified_err)), (exact, verified)


def test_parameter_rectangle_on_a_flat_panel_is_the_rectangle_of_its_corners(tmp_path):
    path = write_scene(tmp_path, curved_room(flat_material="facade_flat"), domain=("facade", "facade_flat"),
                       element_size=0.5)
    panels = summary_panels(path, tmp_path)
    flat = next(i for i, p in enumerate(panels) if p["parameterisation"] == "plane")
    origin, u, v = (np.array(panels[flat][k]) for k in ("origin", "u_axis", "v_axis"))
    rect = {"u0": 0.5, "u1": 1.5, "v0": 0.5, "v1": 1.5}
    corners = [origin + a * u + b * v for a, b in ((0.5, 0.5), (1.5, 0.5), (1.5, 1.5), (0.5, 1.5))]
    assert np.allclose(np.array(corners)[:, 1], 0.0, atol=1e-5)  # on the wall along the x axis
    scene = fenestra.load_scene(path)
    scene.render.paths_per_sensor = 512
    values = {name: fenestra.evaluate(scene, [opening])[0]
              for name, opening in (("parameter", {"panel": flat, "parameter_rectangle": rect}),
                                    ("corners", {"corners": [list(map(float, p)) for p in corners]}))}
    assert np.allclose(values["parameter"], values["corners"], rtol=1e-4), values
    assert all(x > 0 for x in values["corners"])


NOTCH = (5, 10, 1.2)  # facets 5..10 of the wall are grey above 1.2 m


def test_notched_wall_is_diced_around_its_notch(tmp_path):
    """A chart that is not a rectangle: the wall without the top of its middle facets."""
    size = 0.25
    scene = fenestra.load_scene(write_scene(tmp_path, curved_room(notch=NOTCH), element_size=size))
    grid, corners = scene.element_grid, scene.element_corners
    assert set(grid[:, 0]) == {0}
    assert facet_distance(corners).max() < 1e-4
    # The notch spans u 1.14..2.61 m of the centred grid (symmetric on the wall), v 1.2..2 m:
    # columns 4..10 x rows 4..7 of the 15 x 8 grid overlap it.
    margin = (UNROLLED - 15 * size) / 2
    notch_u = (NOTCH[0] * CHORD - margin, (NOTCH[1] + 1) * CHORD - margin)
    dropped = {(r, c) for r in range(8) for c in range(15)
               if c * size < notch_u[1] and (c + 1) * size > notch_u[0] and (r + 1) * size > NOTCH[2]}
    assert len(dropped) == 7 * 4
    assert {(int(r), int(c)) for _, r, c in grid} == {(r, c) for r in range(8) for c in range(15)} - dropped
    # No element reaches into the notch.
    angle = np.arctan2(corners[..., 1], corners[..., 0]) / (ARC / FACETS)
    in_notch = (angle > NOTCH[0] + 1e-3) & (angle < NOTCH[1] + 1 - 1e-3) & (corners[..., 2] > NOTCH[2] + 1e-3)
    assert not in_notch.any()


def test_parameter_rectangle_across_a_notch_is_refused(tmp_path):
    scene_path = write_scene(tmp_path, curved_room(notch=NOTCH), element_size=0.25)
    margin = (UNROLLED - 15 * 0.25) / 2
    # Corners on facets 2 and 13 (0.2 and 1.8 m high) and centre (1 m high) on the faces; the
    # middle of its top edge is in the notch.
    rect = {"u0": 2.2 * CHORD - margin, "u1": 13.8 * CHORD - margin, "v0": 0.2, "v1": 1.8}
    openings_path = write_openings(tmp_path / "openings.json", [{"panel": 0, "parameter_rectangle": rect}])
    expect_cli_refusal("evaluate", scene_path, ["opening 0", "outside its panel 0"], ("--openings", openings_path))


def test_exact_evaluation_refuses_an_opening_part_in_the_margin(tmp_path):
    """Paths are recorded by element: an opening reaching into the margin the grid leaves cannot be
    evaluated from the records (evaluate() traces it), so it is refused rather than cut short."""
    scene = fenestra.load_scene(write_scene(tmp_path, curved_room(), element_size=0.5))
    scene.render.paths_per_sensor = 256
    c = fenestra.contributions(scene)

    def exact(u0):
        openings = {"openings": [{"panel": 0, "parameter_rectangle": dict(WINDOW, u0=u0, u1=1.0)}]}
        return c.evaluate_openings(scene, fenestra.api.openings_argument(openings))[0]

    # The grid starts 0.21 m from the wall's end: u -0.2..1 reaches into the margin.
    assert np.all(exact(0.0) > 0)
    with pytest.raises(ValueError, match="opening 0 reaches beyond the elements of panel 0"):
        exact(-0.2)


# 4. Bad input: refused with a message naming the problem, nothing written; an exception in Python.

def expect_cli_refusal(command, scene, fragments, extra=()):
    folder = scene.parent
    before = sorted(os.listdir(folder))
    out = folder / ("out" if command == "contributions" else "out.json")
    r = run(command, scene, "-o", out, "--paths", 16, "--quiet", *extra)
    assert r.returncode == 1, (r.returncode, r.stderr)  # a signal gives a negative status
    for fragment in fragments:
        assert fragment in r.stderr, r.stderr
    assert "json.exception" not in r.stderr and "terminate" not in r.stderr, r.stderr
    assert sorted(os.listdir(folder)) == before, "nothing may be written"
    return r.stderr


def curved_scene(tmp_path):
    return write_scene(tmp_path, curved_room(), element_size=0.5)


BAD_OPENINGS = [
    # (case, openings, fragments of the message)
    ("outside_the_panel", [{"panel": 0, "parameter_rectangle": dict(WINDOW, u1=5.0)}],
     ["opening 0", "outside its panel 0", "u 1..5"]),
    ("before_the_panel", [{"panel": 0, "parameter_rectangle": dict(WINDOW, u0=-1.0)}],
     ["opening 0", "outside its panel 0"]),
    ("above_the_panel", [{"panel": 0, "parameter_rectangle": dict(WINDOW, v1=2.5)}],
     ["opening 0", "outside its panel 0"]),
    ("second_of_two_outside", [{"panel": 0, "parameter_rectangle": WINDOW},
                               {"panel": 0, "parameter_rectangle": dict(WINDOW, v0=-0.5)}],
     ["opening 1", "outside its panel 0"]),
    ("missing_panel", [{"panel": 7, "parameter_rectangle": WINDOW}],
     ["opening 0", "panel 7", "does not exist", "1 panels"]),
    ("u0_after_u1", [{"panel": 0, "parameter_rectangle": dict(WINDOW, u0=2.5, u1=1.0)}],
     ["opening 0", "u0 < u1"]),
    ("u0_equals_u1", [{"panel": 0, "parameter_rectangle": dict(WINDOW, u1=1.0)}],
     ["opening 0", "u0 < u1"]),
    ("v0_after_v1", [{"panel": 0, "parameter_rectangle": dict(WINDOW, v0=1.5, v1=0.5)}],
     ["opening 0", "v0 < v1"]),
    ("string_value", [{"panel": 0, "parameter_rectangle": dict(WINDOW, u0="1.0")}],
     ["opening 0", "no number \"u0\""]),
    ("null_value", [{"panel": 0, "parameter_rectangle": dict(WINDOW, v1=None)}],
     ["opening 0", "no number \"v1\""]),
    ("missing_value", [{"panel": 0, "parameter_rectangle": {"u0": 1.0, "u1": 2.0, "v0": 0.5}}],
     ["opening 0", "no number \"v1\""]),
    ("huge_value", [{"panel": 0, "parameter_rectangle": dict(WINDOW, u0=-1e300)}],
     ["opening 0", "u0 is not a finite number"]),
    ("not_an_object", [{"panel": 0, "parameter_rectangle": [1.0, 2.5, 0.5, 1.5]}],
     ["opening 0", "not an object"]),
    ("without_panel", [{"parameter_rectangle": WINDOW}],
     ["opening 0", "needs \"panel\""]),
    ("negative_panel", [{"panel": -1, "parameter_rectangle": WINDOW}],
     ["opening 0", "needs \"panel\""]),
    ("panel_as_text", [{"panel": "0", "parameter_rectangle": WINDOW}],
     ["opening 0", "needs \"panel\""]),
]


# Also through the command line (each run costs the command's start-up, about half a second).
CLI_CASES = {"outside_the_panel", "second_of_two_outside", "missing_panel", "u0_after_u1", "u0_equals_u1",
             "string_value", "without_panel"}


@pytest.mark.parametrize("case, openings, fragments", BAD_OPENINGS, ids=[c[0] for c in BAD_OPENINGS])
def test_bad_parameter_rectangles_are_refused(tmp_path, case, openings, fragments):
    scene_path = curved_scene(tmp_path)
    openings_path = write_openings(tmp_path / "openings.json", openings)
    if case in CLI_CASES:
        expect_cli_refusal("evaluate", scene_path, fragments, ("--openings", openings_path))
    if not any("outside" in f or "exist" in f or "u0 < u1" in f or "v0 < v1" in f for f in fragments):
        with pytest.raises(ValueError) as error:  # a file's own errors, without a scene
            fenestra.read_openings(str(openings_path))
        for fragment in fragments:
            assert fragment in str(error.value), str(error.value)
    scene = fenestra.load_scene(scene_path)
    scene.render.paths_per_sensor = 16
    with pytest.raises(ValueError) as error:
        fenestra.evaluate(scene, {"openings": openings})
    for fragment in fragments:
        assert fragment in str(error.value), str(error.value)
    with pytest.raises(ValueError):
        fenestra.evaluate(scene, openings)  # the bare list


def test_non_finite_parameter_values_are_refused(tmp_path):
    scene_path = curved_scene(tmp_path)
    # JSON has no NaN or infinity: Python writes NaN, Infinity; 1e400 overflows.
    for text in ("NaN", "Infinity", "-Infinity", "1e400", "-1e400"):
        openings_path = tmp_path / "openings.json"
        openings_path.write_text('{"openings": [{"panel": 0, "parameter_rectangle": '
                                 '{"u0": %s, "u1": 2.5, "v0": 0.5, "v1": 1.5}}]}' % text)
        if text in ("NaN", "1e400"):
            message = expect_cli_refusal("evaluate", scene_path, ["openings.json"], ("--openings", openings_path))
            assert "u0" in message, message
        with pytest.raises(ValueError, match="openings.json.*u0"):
            fenestra.read_openings(str(openings_path))
        openings_path.unlink()
    scene = fenestra.load_scene(scene_path)
    scene.render.paths_per_sensor = 16
    for value in (float("nan"), float("inf"), -float("inf")):
        with pytest.raises(ValueError):
            fenestra.evaluate(scene, [{"panel": 0, "parameter_rectangle": dict(WINDOW, v0=value)}])


def test_python_non_finite_parameter_value_is_refused_naming_the_opening(tmp_path):
    scene = fenestra.load_scene(curved_scene(tmp_path))
    with pytest.raises(ValueError) as error:
        fenestra.evaluate(scene, [{"panel": 0, "parameter_rectangle": dict(WINDOW, u0=float("nan"))}])
    assert "opening 0" in str(error.value) and "json.exception" not in str(error.value), str(error.value)


def test_corners_on_a_curved_panel_are_refused(tmp_path):
    scene_path = write_scene(tmp_path, curved_room(flat_material="facade_flat"), domain=("facade", "facade_flat"),
                             element_size=0.5)
    scene = fenestra.load_scene(scene_path)
    scene.render.paths_per_sensor = 16
    grid, corners = scene.element_grid, scene.element_corners
    curved_panel = next(p for p in set(grid[:, 0]) if facet_distance(corners[grid[:, 0] == p]).max() < 1e-4)
    on_curved = corners[np.flatnonzero(grid[:, 0] == curved_panel)[3]]  # one element: within a facet
    on_flat = corners[np.flatnonzero(grid[:, 0] != curved_panel)[3]]
    fragments = ["opening 0", "does not lie on any flat opening-domain panel", "parameter_rectangle"]
    openings_path = write_openings(tmp_path / "openings.json", [{"corners": on_curved.tolist()}])
    expect_cli_refusal("evaluate", scene_path, fragments, ("--openings", openings_path))
    with pytest.raises(ValueError) as error:
        fenestra.evaluate(scene, [on_curved])
    assert all(f in str(error.value) for f in fragments), str(error.value)
    # The same form on the flat panel of the same scene is accepted.
    scene.render.paths_per_sensor = 256
    values, _ = fenestra.evaluate(scene, [on_flat])
    assert np.all(np.isfinite(values)) and values.sum() > 0


def refuse_scene(scene_path, fragments):
    """Refused by the command line and by load_scene()."""
    expect_cli_refusal("contributions", scene_path, fragments)
    with pytest.raises(ValueError) as error:
        fenestra.load_scene(scene_path)
    for fragment in fragments:
        assert fragment in str(error.value), str(error.value)


def ring_uv(k, z):
    """A UV map winding the wall 450 degrees around an annulus: no fold, but the last facets lie
    on the first ones."""
    angle = k * 2.5 * math.pi / FACETS
    radius = 1.0 + z / HEIGHT
    return radius * math.cos(angle), radius * math.sin(angle)


def with_some_uv(text):
    """The curved wall's first face split in two triangles, only one of them with UVs."""
    lines = []
    for line in text.split("\n"):
        words = line.split()
        if words[:1] == ["f"] and "/" in line and not any(done.startswith("f ") and "/" in done for done in lines):
            a, b, c, d = words[1:]
            lines += ["f %s %s %s" % (a, b, c), "f %s %s %s" % tuple(w.split("/")[0] for w in (a, c, d))]
        else:
            lines.append(line)
    return "\n".join(lines)


def with_vt_index(text, index):
    """The curved wall's first face refers to texture coordinate `index` at its first corner."""
    lines = text.split("\n")
    k = next(i for i, line in enumerate(lines) if line.startswith("f ") and "/" in line)
    words = lines[k].split()
    words[1] = "%s/%d" % (words[1].split("/")[0], index)
    lines[k] = " ".join(words)
    return "\n".join(lines)


BAD_SCENES = [
    # (case, OBJ text, scene overrides, fragments of the message)
    ("dome_without_uv", lambda: dome(), {"sensors": {"points": [[0.3, 0.2, 0.8]], "normals": [0, 0, 1]}},
     ["group 'dome'", "no UV map and cannot be unrolled flat"]),
    ("closed_cylinder_without_uv", lambda: closed_cylinder(),
     {"sensors": {"points": [[0.3, 0.2, 0.8]], "normals": [0, 0, 1]}},
     ["group 'drum'", "no UV map and cannot be unrolled flat"]),
    ("degenerate_uv_triangle", lambda: curved_room(uv=lambda k, z: (k * CHORD, 0.0 if k == 5 else z)), {},
     ["UV map", "is degenerate at the face at", "no area"]),
    ("uv_map_without_area", lambda: curved_room(uv=lambda k, z: (0.5, 0.5)), {},
     ["UV map", "is degenerate", "no area of UV space"]),
    ("folding_uv_map", lambda: curved_room(uv=lambda k, z: ((k if k <= 8 else 16 - k) * CHORD, z)), {},
     ["UV map", "folds over at the face at", "mirrored"]),
    ("overlapping_uv_map", lambda: curved_room(uv=ring_uv), {},
     ["UV map", "overlaps itself", "take the same place"]),
    ("uv_on_some_faces", lambda: with_some_uv(curved_room(uv=lambda k, z: (k * CHORD, z))), {},
     ["UV map on some of its faces only"]),
    ("vt_index_past_the_last", lambda: with_vt_index(curved_room(uv=lambda k, z: (k * CHORD, z)), 35), {},
     ["room.obj", "texture coordinate index 35 is past the last texture coordinate"]),
    ("vt_index_zero", lambda: with_vt_index(curved_room(uv=lambda k, z: (k * CHORD, z)), 0), {},
     ["room.obj", "texture coordinate index '0'"]),
    ("thickness_with_curved_domain", lambda: curved_room(),
     {"opening_domain": {"materials": ["facade"], "element_size": 0.5, "thickness": 0.3}},
     ["opening_domain.thickness 0.3", "is curved", "single surfaces"]),
    ("curved_solid", lambda: curved_room(behind=0.3), {},
     ["group 'wall_curved'", "modelled as a solid", "single surfaces"]),
]


@pytest.mark.parametrize("case, obj, overrides, fragments", BAD_SCENES, ids=[c[0] for c in BAD_SCENES])
def test_bad_curved_domains_are_refused(tmp_path, case, obj, overrides, fragments):
    scene_path = write_scene(tmp_path / "scene", obj(), element_size=0.5, **overrides)
    refuse_scene(scene_path, fragments)


def moved_obj(text, offset):
    """The OBJ text with every vertex moved by `offset` (meters), written with its full digits."""
    lines = []
    for line in text.split("\n"):
        words = line.split()
        if words[:1] == ["v"]:
            line = "v " + " ".join(repr(float(w) + d) for w, d in zip(words[1:4], offset))
        lines.append(line)
    return "\n".join(lines)


FACE_AT = re.compile(r"the face at \(([^,]+), ([^,]+), ([^)]+)\)")


@pytest.mark.parametrize("case", ["degenerate_uv_triangle", "folding_uv_map", "overlapping_uv_map"])
def test_a_bad_chart_names_its_face_where_the_user_put_it(tmp_path, case):
    """A curved wall at UTM coordinates is refused naming its face in the model's coordinates, not in
    the local frame it is traced in."""
    _, obj, overrides, _ = next(c for c in BAD_SCENES if c[0] == case)
    offset = (499993.0, 4999990.0, 120.0)
    faces = []
    for name, shift in (("origin", (0.0, 0.0, 0.0)), ("utm", offset)):
        sensors = {"points": [[p[i] + shift[i] for i in range(3)] for p in SENSORS], "normals": [0, 0, 1]}
        path = write_scene(tmp_path / name, moved_obj(obj(), shift), element_size=0.5,
                           **dict(overrides, sensors=sensors))
        with pytest.raises(ValueError) as error:
            fenestra.load_scene(path)
        found = FACE_AT.search(str(error.value))
        assert found, str(error.value)
        faces.append(np.array([float(x) for x in found.groups()]))
    assert np.allclose(faces[1], faces[0] + np.array(offset), atol=1e-3), faces


def test_vt_index_counting_back_past_the_first_is_refused(tmp_path):
    text = curved_room(uv=lambda k, z: (k * CHORD, z))
    # The floor's first face, before any vt line, refers back 99 texture coordinates.
    lines = text.split("\n")
    k = next(i for i, line in enumerate(lines) if line.startswith("f "))
    lines[k] = "f " + " ".join("%s/-99" % w for w in lines[k].split()[1:])
    with pytest.raises(ValueError, match="texture coordinate"):
        fenestra.load_scene(write_scene(tmp_path, "\n".join(lines), element_size=0.5))


def test_curved_domain_controls_load(tmp_path):
    """The refused scenes' neighbours load: the refusals above are about what they name."""
    # The UV map the bad ones were made from.
    scene = fenestra.load_scene(write_scene(tmp_path / "uv", curved_room(uv=lambda k, z: (k * CHORD, z)),
                                            element_size=0.5))
    assert set(scene.element_grid[:, 0]) == {0} and scene.element_count == 7 * 4
    # Thickness 0, given, is allowed on a curved wall.
    scene = fenestra.load_scene(write_scene(tmp_path / "zero", curved_room(),
                                            opening_domain={"materials": ["facade"], "element_size": 0.5,
                                                            "thickness": 0.0}))
    assert scene.element_count == 7 * 4
    # An outer wall 2.5 m away is no solid wall's face (measured thicknesses reach 2 m).
    scene = fenestra.load_scene(write_scene(tmp_path / "far", curved_room(behind=2.5), element_size=0.5))
    assert scene.element_count == 7 * 4


# 5. Seeded fuzz of the parameter rectangle.

def mutate(rng, rect):
    rect = dict(rect)
    keys = ["u0", "u1", "v0", "v1"]
    for _ in range(rng.randint(1, 3)):
        kind = rng.randrange(9)
        key = rng.choice(keys)
        if kind == 0:
            rect[key] = rng.uniform(-10.0, 10.0)
        elif kind == 1:
            rect[key] = rng.choice([-1.0, 1.0]) * 10.0 ** rng.uniform(-12, 300)
        elif kind == 2:
            rect[key] = -abs(rect[key]) - rng.uniform(0.0, 1.0)
        elif kind == 3:
            a, b = ("u0", "u1") if rng.random() < 0.5 else ("v0", "v1")
            rect[a], rect[b] = rect[b], rect[a]
        elif kind == 4:
            rect[key] = rect[key] + rng.choice([-1.0, 1.0]) * 10.0 ** rng.uniform(-9, -3)
        elif kind == 5:
            rect[key] = rng.choice([0.0, -0.0, 1e6, -1e6, 1e6 + 1, 5e-324])
        elif kind == 6:
            rect[key] = rng.choice(["1", None, True, [], {}])
        elif kind == 7:
            other = rng.choice(keys)
            rect[key] = rect[other]
        else:
            rect[key] = rng.uniform(-0.5, 4.5) if key[0] == "u" else rng.uniform(-0.5, 2.5)
    return rect


def test_fuzzed_parameter_rectangles_never_crash(tmp_path):
    scene_path = curved_scene(tmp_path)
    rng = random.Random(20240611)
    cases = []
    for i in range(30):
        rect = mutate(rng, WINDOW)
        openings = [{"panel": 0, "parameter_rectangle": rect}]
        if rng.random() < 0.3:
            openings.insert(0, {"panel": 0, "parameter_rectangle": WINDOW})
        path = write_openings(tmp_path / ("fuzz%d.json" % i), openings)
        cases.append((rect, path, tmp_path / ("fuzz%d_out.json" % i)))

    def evaluate(case):  # a hang raises subprocess.TimeoutExpired
        _, openings_path, out = case
        return run("evaluate", scene_path, "--openings", openings_path, "-o", out, "--paths", 16, "--quiet",
                   "--threads", 1, timeout=60)

    with concurrent.futures.ThreadPoolExecutor(max_workers=2) as pool:  # the command's start-up dominates
        runs = list(pool.map(evaluate, cases))
    outcomes = {"accepted": 0, "refused": 0}
    for (rect, _, out), r in zip(cases, runs):
        assert r.returncode in (0, 1), (rect, r.returncode, r.stderr)  # a signal gives a negative status
        if r.returncode == 0:
            sensors = json.loads(out.read_text())["sensors"]
            assert len(sensors) == len(SENSORS) and all(math.isfinite(s["value"]) and s["value"] >= 0 for s in sensors)
            outcomes["accepted"] += 1
        else:
            assert "error" in r.stderr and "opening" in r.stderr, (rect, r.stderr)
            assert "terminate" not in r.stderr and "json.exception" not in r.stderr, r.stderr
            assert not out.exists()
            outcomes["refused"] += 1
    assert outcomes["accepted"] > 0 and outcomes["refused"] > 0, outcomes
