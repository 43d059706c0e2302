"""fenestra.sensor_grid (the placement behind Blender's Add Sensor Grid; docs/scene-format.md,
"Sensor grids"): a solid room's grid over the floor's upper face, off the walls and the domain, which
the setup checks then pass; the same grid in site coordinates; and seeded mutations of the model and
the settings, each of which gives a grid of finite points off the walls or a ValueError in words."""

import random

import numpy as np
import pytest

import fenestra

FACES = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)]  # facing out


def box(lo, hi, inward=False):
    (x0, y0, z0), (x1, y1, z1) = lo, hi
    v = [(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0), (x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)]
    tris = []
    for a, b, c, d in FACES:
        tris += [(a, c, b), (a, d, c)] if inward else [(a, b, c), (a, c, d)]
    return np.array(v, float), np.array(tris)


def merged(*parts):
    vertices, triangles, first = [], [], 0
    for v, t in parts:
        vertices.append(v)
        triangles.append(t + first)
        first += len(v)
    return np.concatenate(vertices), np.concatenate(triangles)


def solid_room():
    """A 4 x 5 x 3 m room inside one solid: 0.3 m walls, 0.2 m slabs."""
    return merged(box((-0.3, -0.3, -0.2), (4.3, 5.3, 3.2)), box((0, 0, 0), (4, 5, 3), inward=True))


def off_walls(points, x0=0.0, x1=4.0, y0=0.0, y1=5.0):
    return np.minimum.reduce([points[:, 0] - x0, x1 - points[:, 0], points[:, 1] - y0, y1 - points[:, 1]])


def test_a_solid_rooms_grid_lies_over_the_floors_upper_face():
    vertices, triangles = solid_room()
    grid = fenestra.sensor_grid(vertices, triangles, height=0.8, spacing=0.5)
    assert grid["enclosed"] and grid["inset"] == 0.25
    (room,) = grid["rooms"]
    p = room["points"]
    assert p.shape == (80, 3) and room["quads"].shape == (63, 4)
    assert np.allclose(p[:, 2], 0.8, atol=1e-5) and np.allclose(room["floor_z"], 0.0, atol=1e-5)
    assert off_walls(p).min() >= 0.25 - 1e-4


def test_the_setup_checks_pass_its_grid_and_name_the_rows_a_floors_extent_gives(tmp_path):
    """The grid in a scene whose south wall's inner face is the domain: no warning. The same room's
    floor extent at 0.8 m spacing, rows in the wall planes: on the domain and on the walls."""
    vertices, triangles = solid_room()
    room = fenestra.sensor_grid(vertices, triangles)["rooms"][0]["points"]
    south = (12 + 2 * 2, 12 + 2 * 2 + 1)  # the cavity's triangles follow the block's 12; face 2 is y = 0
    obj = ["v %.6f %.6f %.6f" % tuple(v) for v in vertices]
    obj += ["g block", "usemtl grey"] + ["f %d %d %d" % tuple(t + 1) for k, t in enumerate(triangles)
                                         if k not in south]
    obj += ["g window", "usemtl facade"] + ["f %d %d %d" % tuple(triangles[k] + 1) for k in south]
    (tmp_path / "room.obj").write_text("\n".join(obj) + "\n")

    def scene(points):
        return fenestra.scene_from_dict({
            "fenestra": 1, "geometry": "room.obj",
            "materials": {"grey": {"reflectance": 0.5}, "facade": {"reflectance": 0.5}},
            "opening_domain": {"materials": ["facade"], "element_size": 0.5},
            "sensors": {"points": points.tolist()}, "goals": {"uniform": [{"level": 0.5}]},
            "sky": {"type": "uniform", "radiance": 100}}, tmp_path)

    assert fenestra.check_setup(scene(room), "solve") == []
    edge = np.array([(x, y, 0.8) for x in np.linspace(0, 4, 6) for y in np.linspace(0, 5, 7)])
    kinds = {w["kind"]: w for w in fenestra.check_setup(scene(edge), "solve")}
    assert sorted(edge[kinds["on_domain"]["sensors"]][:, 1]) == [0.0] * 6  # the south row (y = 0)
    assert len(kinds["near_surface"]["sensors"]) == 2 * 6 + 6 - 2  # west, east, north rows, corners once


@pytest.mark.parametrize("offset", [(100.0, 0.0, 0.0), (500000.0, 4600000.0, 212.0), (683123.0, 9876543.0, -40.0)])
def test_site_coordinates_get_the_same_grid(offset):
    vertices, triangles = solid_room()
    near = fenestra.sensor_grid(vertices, triangles)["rooms"][0]["points"]
    far = fenestra.sensor_grid(vertices + offset, triangles)["rooms"][0]["points"]
    assert far.shape == near.shape
    assert np.abs(far - offset - near).max() < 1e-4


def test_bad_settings_are_refused_in_words():
    vertices, triangles = solid_room()
    for kwargs, words in [(dict(height=0.0), "height 0 m is not a length above 0 m"),
                          (dict(spacing=-1.0), "spacing -1 m"),
                          (dict(inset=float("inf")), "inset inf m"),
                          (dict(spacing=0.002), "use a spacing of at least 0.01 m"),
                          (dict(floors=np.ones(3, bool)), "floors must mark each of the 24 triangles")]:
        with pytest.raises(ValueError, match=words):
            fenestra.sensor_grid(vertices, triangles, **kwargs)


def test_seeded_mutations_give_a_grid_off_the_walls_or_a_message():
    """Vertices moved, duplicated, made huge or NaN; triangles pointing nowhere or degenerate;
    settings out of range: every call returns finite points kept off the room's walls (when the
    room is intact) or raises ValueError naming the problem."""
    rng = random.Random(20261207)
    base_vertices, base_triangles = solid_room()
    nasty = [float("nan"), float("inf"), -float("inf"), 1e300, -1e300, 1e39, 0.0, -0.0, 1e-300, 5e5, 1e7]
    for case in range(200):
        vertices, triangles = base_vertices.copy(), base_triangles.copy()
        kwargs = dict(height=0.8, spacing=0.5)
        intact = True
        for _ in range(rng.randint(1, 3)):
            kind = rng.randrange(6)
            if kind == 0:
                vertices[rng.randrange(len(vertices)), rng.randrange(3)] = rng.choice(nasty)
                intact = False
            elif kind == 1:
                triangles[rng.randrange(len(triangles)), rng.randrange(3)] = rng.choice([-1, 8, 16, 2 ** 31, 10 ** 6])
                intact = False
            elif kind == 2:  # a degenerate triangle added
                i = rng.randrange(len(vertices))
                triangles = np.vstack([triangles, [i, i, (i + 1) % len(vertices)]])
            elif kind == 3:
                kwargs[rng.choice(["height", "spacing", "inset"])] = rng.choice(nasty + [0.3, 2.0, 150.0])
                intact = False
            elif kind == 4:  # the whole model moved by whole or fractional meters
                vertices = vertices + rng.choice([(1.0, 2.0, 3.0), (0.37, -0.11, 0.0), (5e5, 4.6e6, 0.0)])
                intact = intact and False
            else:
                vertices = vertices + rng.uniform(-1e-6, 1e-6)
        try:
            grid = fenestra.sensor_grid(vertices, triangles, **kwargs)
        except ValueError as exc:
            message = str(exc)
            assert message.startswith("sensor grid: ") or message.startswith("sensor_grid: "), (case, message)
            assert len(message) < 400, (case, message)
            continue
        for room in grid["rooms"]:
            assert np.isfinite(room["points"]).all(), case
            assert room["points"].shape[0] == room["floor_z"].shape[0], case
            if intact:
                assert off_walls(room["points"]).min() >= grid["inset"] - 1e-3, (case, kwargs)
