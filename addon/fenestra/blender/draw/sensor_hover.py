"""Inspect Sensors: while it runs, the sensor nearest the mouse pointer in the 3D View is labelled
with its goal and achieved lux (Esc or right click ends it; every other event passes through, so
the view can still be turned and zoomed)."""

import bpy
import numpy as np

from ..result import result_display, sensor_results

REACH = 24  # pixels at UI scale 1: farther from every sensor, nothing is labelled
hovered = {}  # "object", "vertex", "region": what sensor_labels draws, empty when nothing


def nearest_sensor(context, mouse):
    """(object name, vertex, distance in pixels) of the sensor drawn nearest the region point mouse."""
    region, view = context.region, context.region_data
    matrix = np.array(view.perspective_matrix, np.float64)
    best = None
    results = context.scene.fenestra.results
    for obj in result_display.sensor_objects(context):
        if sensor_results.per_vertex(results, obj.name, len(obj.data.vertices)) is None:
            continue
        co = np.zeros(len(obj.data.vertices) * 3)
        obj.data.vertices.foreach_get("co", co)
        m = np.array(obj.matrix_world, np.float64)
        world = co.reshape(-1, 3) @ m[:3, :3].T + m[:3, 3]
        clip = np.hstack([world, np.ones((len(world), 1))]) @ matrix.T
        front = clip[:, 3] > 1e-9
        if not front.any():
            continue
        xy = clip[:, :2] / np.where(front, clip[:, 3], 1.0)[:, None]
        pixels = (xy + 1.0) * 0.5 * (region.width, region.height)
        distance = np.where(front, np.hypot(*(pixels - mouse).T), np.inf)
        i = int(np.argmin(distance))
        if best is None or distance[i] < best[2]:
            best = (obj.name, i, float(distance[i]))
    return best


class FENESTRA_OT_inspect_sensors(bpy.types.Operator):
    """Label the sensor under the mouse pointer with its goal and achieved lux (Esc or right click to stop)"""
    bl_idname = "fenestra.inspect_sensors"
    bl_label = "Inspect Sensors"

    @classmethod
    def poll(cls, context):
        return context.scene.fenestra.results.valid and context.area is not None and context.area.type == 'VIEW_3D'

    def invoke(self, context, event):
        context.window_manager.modal_handler_add(self)
        context.workspace.status_text_set("Fenestra: point at a sensor to see its goal and achieved lux "
                                          "(Esc or right click: stop)")
        return {'RUNNING_MODAL'}

    def _stop(self, context):
        hovered.clear()
        context.workspace.status_text_set(None)
        for area in context.window.screen.areas:
            if area.type == 'VIEW_3D':
                area.tag_redraw()
        return {'FINISHED'}

    def modal(self, context, event):
        if event.type in {'ESC', 'RIGHTMOUSE'} and event.value == 'PRESS':
            return self._stop(context)
        if not context.scene.fenestra.results.valid:
            return self._stop(context)
        if event.type == 'MOUSEMOVE':
            hovered.clear()
            for area in context.window.screen.areas:  # the 3D View the pointer is over
                if area.type != 'VIEW_3D':
                    continue
                region = next((r for r in area.regions if r.type == 'WINDOW'), None)
                x, y = (event.mouse_x - region.x, event.mouse_y - region.y) if region else (-1, -1)
                if not (0 <= x < (region.width if region else 0) and 0 <= y < region.height):
                    continue
                with context.temp_override(area=area, region=region):
                    found = nearest_sensor(context, (x, y))
                if found is not None and found[2] <= REACH * context.preferences.system.ui_scale:
                    hovered.update(object=found[0], vertex=found[1], region=region.as_pointer())
                area.tag_redraw()
        return {'PASS_THROUGH'}


classes = (FENESTRA_OT_inspect_sensors,)
