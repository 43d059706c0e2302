"""Each sensor's result found by its object and vertex, and the sensors the user has selected
(reading only: used while drawing)."""

import bmesh
import numpy as np

from ..com import goal_errors

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


def _goals_and_achieved(results):
    n = len(results.sensors)
    goal, achieved = np.zeros(n), np.zeros(n)
    results.sensors.foreach_get("goal", goal)
    results.sensors.foreach_get("achieved", achieved)
    return goal, achieved


def farthest_from_goal(results, count):
    """The `count` sensors farthest from their goals (goal_errors.scaled_errors: relative where the
    goal is meaningful; sensors without a goal last)."""
    error = goal_errors.scaled_errors(*_goals_and_achieved(results))
    return [results.sensors[int(i)] for i in np.argsort(-error, kind="stable")[:count]]


def worst_sensor_lines(results):
    """("Worst sensor 12.3 %", "goal 300 lx, got 337 lx"), in lux for a goal too low for a relative
    error to mean anything ("Worst sensor 2366 lx off"); None without sensors with goals."""
    goal, achieved = _goals_and_achieved(results)
    error = goal_errors.scaled_errors(goal, achieved)
    if not len(error) or error.max() < 0:
        return None
    i = int(np.argmax(error))
    headline, detail = goal_errors.describe(goal[i], achieved[i], goal_errors.goal_floor(goal))
    return "Worst sensor " + headline, detail
