"""Each sensor's result found by its object and vertex, and the sensors the user has selected
(reading only: used while drawing)."""

import bmesh
import numpy as np

_cache = {"key": None}


def _key(results):
    n = len(results.sensors)
    achieved = np.zeros(n)
    results.sensors.foreach_get("achieved", achieved)
    return n, float(achieved.sum()), results.study_path


def table(results):
    """{object name: (vertex indices, goals, achieved)} as arrays (goal NaN: none), rebuilt when the
    result changes."""
    if not results.valid:
        return {}
    key = _key(results)
    if _cache["key"] != key:
        n = len(results.sensors)
        goal, achieved = np.zeros(n), np.zeros(n)
        results.sensors.foreach_get("goal", goal)
        results.sensors.foreach_get("achieved", achieved)
        goal[goal < 0] = np.nan
        rows = {}
        for i, sensor in enumerate(results.sensors):
            rows.setdefault(sensor.object_name, []).append((sensor.vertex, i))
        by_object = {}
        for name, pairs in rows.items():
            vertices, index = np.array(pairs, np.int64).T
            by_object[name] = (vertices, goal[index], achieved[index])
        _cache.update(key=key, table=by_object)
    return _cache["table"]


def per_vertex(results, obj_name, vertex_count):
    """(goal, achieved) arrays over the object's vertices, NaN where a vertex has no result; None
    when the result has no sensor of this object or its vertex count changed since."""
    entry = table(results).get(obj_name)
    if entry is None or len(entry[0]) != vertex_count:
        return None
    vertices, goal, achieved = entry
    g, a = np.full(vertex_count, np.nan), np.full(vertex_count, np.nan)
    g[vertices], a[vertices] = goal, achieved
    return g, a


def selection(obj):
    """(active vertex index or None, selected vertex indices) of a mesh: from the edit mesh in Edit
    Mode (the active vertex is the last one clicked), else as last left in Edit Mode."""
    if obj.mode == 'EDIT':
        bm = bmesh.from_edit_mesh(obj.data)
        active = bm.select_history.active
        active = active.index if isinstance(active, bmesh.types.BMVert) else None
        chosen = [v.index for v in bm.verts if v.select]
        return active, np.array(chosen, np.int64)
    flags = np.zeros(len(obj.data.vertices), bool)
    obj.data.vertices.foreach_get("select", flags)
    return None, np.flatnonzero(flags)


def active_sensor(context):
    """(object, vertex index, goal or NaN, achieved) of the active object's active or only selected
    vertex when it is a sensor with a result, else None."""
    obj = context.active_object
    results = context.scene.fenestra.results
    if obj is None or obj.type != 'MESH' or not obj.fenestra.is_sensor or not results.valid:
        return None
    values = per_vertex(results, obj.name, len(obj.data.vertices))
    if values is None:
        return None
    active, chosen = selection(obj)
    if active is None and len(chosen) == 1:
        active = int(chosen[0])
    if active is None or active >= len(values[0]):
        return None
    return obj, active, values[0][active], values[1][active]


def name(sensor, vertex_only=False):
    """A result row's sensor as the user knows it: its object and vertex (the vertex alone when
    every sensor is in one object)."""
    if vertex_only or not sensor.object_name:
        return "%d" % sensor.vertex
    return "%s %d" % (sensor.object_name, sensor.vertex)


def farthest_from_goal(results, count):
    """The `count` sensors with the largest |achieved - goal| / goal (sensors without a goal last)."""
    n = len(results.sensors)
    goal, achieved = np.zeros(n), np.zeros(n)
    results.sensors.foreach_get("goal", goal)
    results.sensors.foreach_get("achieved", achieved)
    with np.errstate(divide="ignore", invalid="ignore"):
        error = np.where(goal > 0, np.abs(achieved - goal) / goal, -1.0)
    return [results.sensors[int(i)] for i in np.argsort(-error, kind="stable")[:count]]
