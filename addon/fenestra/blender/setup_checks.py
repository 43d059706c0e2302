"""Checks of a study before it is solved: setups that solve, but whose answer is not the one the
user means. Each warning says how many sensors or faces it is about and what to change.

- Objects left out because they are hidden (visibility.py).
- All goals 0: the solve opens nothing and reports a perfect 0 % error.
- Sensors outdoors, or outside every room: they see the sky in most directions, so no opening
  changes their light much and their error stays large.
- An open room: sensors that see the sky through gaps that are not opening domain (a missing roof,
  an existing window); the light through them counts toward the goals.
- Sensors facing downward: a sensor measures the light arriving on the side its normal points to,
  so a sensor grid with flipped normals measures the floor's light.
- Domain faces whose room the solver cannot tell: the solver takes a flat part's inside to be the
  side of its plane where most sensors are (it ignores the faces' normals, which therefore do not
  change the answer). When the sensors that see the faces are on the other side, a thick wall is
  measured and cut on the wrong side.

Only geometry is looked at (rays against the exported triangles, mathutils.bvhtree): a few dozen
rays per sensor, on at most MAX_SENSORS sensors, so the checks take a fraction of a second.
"""

import numpy as np

from . import visibility

RAYS = 64                # directions per sensor, spread over the sphere
MAX_SENSORS = 400        # sensors looked at (evenly spaced through the study's order)
OUTDOORS = 0.5           # a sensor seeing the sky in this share of its directions is outdoors
GAP_RAYS = 2             # ... sees the sky through a gap when this many of its rays escape
DOWNWARD = -0.5          # a sensor normal's z below this faces downward
LIFT = 1e-3              # m: rays start this far off the sensor, along its normal
MAX_PARTS = 50           # flat domain parts checked for their side, the largest first
SAMPLES_PER_PART = 3     # points of a part the sensors look at


def _directions(count):
    """Unit vectors spread evenly over the sphere (a Fibonacci lattice), turned off the axes so
    that none runs exactly along a box room's edges or corners."""
    i = np.arange(count) + 0.5
    z = 1.0 - 2.0 * i / count
    phi = i * np.pi * (3.0 - np.sqrt(5.0))
    r = np.sqrt(1.0 - z * z)
    d = np.stack([r * np.cos(phi + 0.3), r * np.sin(phi + 0.3), z], axis=1)
    tilt = np.radians(7.0)
    turn = np.array([[1, 0, 0], [0, np.cos(tilt), -np.sin(tilt)], [0, np.sin(tilt), np.cos(tilt)]])
    return d @ turn.T


def _tree(study):
    """A BVH tree of every triangle the study exported (domain faces included: before a solve
    they are walls)."""
    from mathutils.bvhtree import BVHTree
    verts, tris, offset = [], [], 0
    for _, v, t, _ in study.triangles:
        verts.append(v)
        tris.append(t + offset)
        offset += len(v)
    if not verts:
        return None
    return BVHTree.FromPolygons(np.concatenate(verts).tolist(), np.concatenate(tris).tolist(), all_triangles=True)


def _sensors(study):
    points = np.asarray(study.scene["sensors"]["points"], np.float64)
    normals = np.asarray(study.scene["sensors"]["normals"], np.float64)
    return points, normals


def _sampled(count):
    """Indices of the sensors looked at."""
    if count <= MAX_SENSORS:
        return np.arange(count)
    return np.unique(np.linspace(0, count - 1, MAX_SENSORS).round().astype(int))


def _of(count, total, checked):
    """'3 of 40 sensors', or '3 of the 400 sensors checked (of 9000)'."""
    if checked < total:
        return "%d of the %d sensors checked (of %d)" % (count, checked, total)
    return "%d of %d sensors" % (count, total)


def zero_goals(study):
    """All goals 0: nothing to open for."""
    scene = study.scene
    n = len(scene["sensors"]["points"])
    if "goals" in scene["sensors"]:
        if n and not np.any(np.asarray(scene["sensors"]["goals"], np.float64) > 0):
            return ["All %d painted goals are 0 ('fenestra_goal' black, or Scale 0): the solve opens nothing "
                    "and reports 0 %% error. Paint the goals, or raise Scale" % n]
        return []
    uniform = scene.get("goals", {}).get("uniform", [])
    if uniform and all(u["level"] <= 0 and u.get("min", 0) <= 0 for u in uniform):
        return ["All %d sensor goals are 0: the solve opens nothing and reports 0 %% error. Set a Goal above 0"
                % n]
    return []


def _escapes(tree, points, normals):
    """(share of all directions, share of the sensor's own hemisphere) reaching the sky without
    meeting geometry, and the escaping directions' mean, per sensor."""
    directions = _directions(RAYS)
    escaped = np.zeros((len(points), RAYS), bool)
    for k, (p, n) in enumerate(zip(points, normals)):
        origin = p + LIFT * n
        for j, d in enumerate(directions):
            escaped[k, j] = tree.ray_cast(origin.tolist(), d.tolist())[0] is None
    facing = normals @ directions.T > 0
    hemisphere = (escaped & facing).sum(axis=1) / np.maximum(facing.sum(axis=1), 1)
    mean = (escaped[:, :, None] * directions[None]).sum(axis=1)
    return escaped.mean(axis=1), hemisphere, escaped.sum(axis=1), mean


def sensors_in_the_open(tree, study):
    """Sensors outdoors, and sensors seeing the sky through gaps that are not opening domain."""
    points, normals = _sensors(study)
    chosen = _sampled(len(points))
    sphere, hemisphere, count, mean = _escapes(tree, points[chosen], normals[chosen])
    outdoors = (sphere >= OUTDOORS) | (hemisphere >= OUTDOORS)
    gaps = ~outdoors & (count >= GAP_RAYS)
    warnings = []
    if outdoors.any():
        warnings.append("%s are outdoors or outside every room (they see the sky in most directions): no "
                        "opening changes their light much, so their error stays large. Move them into the "
                        "rooms, or remove them" % _of(int(outdoors.sum()), len(points), len(chosen)))
    if gaps.any():
        way = mean[gaps].sum(axis=0)
        way = way / (np.linalg.norm(way) or 1.0)
        where = ("mostly upward: a missing roof or ceiling?" if way[2] > 0.5 else
                 "mostly downward: a missing floor?" if way[2] < -0.5 else
                 "mostly sideways: a missing wall, a door or window that is not opening domain?")
        warnings.append("%s see the sky through gaps that are not opening domain (%.0f %% of their directions on "
                        "average, %s): daylight through them counts toward the goals. Close the model there if "
                        "the room is closed" % (_of(int(gaps.sum()), len(points), len(chosen)),
                                                100 * sphere[gaps].mean(), where))
    return warnings


def downward_sensors(study):
    """Sensor objects whose sensors face downward."""
    _, normals = _sensors(study)
    warnings, start = [], 0
    for name, count in study.sensor_objects:
        down = int((normals[start:start + count, 2] < DOWNWARD).sum())
        start += count
        if down:
            warnings.append("%d of %d sensors of '%s' face downward: a sensor measures the light on the side its "
                            "normal points to, here the light from below. If they should face up, flip the "
                            "normals of '%s' (Edit Mode: Mesh > Normals > Flip)" % (down, count, name, name))
    return warnings


def _flat_parts(study):
    """The domain's triangles grouped by plane: [(object name, unit normal, offset, [(centroid, area)])]."""
    parts = {}
    for name, verts, tris, domain in study.triangles:
        if not domain.any():
            continue
        corners = verts[tris[domain]]
        cross = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
        area = np.linalg.norm(cross, axis=1) / 2
        keep = area > 1e-9
        normal = cross[keep] / (2 * area[keep, None])
        # One orientation per plane: the largest component positive.
        flip = np.take_along_axis(normal, np.abs(normal).argmax(axis=1)[:, None], axis=1)[:, 0] < 0
        normal[flip] *= -1
        centroid = corners[keep].mean(axis=1)
        offset = np.einsum("ij,ij->i", normal, centroid)
        for n, d, c, a in zip(normal, offset, centroid, area[keep]):
            key = (name,) + tuple(np.round(n, 2)) + (round(float(d), 2),)
            parts.setdefault(key, (name, n, d, []))[3].append((c, a))
    return list(parts.values())


def domain_sides(tree, study):
    """Flat parts of the domain seen by sensors on the side of their plane that the solver does
    not take for the room (the side of most sensors)."""
    points, _ = _sensors(study)
    chosen = points[_sampled(len(points))]
    parts = sorted(_flat_parts(study), key=lambda p: -sum(a for _, a in p[3]))[:MAX_PARTS]
    wrong = {}
    for name, normal, offset, triangles in parts:
        side = points @ normal - offset
        inside = 1.0 if np.sign(side).sum() > 0 else -1.0   # the solver's vote: every sensor counts
        seen = {1.0: 0, -1.0: 0}
        samples = [c for c, _ in sorted(triangles, key=lambda t: -t[1])[:SAMPLES_PER_PART]]
        for p, s in zip(chosen, np.sign(chosen @ normal - offset)):
            if s == 0:
                continue
            for target in samples:
                d = target - p
                length = float(np.linalg.norm(d))
                if length > 1e-6 and tree.ray_cast(p.tolist(), (d / length).tolist(), length - 1e-4)[0] is None:
                    seen[s] += 1
                    break
        if seen[-inside] > seen[inside]:
            total = wrong.setdefault(name, [0, 0, int((np.sign(side) == inside).sum()), len(points)])
            total[0] += 1
            total[1] = max(total[1], seen[-inside])
    return ["The domain faces of '%s' (%d flat part%s) are seen by %d sensors from one side, but %d of %d sensors "
            "lie on the other side of their plane, which the solver takes for the room: a thick wall would be "
            "measured and cut toward those sensors. Solve the rooms on either side as separate studies, or leave "
            "Wall Thickness at 0 with single-face walls" % (name, parts_, plural, seen_, majority, total)
            for name, (parts_, seen_, majority, total) in wrong.items()
            for plural in ["s" if parts_ > 1 else ""]]


def hidden_objects(context):
    """Marked objects left out of the study because they are hidden (the others are in it)."""
    def left_out(count, what, name, reason):
        one = count == 1
        return ("The %d %s%s of '%s' %s on a hidden object (%s) and %s left out of the study"
                % (count, what, "" if one else "s", name, "is" if one else "are", reason, "is" if one else "are"))
    return ([left_out(faces, "domain face", obj.name, reason) for obj, faces, reason in visibility.hidden_domain(context)]
            + [left_out(n, "sensor", obj.name, reason) for obj, n, reason in visibility.hidden_sensors(context)])


def run(context, study):
    """Every check's warnings for an exported study (export.build)."""
    warnings = hidden_objects(context) + zero_goals(study) + downward_sensors(study)
    tree = _tree(study)
    if tree is not None:
        warnings += sensors_in_the_open(tree, study) + domain_sides(tree, study)
    return warnings
