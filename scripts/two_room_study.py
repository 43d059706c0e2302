"""Two rooms and three opening panels, with walls thin or solid, and a truth of three openings.

Room A (west) and room B (east) stand side by side, joined by a door in the wall between them.
The opening domain is room A's south and west walls and room B's roof (three panels). With
`wall > 0` every wall, the floor and the roof are solid slabs of that thickness (outer faces and
edges modelled, the domain's thickness measured by the loader); with `wall == 0` they are single
faces. The truth is three admissible openings (the automatic constraints), one per panel, placed
at random from `seed`: with `on_grid`, their edges lie on the element grid; otherwise every edge
lies between grid lines.

    write_two_room_study(folder, widths=(4.0, 3.5), depth=4.5, height=2.8, wall=0.3, seed=1)

writes scene.obj, scene.json and truth.json in folder and returns (scene dict, truth dict).
Lengths are meters; the sky is uniform at 1000 lux of unobstructed horizontal illuminance.
"""

import json
import os

import numpy as np

import fenestra

ELEMENT = 0.25
# The truth's sizes (width, height) in meters off the grid; on the grid, the nearest whole elements.
TRUTH_SIZES = {"south": (1.35, 1.4), "west": (1.35, 0.95), "roof": (1.05, 1.15)}
MATERIALS = {
    "wall": {"type": "diffuse", "reflectance": 0.6},
    "facade": {"type": "diffuse", "reflectance": 0.6},
    "roof": {"type": "diffuse", "reflectance": 0.8},
    "floor": {"type": "diffuse", "reflectance": 0.3},
    "ceiling": {"type": "diffuse", "reflectance": 0.8},
    "ground": {"type": "diffuse", "reflectance": 0.2},
}


class Obj:
    """OBJ text of quads, each wound so that its normal is the one given."""

    def __init__(self):
        self.lines, self.count = [], 0

    def quad(self, material, axis, value, normal_sign, ranges):
        """The rectangle at coordinate `value` of `axis`, spanning `ranges` on the two other axes,
        facing along +axis (normal_sign 1) or -axis (-1)."""
        i, j = [k for k in range(3) if k != axis]
        (a0, a1), (b0, b1) = ranges
        points = []
        for a, b in ((a0, b0), (a1, b0), (a1, b1), (a0, b1)):
            p = [0.0, 0.0, 0.0]
            p[axis], p[i], p[j] = value, a, b
            points.append(p)
        n = np.cross(np.subtract(points[1], points[0]), np.subtract(points[3], points[0]))
        if n[axis] * normal_sign < 0:
            points.reverse()
        self.lines.append("usemtl " + material)
        self.lines += ["v %.6f %.6f %.6f" % tuple(p) for p in points]
        self.lines.append("f %d %d %d %d" % tuple(self.count + k for k in (1, 2, 3, 4)))
        self.count += 4

    def face(self, material, axis, value, normal_sign, ranges, inset=None):
        """A face; with inset = (material, ranges), that sub-rectangle takes the other material and
        the rest of the face is cut into up to four strips around it."""
        if inset is None:
            self.quad(material, axis, value, normal_sign, ranges)
            return
        inner, ((c0, c1), (d0, d1)) = inset
        (a0, a1), (b0, b1) = ranges
        self.quad(inner, axis, value, normal_sign, ((c0, c1), (d0, d1)))
        for strip in (((a0, c0), (b0, b1)), ((c1, a1), (b0, b1)), ((c0, c1), (b0, d0)), ((c0, c1), (d1, b1))):
            if strip[0][1] - strip[0][0] > 1e-9 and strip[1][1] - strip[1][0] > 1e-9:
                self.quad(material, axis, value, normal_sign, strip)

    def box(self, material, lo, hi, insets=None):
        """A solid box, faces outward; insets maps (axis, side) (side 0: the low face, 1: the high
        face) to the (material, ranges) of a sub-rectangle of that face."""
        insets = insets or {}
        for axis in range(3):
            others = [k for k in range(3) if k != axis]
            ranges = tuple((lo[k], hi[k]) for k in others)
            for side, (value, sign) in enumerate(((lo[axis], -1), (hi[axis], 1))):
                self.face(material, axis, value, sign, ranges, insets.get((axis, side)))

    def text(self):
        return "# two rooms and three opening panels (scripts/two_room_study.py)\n" + "\n".join(self.lines) + "\n"


def thin_rooms(obj, wa, wb, d, h, door):
    """Single faces, facing the rooms; the wall between the rooms is seen from both sides."""
    x1, x2 = wa, wa + wb
    obj.quad("floor", 2, 0.0, 1, ((0, x2), (0, d)))
    obj.quad("ceiling", 2, h, -1, ((0, x1), (0, d)))
    obj.quad("facade", 2, h, -1, ((x1, x2), (0, d)))  # room B's roof
    obj.quad("facade", 1, 0.0, 1, ((0, x1), (0, h)))  # room A's south wall
    obj.quad("wall", 1, 0.0, 1, ((x1, x2), (0, h)))
    obj.quad("wall", 1, d, -1, ((0, x2), (0, h)))
    obj.quad("facade", 0, 0.0, 1, ((0, d), (0, h)))  # room A's west wall
    obj.quad("wall", 0, x2, -1, ((0, d), (0, h)))
    (y0, y1), top = door
    for ranges in (((0, y0), (0, h)), ((y1, d), (0, h)), ((y0, y1), (top, h))):
        obj.quad("wall", 0, x1, 1, ranges)
    obj.quad("ground", 2, -0.05, 1, ((-20, 20), (-20, 20)))


def solid_rooms(obj, wa, wb, d, h, t, door):
    """Slabs of thickness t: floor and roof over the whole plan, walls between them. The domain is
    the inner faces of room A's south and west walls and of room B's roof."""
    x1 = wa            # the wall between the rooms: x1 .. x1 + t
    x2 = wa + t + wb   # room B: x1 + t .. x2
    y_all = (-t, d + t)
    obj.box("wall", (-t, -t, -t), (x2 + t, d + t, 0.0), {(2, 1): ("floor", ((0, x2), (0, d)))})  # floor slab
    obj.box("wall", (-t, -t, h), (x1 + t, d + t, h + t),
            {(2, 0): ("ceiling", ((0, x1), (0, d)))})                          # roof over A
    obj.box("wall", (x1 + t, -t, h), (x2 + t, d + t, h + t),
            {(2, 0): ("facade", ((x1 + t, x2), (0, d)))})                      # roof over B (domain)
    obj.box("wall", (-t, y_all[0], 0), (0, y_all[1], h), {(0, 1): ("facade", ((0, d), (0, h)))})  # west A
    obj.box("wall", (0, -t, 0), (x1, 0, h), {(1, 1): ("facade", ((0, x1), (0, h)))})              # south A
    obj.box("wall", (0, d, 0), (x1, d + t, h))                                                    # north A
    obj.box("wall", (x1 + t, -t, 0), (x2, 0, h))                                                  # south B
    obj.box("wall", (x1 + t, d, 0), (x2, d + t, h))                                               # north B
    obj.box("wall", (x2, y_all[0], 0), (x2 + t, y_all[1], h))                                     # east B
    (y0, y1), top = door
    obj.box("wall", (x1, y_all[0], 0), (x1 + t, y0, h))
    obj.box("wall", (x1, y1, 0), (x1 + t, y_all[1], h))
    obj.box("wall", (x1, y0, top), (x1 + t, y1, h))
    obj.quad("ground", 2, -t - 0.01, 1, ((-20, 20), (-20, 20)))


def sensor_grid(x0, x1, d, spacing=0.5, inset=0.4, height=0.8):
    xs = np.arange(x0 + inset, x1 - inset + 1e-9, spacing)
    ys = np.arange(inset, d - inset + 1e-9, spacing)
    return [[round(float(x), 6), round(float(y), 6), height] for y in ys for x in xs]


def panel_lines(scene, panel):
    """The panel's grid lines along its two world axes that vary: [(axis, sorted line coordinates)] in
    the order (width axis, height axis) of the panel's rows and columns, and the panel's corners."""
    grid, corners = np.asarray(scene.element_grid), np.asarray(scene.element_corners)
    mine = corners[grid[:, 0] == panel]
    varying = [k for k in range(3) if np.ptp(mine[:, :, k]) > 1e-6]
    # The width axis is the one along the panel's columns (element corner 0 -> 1).
    along = int(np.argmax(np.abs(mine[0, 1] - mine[0, 0])))
    order = [along] + [k for k in varying if k != along]
    return [(k, np.unique(np.round(mine[:, :, k], 6))) for k in order]


def truth_rectangle(rng, lines, size, on_grid, bounds):
    """Lower and upper edges on each axis: `size` rounded to whole elements, at a random position
    whose edges are inside bounds (the admissible band); off the grid, each edge moves by a random
    part of an element and the size is the one asked."""
    edges = []
    for (axis, values), want, (lo, hi) in zip(lines, size, bounds):
        n = max(2, int(round(want / ELEMENT)))
        ok = [i for i in range(len(values) - n) if values[i] >= lo - 1e-9 and values[i + n] <= hi + 1e-9]
        # Off the grid: room for the shift inside the band, one element each side.
        if not on_grid:
            ok = [i for i in ok if values[i] - ELEMENT >= lo - 1e-9 and values[i + n] + ELEMENT <= hi + 1e-9]
        if not ok:
            raise ValueError("no admissible place for a %.2f m opening along axis %d" % (want, axis))
        i = int(rng.choice(ok))
        a, b = float(values[i]), float(values[i + n])
        if not on_grid:
            a += float(rng.uniform(0.3, 0.7)) * ELEMENT * float(rng.choice([-1, 1]))
            b = a + want
            # Neither edge within 3 cm of a grid line.
            for _ in range(20):
                if min(abs(values - a).min(), abs(values - b).min()) > 0.03:
                    break
                a += 0.04
                b += 0.04
        edges.append((axis, a, b))
    return edges


def corners_of(edges, fixed_axis, fixed_value):
    (ax, a0, a1), (bx, b0, b1) = edges
    quad = []
    for a, b in ((a0, b0), (a1, b0), (a1, b1), (a0, b1)):
        p = [0.0, 0.0, 0.0]
        p[fixed_axis], p[ax], p[bx] = fixed_value, a, b
        quad.append([round(v, 6) for v in p])
    return quad


def write_two_room_study(folder, widths=(4.0, 3.5), depth=4.5, height=2.8, wall=0.3, on_grid=True, seed=1,
                         paths=4096):
    wa, wb = widths
    d, h, t = depth, height, wall
    os.makedirs(folder, exist_ok=True)
    door = ((0.6, 1.5), 2.1)
    obj = Obj()
    if t > 0:
        solid_rooms(obj, wa, wb, d, h, t, door)
        b0 = wa + t
    else:
        thin_rooms(obj, wa, wb, d, h, door)
        b0 = wa
    with open(os.path.join(folder, "scene.obj"), "w") as f:
        f.write(obj.text())
    sensors = sensor_grid(0.0, wa, d) + sensor_grid(b0, b0 + wb, d)
    domain = {"materials": ["facade"], "element_size": ELEMENT}
    if t == 0:
        domain["thickness"] = 0.0
    scene = {
        "fenestra": 1,
        "geometry": "scene.obj",
        "materials": MATERIALS,
        "opening_domain": domain,
        "sensors": {"points": sensors, "normals": [0, 0, 1]},
        "sky": {"type": "uniform", "radiance": 1000.0 / np.pi},
        "render": {"paths_per_sensor": paths, "max_bounces": 8, "seed": 1, "threads": 0},
    }
    with open(os.path.join(folder, "scene.json"), "w") as f:
        json.dump(scene, f, indent=2)

    loaded = fenestra.load_scene(os.path.join(folder, "scene.json"))
    rng = np.random.default_rng(seed)
    margin, sill, head = 0.25, 0.3, 0.2  # the automatic constraints (margin rounded to whole elements)
    truth = []
    grid, corners = np.asarray(loaded.element_grid), np.asarray(loaded.element_corners)
    for panel in sorted(set(grid[:, 0].tolist())):
        c = corners[grid[:, 0] == panel].reshape(-1, 3)
        fixed = int(np.argmin(np.ptp(c, axis=0)))
        value = float(c[0, fixed])
        name = {2: "roof", 1: "south", 0: "west"}[fixed]
        lines = panel_lines(loaded, panel)
        bounds = []
        for axis, values in lines:
            lo, hi = values[0] + margin, values[-1] - margin
            if axis == 2:  # a wall's height: the sill and head limits from the floor and ceiling
                lo, hi = max(lo, 0.0 + sill), min(hi, h - head)
            bounds.append((lo, hi))
        edges = truth_rectangle(rng, lines, TRUTH_SIZES[name], on_grid, bounds)
        truth.append({"corners": corners_of(edges, fixed, value)})
    truth = {"openings": truth}
    violations = fenestra.constraint_violations(loaded, truth["openings"])
    if violations:
        raise ValueError("the truth is not admissible: %s" % violations)
    with open(os.path.join(folder, "truth.json"), "w") as f:
        json.dump(truth, f, indent=2)
    return scene, truth


if __name__ == "__main__":
    import argparse
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("folder")
    parser.add_argument("--widths", type=float, nargs=2, default=(4.0, 3.5))
    parser.add_argument("--depth", type=float, default=4.5)
    parser.add_argument("--height", type=float, default=2.8)
    parser.add_argument("--wall", type=float, default=0.3)
    parser.add_argument("--off-grid", action="store_true")
    parser.add_argument("--seed", type=int, default=1)
    a = parser.parse_args()
    _, truth = write_two_room_study(a.folder, tuple(a.widths), a.depth, a.height, a.wall, not a.off_grid, a.seed)
    print(json.dumps(truth))
