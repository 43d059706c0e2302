"""One per-sensor figure of a result, found by object and vertex: {object name: (vertex indices,
values)} from a collection of items with `object_name`, `vertex` and the figure, cached until the
result or the figure changes (drawing reads it every redraw). Used for an Annual Daylight run's
metrics and for a climate solve's year; no physics."""

import numpy as np


class SensorTable:
    def __init__(self):
        self.key, self.table = None, {}

    def get(self, sensors, field, factor, key):
        """The table of `field` times `factor`; `key` (a tuple) tells one result from another."""
        key = (field, factor, len(sensors)) + tuple(key)
        if self.key != key:
            n = len(sensors)
            values = np.zeros(n)
            sensors.foreach_get(field, values)
            rows = {}
            for i, sensor in enumerate(sensors):
                rows.setdefault(sensor.object_name, []).append((sensor.vertex, i))
            by_object = {}
            for name, pairs in rows.items():
                vertices, index = np.array(pairs, np.int64).T
                by_object[name] = (vertices, values[index] * factor)
            self.key, self.table = key, by_object
        return self.table

    def forget(self):
        self.key, self.table = None, {}


def per_vertex(table, obj_name, vertex_count):
    """The values over the object's vertices (NaN where a vertex has none); None when the table has
    no sensor of this object or its vertex count changed since."""
    entry = table.get(obj_name)
    if entry is None or len(entry[0]) != vertex_count:
        return None
    vertices, values = entry
    shown = np.full(vertex_count, np.nan)
    shown[vertices] = values
    return shown
