"""The openings as their cutters stand now: a solve's result stays editable in the model.

A flat opening's cutter is a box (cutter.py) whose room-side end lies `margin` inside the room,
parallel to the wall. The user may move it along the wall, scale it or turn it in the wall's
plane; the opening is read back as that end face projected onto the domain's plane it crosses
(scaled out of square, it is read as the rectangle around it along its first edge). A curved
opening's cutter follows its wall, which a move would leave: it is read back as the solve put it
(panel and parameter rectangle, kept on the cutter), and refused once moved or reshaped.
"""

import numpy as np

from ..com.names import OPENING_RECORD, ROOM_SIDE_ATTRIBUTE
from ..com.study_error import StudyError

PARALLEL = 0.999             # |cos| between the end face and a domain face lying in one plane
SAME = 1e-4                  # m: a curved cutter within this of where it was put has not moved


def _shape(obj):
    """The cutter's placement and mesh, as numbers to compare."""
    co = np.empty(len(obj.data.vertices) * 3, np.float64)
    obj.data.vertices.foreach_get("co", co)
    return [float(x) for row in obj.matrix_basis for x in row] + [float(len(co))] + co.reshape(-1, 3).sum(axis=0).tolist()


def remember(obj, opening):
    """Keeps on a new cutter what reading it back needs (results.apply calls this)."""
    rectangle = opening.get("parameter_rectangle") or {}
    obj[OPENING_RECORD] = {
        "curved": bool(opening.get("curved") or opening.get("surface_grid")),
        "panel": int(opening.get("panel", -1)),
        "parameter_rectangle": [float(rectangle.get(k, 0.0)) for k in ("u0", "u1", "v0", "v1")],
        "shape": _shape(obj),
    }


def _curved(obj, record):
    if np.max(np.abs(np.subtract(_shape(obj), list(record["shape"])))) > SAME:
        raise StudyError("'%s' is on a curved part of the domain and was moved or reshaped: Evaluate reads a "
                         "curved opening only where the solve put it. Undo the change, or solve again" % obj.name)
    u0, u1, v0, v1 = record["parameter_rectangle"]
    return {"panel": int(record["panel"]), "parameter_rectangle": {"u0": u0, "u1": u1, "v0": v0, "v1": v1}}


def _room_side_end(obj):
    """The world corners of the cutter's room-side end: its largest face on the room side (the
    others there are its sides' strips, `margin` wide)."""
    mesh = obj.data
    attr = mesh.attributes.get(ROOM_SIDE_ATTRIBUTE)
    if attr is None or attr.domain != 'FACE':
        raise StudyError("'%s' has lost the mark of its room side: it cannot be read as an opening. Solve again"
                         % obj.name)
    flags = np.zeros(len(mesh.polygons), bool)
    attr.data.foreach_get("value", flags)
    m = np.array(obj.matrix_world, np.float64)
    best, best_area = None, 0.0
    for polygon in mesh.polygons:
        if not flags[polygon.index] or len(polygon.vertices) != 4:
            continue
        corners = np.array([mesh.vertices[i].co for i in polygon.vertices], np.float64) @ m[:3, :3].T + m[:3, 3]
        area = np.linalg.norm(np.cross(corners[2] - corners[0], corners[3] - corners[1])) / 2
        if area > best_area:
            best, best_area = corners, area
    if best is None:
        raise StudyError("'%s' has no room-side end face: it cannot be read as an opening. Solve again" % obj.name)
    return best


def _extent(obj, centre, normal):
    co = np.empty(len(obj.data.vertices) * 3, np.float64)
    obj.data.vertices.foreach_get("co", co)
    m = np.array(obj.matrix_world, np.float64)
    world = co.reshape(-1, 3) @ m[:3, :3].T + m[:3, 3]
    return float(np.abs((world - centre) @ normal).max())


def _domain_triangles(study):
    """Every domain triangle of the study, (k, 3, 3) world corners."""
    found = [verts[tris[domain]] for _, verts, tris, domain in study.triangles if domain.any()]
    return np.concatenate(found) if found else np.zeros((0, 3, 3))


def _domain_plane(obj, triangles, end):
    """(point, unit normal) of the domain's plane the cutter crosses, parallel to its end face:
    where the end face's centre lands on a domain triangle, else the nearest such plane."""
    centre = end.mean(axis=0)
    normal = np.cross(end[2] - end[0], end[3] - end[1])
    normal /= np.linalg.norm(normal)
    reach = _extent(obj, centre, normal) + 1e-3
    n = np.cross(triangles[:, 1] - triangles[:, 0], triangles[:, 2] - triangles[:, 0])
    length = np.linalg.norm(n, axis=1)
    keep = length > 1e-12
    n[keep] /= length[keep, None]
    offset = np.einsum("ij,ij->i", triangles[:, 0] - centre, n)
    near = keep & (np.abs(n @ normal) >= PARALLEL) & (np.abs(offset) <= reach)
    if not near.any():
        raise StudyError("'%s' no longer lies flat across the opening domain: move it back onto the marked faces, "
                         "turning it only in their plane" % obj.name)
    # The centre dropped onto each plane, inside its triangle when on the same side of all three edges.
    point = centre + offset[:, None] * n
    inside = np.ones(len(triangles), bool)
    for a, b in ((0, 1), (1, 2), (2, 0)):
        edge = triangles[:, b] - triangles[:, a]
        inside &= np.einsum("ij,ij->i", np.cross(edge, point - triangles[:, a]), n) >= -1e-9
    chosen = near & inside if (near & inside).any() else near
    best = np.flatnonzero(chosen)[np.argmin(np.abs(offset[chosen]))]
    return triangles[best, 0], n[best]


def _flat(obj, triangles):
    """The rectangle of a flat cutter's room-side end, projected onto the domain."""
    end = _room_side_end(obj)
    point, normal = _domain_plane(obj, triangles, end)
    on = end - np.outer((end - point) @ normal, normal)
    u = on[1] - on[0]
    u /= np.linalg.norm(u)
    v = np.cross(normal, u)
    if np.dot(on[3] - on[0], v) < 0:
        v = -v
    a, b = (on - on[0]) @ u, (on - on[0]) @ v
    origin = on[0]
    corners = [origin + a.min() * u + b.min() * v, origin + a.max() * u + b.min() * v,
               origin + a.max() * u + b.max() * v, origin + a.min() * u + b.max() * v]
    return {"corners": [[round(float(x), 6) for x in c] for c in corners]}


def cutters(scene):
    """The scene's cutters, in the order of their names ("Fenestra Opening 001", ...)."""
    return sorted((o for o in scene.objects if o.fenestra.is_opening and o.type == 'MESH'), key=lambda o: o.name)


def read(objects, study):
    """Each cutter's opening, as fenestra.evaluate takes it: {"corners"} for a flat one, {"panel",
    "parameter_rectangle"} for a curved one. Raises StudyError, naming the cutter, for one that
    cannot be read."""
    openings, triangles = [], _domain_triangles(study)
    for obj in objects:
        record = obj.get(OPENING_RECORD)
        if record is not None and record.get("curved"):
            openings.append(_curved(obj, record))
        else:
            openings.append(_flat(obj, triangles))
    return openings
