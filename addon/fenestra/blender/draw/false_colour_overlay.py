"""Draws the sensors in false colour in the 3D View: each sensor object's faces shaded between its
vertices' colours, and a dot at every vertex (a sensor object may have no faces). Drawing only."""

import bpy
import numpy as np

from .viewport_drawing import ViewportDrawing
from .. import compat
from ..result import result_display
from .toward_viewer import toward_viewer

POINT_SIZE = 7.0  # pixels at UI scale 1
_cache = {}  # object name -> (world vertex positions (n, 3), triangle corner indices (m * 3,))


def _geometry(obj, depsgraph):
    """The evaluated mesh's world vertices and triangles (what the study exported)."""
    obj_eval = obj.evaluated_get(depsgraph)
    mesh = obj_eval.to_mesh()
    try:
        co = np.zeros(len(mesh.vertices) * 3)
        mesh.vertices.foreach_get("co", co)
        m = np.array(obj_eval.matrix_world, np.float64)
        co = co.reshape(-1, 3) @ m[:3, :3].T + m[:3, 3]
        mesh.calc_loop_triangles()
        corners = np.zeros(len(mesh.loop_triangles) * 3, np.int64)
        mesh.loop_triangles.foreach_get("vertices", corners)
        return co, corners
    finally:
        obj_eval.to_mesh_clear()


def _draw():
    context = bpy.context
    if context.region_data is None:
        return
    shown = result_display.current(context)
    if shown is None:
        return
    scale, values = shown
    import gpu
    import gpu_extras.batch
    depsgraph = context.evaluated_depsgraph_get()
    shader = gpu.shader.from_builtin(compat.SMOOTH_COLOR_SHADER)
    gpu.state.depth_test_set('LESS_EQUAL')
    gpu.state.point_size_set(POINT_SIZE * context.preferences.system.ui_scale)
    for name, per_vertex in values.items():
        obj = bpy.data.objects.get(name)
        if name not in _cache:
            _cache[name] = _geometry(obj, depsgraph)
        co, corners = _cache[name]
        if len(co) != len(per_vertex):
            continue  # a modifier changed the vertex count since the solve
        colours = scale.colours(per_vertex).astype(np.float32)
        if len(corners):
            faces = toward_viewer(co[corners], context.region_data).astype(np.float32)
            gpu_extras.batch.batch_for_shader(shader, 'TRIS', {"pos": faces, "color": colours[corners]}).draw(shader)
        dots = toward_viewer(co, context.region_data, 0.004).astype(np.float32)
        gpu_extras.batch.batch_for_shader(shader, 'POINTS', {"pos": dots, "color": colours}).draw(shader)
    gpu.state.point_size_set(1.0)
    gpu.state.depth_test_set('NONE')


def _forget(*_):
    _cache.clear()


_drawing = ViewportDrawing(_draw, 'POST_VIEW', forget=_forget)
register, unregister = _drawing.register, _drawing.unregister
