"""A generated office floor for climate-goal studies: perimeter rooms on four facades around a
ring corridor and a core, each room a closed box of thin walls with a door to the corridor.

Plan (meters, x east, y north, z up, 3 m storey): a `width` x `depth` floor whose perimeter is a
band of rooms `room_depth` deep, `rooms_long` rooms on each long side (south and north) and
`rooms_short` on each short side (west and east); inside the band a corridor `corridor` wide rings
the core. Adjacent boxes are `gap` apart (the partitions' thickness); doors (1.0 x 2.1 m) join each
room to the corridor through a short lined passage. Every room's outer walls (the facade, on one or
two sides) are the opening domain. Sensors: a grid at desk height (0.8 m) per room, `spacing`
apart and half a spacing from the walls, one sensor group per room (`south_1`, `west_2`, ...).

    from office_floor import write_office_floor
    path = write_office_floor(directory, element_size=0.26, spacing=0.75)
"""

import json
import os

HEIGHT, DESK, DOOR_WIDTH, DOOR_HEIGHT = 3.0, 0.8, 1.0, 2.1


class _Obj:
    """OBJ text of named quads."""

    def __init__(self):
        self.lines, self.vertices = [], 0

    def quad(self, name, material, corners):
        self.lines += ["o %s" % name, "usemtl %s" % material]
        self.lines += ["v %.4f %.4f %.4f" % c for c in corners]
        self.lines.append("f %d %d %d %d" % tuple(self.vertices + i for i in (1, 2, 3, 4)))
        self.vertices += 4

    def text(self):
        return "\n".join(self.lines) + "\n"


def _wall_quads(axis, at, span, inward, hole=None):
    """A vertical wall at `axis` (0: x = at, 1: y = at) over span (lo, hi) x (0, HEIGHT), wound to
    face `inward` (+1 or -1 along the axis), less `hole` ((lo, hi) along the wall, up to DOOR_HEIGHT):
    its quads as lists of corners."""
    def corner(u, z):
        return (at, u, z) if axis == 0 else (u, at, z)

    pieces = [(span[0], span[1], 0.0, HEIGHT)]
    if hole is not None:
        pieces = [(span[0], hole[0], 0.0, HEIGHT), (hole[1], span[1], 0.0, HEIGHT), (hole[0], hole[1], DOOR_HEIGHT, HEIGHT)]
    quads = []
    for u0, u1, z0, z1 in pieces:
        if u1 - u0 <= 1e-9:
            continue
        quad = [corner(u0, z0), corner(u1, z0), corner(u1, z1), corner(u0, z1)]
        # Counter-clockwise seen from the side it faces: u x z is +x on an x wall, -y on a y wall.
        if (1 if axis == 0 else -1) != inward:
            quad.reverse()
        quads.append(quad)
    return quads


def _box(obj, name, x, y, materials, holes=None, outward=False):
    """An axis-aligned box x = (x0, x1), y = (y0, y1) of height HEIGHT, faces inward (or outward).
    `materials`: per side ("south", "north", "west", "east", "floor", "ceiling") its material;
    `holes`: per side a (lo, hi) door span."""
    holes = holes or {}
    s = -1 if outward else 1
    (x0, x1), (y0, y1) = x, y
    z = {"floor": 0.0, "ceiling": HEIGHT}
    for side, axis, at, span, inward in (("south", 1, y0, x, 1), ("north", 1, y1, x, -1),
                                         ("west", 0, x0, y, 1), ("east", 0, x1, y, -1)):
        for i, quad in enumerate(_wall_quads(axis, at, span, s * inward, holes.get(side))):
            obj.quad("%s_%s%s" % (name, side, "_%d" % i if i else ""), materials[side], quad)
    for side, up in (("floor", 1), ("ceiling", -1)):
        quad = [(x0, y0, z[side]), (x1, y0, z[side]), (x1, y1, z[side]), (x0, y1, z[side])]
        if s * up < 0:
            quad.reverse()
        obj.quad("%s_%s" % (name, side), materials[side], quad)


def _passage(obj, name, axis, span, across, material):
    """The lining of a door's passage through a partition: jambs and head between the two walls at
    `across` (lo, hi) along `axis`, the door spanning `span` along the wall."""
    a0, a1 = across
    u0, u1 = span

    def p(u, a, z):
        return (a, u, z) if axis == 0 else (u, a, z)

    for u, facing in ((u0, 1), (u1, -1)):  # jambs face into the passage
        quad = [p(u, a0, 0.0), p(u, a1, 0.0), p(u, a1, DOOR_HEIGHT), p(u, a0, DOOR_HEIGHT)]
        obj.quad("%s_jamb" % name, material, quad if (facing > 0) == (axis == 0) else quad[::-1])
    head = [p(u0, a0, DOOR_HEIGHT), p(u0, a1, DOOR_HEIGHT), p(u1, a1, DOOR_HEIGHT), p(u1, a0, DOOR_HEIGHT)]
    obj.quad("%s_head" % name, material, head if axis == 1 else head[::-1])
    sill = [p(u0, a0, 0.0), p(u1, a0, 0.0), p(u1, a1, 0.0), p(u0, a1, 0.0)]
    obj.quad("%s_threshold" % name, material, sill if axis == 1 else sill[::-1])


def office_floor(width=36.0, depth=24.0, room_depth=6.0, rooms_long=4, rooms_short=2, corridor=1.8, gap=0.2):
    """The floor's OBJ text and its rooms: [(name, (x0, x1), (y0, y1))], inner faces of each box."""
    obj, rooms = _Obj(), []
    h = gap / 2.0
    inner_x, inner_y = (room_depth + h, width - room_depth - h), (room_depth + h, depth - room_depth - h)
    bay = width / rooms_long
    for row, (y0, y1, facade, inner) in enumerate(((0.0, room_depth - h, "south", "north"),
                                                  (depth - room_depth + h, depth, "north", "south"))):
        for i in range(rooms_long):
            x0 = i * bay + (h if i else 0.0)
            x1 = (i + 1) * bay - (h if i < rooms_long - 1 else 0.0)
            rooms.append(("%s_%d" % (facade, i + 1), (x0, x1), (y0, y1), {facade} |
                          ({"west"} if i == 0 else set()) | ({"east"} if i == rooms_long - 1 else set()), inner))
    side = (depth - 2.0 * room_depth) / rooms_short
    for facade, x in (("west", (0.0, room_depth - h)), ("east", (width - room_depth + h, width))):
        for i in range(rooms_short):
            y0 = room_depth + i * side + h
            y1 = room_depth + (i + 1) * side - h
            rooms.append(("%s_%d" % (facade, i + 1), x, (y0, y1), {facade}, "east" if facade == "west" else "west"))

    corridor_box = (inner_x, inner_y)
    out = []
    for name, x, y, facades, inner in rooms:
        materials = {s: ("facade" if s in facades else "partition") for s in ("south", "north", "west", "east")}
        materials.update(floor="floor", ceiling="ceiling")
        # The door: in the middle of the wall's stretch that faces the corridor.
        axis = 1 if inner in ("south", "north") else 0
        lo, hi = (x if axis == 1 else y)
        corridor_lo, corridor_hi = corridor_box[0] if axis == 1 else corridor_box[1]
        lo, hi = max(lo, corridor_lo), min(hi, corridor_hi)
        middle = 0.5 * (lo + hi)
        door = (middle - DOOR_WIDTH / 2, middle + DOOR_WIDTH / 2)
        _box(obj, name, x, y, materials, {inner: door})
        wall = {"north": y[1], "south": y[0], "east": x[1], "west": x[0]}[inner]
        corridor_wall = wall + gap if inner in ("north", "east") else wall - gap
        _passage(obj, name + "_door", axis, door,
                 tuple(sorted((wall, corridor_wall))), "partition")
        out.append((name, x, y, door, inner, corridor_wall))
    # The corridor: the inner rectangle with a door opposite each room's, around the core.
    holes = {}
    for name, x, y, door, inner, corridor_wall in out:
        facing = {"north": "south", "south": "north", "east": "west", "west": "east"}[inner]
        holes.setdefault(facing, []).append(door)
    _corridor(obj, corridor_box, holes)
    core = ((inner_x[0] + corridor, inner_x[1] - corridor), (inner_y[0] + corridor, inner_y[1] - corridor))
    _box(obj, "core", core[0], core[1], {s: "core" for s in ("south", "north", "west", "east", "floor", "ceiling")},
         outward=True)
    return obj.text(), [(name, x, y) for name, x, y, _, _, _ in out]


def _corridor(obj, box, holes):
    """The corridor's box, inward, its walls cut by every door that opens on them."""
    (x0, x1), (y0, y1) = box
    for side, axis, at, span, inward in (("south", 1, y0, (x0, x1), 1), ("north", 1, y1, (x0, x1), -1),
                                         ("west", 0, x0, (y0, y1), 1), ("east", 0, x1, (y0, y1), -1)):
        doors = sorted(holes.get(side, []))
        start = span[0]
        pieces = []
        for d in doors:
            pieces.append((start, d[0], 0.0, HEIGHT))
            pieces.append((d[0], d[1], DOOR_HEIGHT, HEIGHT))
            start = d[1]
        pieces.append((start, span[1], 0.0, HEIGHT))
        for i, (u0, u1, z0, z1) in enumerate(pieces):
            def corner(u, z):
                return (at, u, z) if axis == 0 else (u, at, z)
            quad = [corner(u0, z0), corner(u1, z0), corner(u1, z1), corner(u0, z1)]
            if (1 if axis == 0 else -1) != inward:
                quad.reverse()
            obj.quad("corridor_%s_%d" % (side, i), "partition", quad)
    for name, z, up in (("floor", 0.0, 1), ("ceiling", HEIGHT, -1)):
        quad = [(x0, y0, z), (x1, y0, z), (x1, y1, z), (x0, y1, z)]
        if up < 0:
            quad.reverse()
        obj.quad("corridor_%s" % name, name, quad)


def room_sensors(x, y, spacing):
    """A grid at desk height, `spacing` apart, half a spacing in from the walls."""
    nx, ny = max(1, int(round((x[1] - x[0]) / spacing))), max(1, int(round((y[1] - y[0]) / spacing)))
    dx, dy = (x[1] - x[0]) / nx, (y[1] - y[0]) / ny
    return [[x[0] + (i + 0.5) * dx, y[0] + (j + 0.5) * dy, DESK] for j in range(ny) for i in range(nx)]


def write_office_floor(directory, element_size=0.26, spacing=0.75, paths=1024, weather=None, goals=None,
                       solver=None, **plan):
    """Writes floor.obj and scene.json in `directory`; returns the scene's path. `goals`: the
    scene's `goals` (default per-room sDA300/50% >= 55 % and ASE1000,250 <= 10 % with least
    glazing); `weather`: a .epw path (default the Chicago O'Hare TMY3 file in examples/weather)."""
    text, rooms = office_floor(**plan)
    with open(os.path.join(directory, "floor.obj"), "w") as f:
        f.write(text)
    points, groups = [], {}
    for name, x, y in rooms:
        grid = room_sensors(x, y, spacing)
        groups[name] = list(range(len(points), len(points) + len(grid)))
        points += grid
    if weather is None:
        root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
        weather = os.path.join(root, "examples", "weather", "USA_IL_Chicago-OHare.Intl.AP.725300_TMY3.epw")
    if goals is None:
        goals = {"climate": [g for name, _, _ in rooms for g in (
            {"metric": "sda", "sensors": name, "min_area_fraction": 0.55},
            {"metric": "ase", "sensors": name, "max_area_fraction": 0.10})], "least_glazing": True}
    scene = {
        "fenestra": 1, "geometry": "floor.obj",
        "materials": {"facade": {"reflectance": 0.5}, "partition": {"reflectance": 0.5},
                      "floor": {"reflectance": 0.2}, "ceiling": {"reflectance": 0.8}, "core": {"reflectance": 0.5}},
        "opening_domain": {"materials": ["facade"], "element_size": element_size},
        "sensors": {"points": points, "groups": groups},
        "sky": {"type": "climate", "weather": os.path.abspath(weather)},
        "goals": goals,
        "render": {"paths_per_sensor": paths, "seed": 1},
    }
    if solver is not None:
        scene["solver"] = solver
    path = os.path.join(directory, "scene.json")
    with open(path, "w") as f:
        json.dump(scene, f)
    return path
