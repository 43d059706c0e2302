"""Add Sensor Grid's Blender side: the scene's faces in world coordinates, the chosen objects' marked
as floors, handed to the core's fenestra.sensor_grid (which finds the rooms and places the sensors:
docs/blender.md, "Sensors"); one sensor object per room comes back."""

import bpy
import numpy as np

from ..com import names
from . import export


def model_faces(context, chosen):
    """(vertices (n, 3) m, triangles (m, 3), floors (m,) bool) of every visible object that bounds a
    room (not sensors, not cutters), with the faces of the `chosen` objects marked as floors."""
    depsgraph = context.evaluated_depsgraph_get()
    chosen = {o.name for o in chosen}
    vertices, triangles, floors, first = [], [], [], 0
    for obj in context.scene.objects:
        if (obj.type not in export.GEOMETRY_TYPES or not obj.visible_get() or obj.fenestra.is_opening
                or obj.fenestra.is_sensor):
            continue
        obj_eval, mesh = export.evaluated(obj, depsgraph)
        try:
            if mesh is None or len(mesh.loop_triangles) == 0:
                continue
            tris = np.empty(len(mesh.loop_triangles) * 3, np.int64)
            mesh.loop_triangles.foreach_get("vertices", tris)
            vertices.append(export.world_vertices(mesh, obj_eval.matrix_world))
            triangles.append(tris.reshape(-1, 3) + first)
            floors.append(np.full(len(tris) // 3, obj.name in chosen))
            first += len(mesh.vertices)
        finally:
            obj_eval.to_mesh_clear()
    if not vertices:
        return np.zeros((0, 3)), np.zeros((0, 3), np.int64), np.zeros(0, bool)
    return np.concatenate(vertices), np.concatenate(triangles), np.concatenate(floors)


def room_names(count):
    """The sensor objects' names: 'Fenestra Sensors' for one room, numbered for more."""
    if count == 1:
        return [names.SENSORS_NAME]
    return ["%s %d" % (names.SENSORS_NAME, k + 1) for k in range(count)]


def add_rooms(context, rooms, goal_level):
    """One sensor object per room of fenestra.sensor_grid's answer, its goal attribute at
    `goal_level` (0-1 grey); returns the objects."""
    objects = []
    for name, room in zip(room_names(len(rooms)), rooms):
        points = room["points"]
        mesh = bpy.data.meshes.new(name)
        mesh.from_pydata([tuple(p) for p in points], [], [tuple(q) for q in room["quads"]])
        goal = mesh.color_attributes.new(names.GOAL_ATTRIBUTE, 'FLOAT_COLOR', 'POINT')
        goal.data.foreach_set("color_srgb", [goal_level, goal_level, goal_level, 1.0] * len(points))
        obj = bpy.data.objects.new(name, mesh)
        obj.fenestra.is_sensor = True
        obj.hide_render = True
        context.collection.objects.link(obj)
        objects.append(obj)
    return objects
