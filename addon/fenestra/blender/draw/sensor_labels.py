"""Writes goal and achieved lux next to the selected sensors in the 3D View: the selected vertices
of sensor objects in Edit Mode, or of the active sensor object as last left in Edit Mode
(`scene.fenestra.display.show_sensor_labels`), and the sensor Inspect Sensors points at. Drawing
only."""

import math

import blf
import bmesh
import bpy
from bpy_extras.view3d_utils import location_3d_to_region_2d
from mathutils import Vector

from .viewport_drawing import ViewportDrawing
from . import sensor_hover
from ..result import sensor_results

MAX_LABELS = 24  # more selected vertices than this: only the active one is labelled
TEXT = 11


def label(goal, achieved):
    """One line: goal, achieved and their ratio (lux)."""
    if math.isnan(goal):
        return "no goal, got %.0f lx" % achieved
    ratio = " (%.0f %%)" % (100.0 * achieved / goal) if goal > 0 else ""
    return "goal %.0f lx, got %.0f lx%s" % (goal, achieved, ratio)


def _positions(obj, indices):
    """Local coordinates of these vertices, from the edit mesh in Edit Mode."""
    if obj.mode == 'EDIT':
        bm = bmesh.from_edit_mesh(obj.data)
        bm.verts.ensure_lookup_table()
        return [bm.verts[i].co.copy() for i in indices]
    return [obj.data.vertices[i].co.copy() for i in indices]


def _labelled(context):
    """[(object, vertex indices)] to label: the selected sensors, and the one Inspect Sensors points at."""
    chosen = _selected(context)
    if sensor_hover.hovered and sensor_hover.hovered["region"] == context.region.as_pointer():
        obj = bpy.data.objects.get(sensor_hover.hovered["object"])
        if obj is not None:
            chosen.append((obj, [sensor_hover.hovered["vertex"]]))
    return chosen


def _selected(context):
    objects = [o for o in context.objects_in_mode if o.type == 'MESH'] if context.mode == 'EDIT_MESH' else []
    if not objects and context.active_object is not None and context.active_object.type == 'MESH':
        objects = [context.active_object]
    chosen = []
    for obj in objects:
        if not obj.fenestra.is_sensor:
            continue
        active, selected = sensor_results.selection(obj)
        if obj.mode != 'EDIT' and len(selected) == len(obj.data.vertices):
            continue  # every vertex (as a new sensor grid is): no choice was made
        if len(selected) > MAX_LABELS:
            selected = [active] if active is not None else []
        chosen.append((obj, [int(i) for i in selected]))
    return chosen


def _draw():
    context = bpy.context
    settings = getattr(context.scene, "fenestra", None)
    if (settings is None or not settings.display.show_sensor_labels or not settings.results.valid
            or context.region_data is None):
        return
    scale = context.preferences.system.ui_scale
    blf.size(0, int(TEXT * scale))
    blf.color(0, 1.0, 1.0, 1.0, 1.0)
    blf.enable(0, blf.SHADOW)
    blf.shadow(0, 3, 0.0, 0.0, 0.0, 1.0)
    blf.shadow_offset(0, 1, -1)
    for obj, indices in _labelled(context):
        values = sensor_results.per_vertex(settings.results, obj.name, len(obj.data.vertices))
        if values is None or not indices:
            continue
        for i, co in zip(indices, _positions(obj, indices)):
            if i >= len(values[0]):
                continue
            where = location_3d_to_region_2d(context.region, context.region_data, obj.matrix_world @ Vector(co))
            if where is None:
                continue
            blf.position(0, where.x + 8 * scale, where.y + 4 * scale, 0)
            blf.draw(0, label(values[0][i], values[1][i]))
    blf.disable(0, blf.SHADOW)


_drawing = ViewportDrawing(_draw, 'POST_PIXEL')
register, unregister = _drawing.register, _drawing.unregister
