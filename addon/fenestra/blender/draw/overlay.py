"""Draws the opening domain highlighted in the 3D View, from the `fenestra_domain` face attribute.
Drawing only: no physics, no scene changes.

The faces come from the evaluated mesh: where a result's modifiers have cut the openings, the
attribute follows the cut faces, so the highlight leaves the holes (the result) uncovered; in Edit
Mode it follows the edit mesh. It is drawn slightly toward the viewer (no z-fighting with the
face under it), in its own colour (`scene.fenestra.display.domain_colour`)."""

import bpy
import numpy as np

from .viewport_drawing import ViewportDrawing
from ..com.names import DOMAIN_ATTRIBUTE
from .. import compat
from .toward_viewer import toward_viewer

_cache = {}  # object name -> world-space triangle corners (n * 3, 3) or None


def domain_triangles(obj, depsgraph):
    """World-space corners of the triangles of the evaluated mesh's domain faces, (n * 3, 3)."""
    obj_eval = obj.evaluated_get(depsgraph)
    mesh = obj_eval.to_mesh()
    try:
        if mesh is None:
            return np.zeros((0, 3))
        attribute = mesh.attributes.get(DOMAIN_ATTRIBUTE)
        if attribute is None or attribute.domain != 'FACE' or attribute.data_type != 'BOOLEAN':
            return np.zeros((0, 3))
        marked = np.zeros(len(mesh.polygons), bool)
        attribute.data.foreach_get("value", marked)
        if not marked.any():
            return np.zeros((0, 3))
        mesh.calc_loop_triangles()
        n = len(mesh.loop_triangles)
        corners, polygon = np.zeros(n * 3, np.int64), np.zeros(n, np.int64)
        mesh.loop_triangles.foreach_get("vertices", corners)
        mesh.loop_triangles.foreach_get("polygon_index", polygon)
        co = np.zeros(len(mesh.vertices) * 3)
        mesh.vertices.foreach_get("co", co)
        m = np.array(obj_eval.matrix_world, np.float64)
        co = co.reshape(-1, 3) @ m[:3, :3].T + m[:3, 3]
        return co[corners.reshape(-1, 3)[marked[polygon]].ravel()]
    finally:
        obj_eval.to_mesh_clear()


def _draw():
    context = bpy.context
    settings = getattr(context.scene, "fenestra", None)
    if settings is None or not settings.show_domain or context.region_data is None:
        return
    import gpu
    import gpu_extras.batch
    depsgraph = context.evaluated_depsgraph_get()
    shader = gpu.shader.from_builtin(compat.UNIFORM_COLOR_SHADER)
    gpu.state.blend_set('ALPHA')
    gpu.state.depth_test_set('LESS_EQUAL')
    gpu.state.depth_mask_set(False)  # translucent: faces behind it still show through
    shader.bind()
    shader.uniform_float("color", tuple(settings.display.domain_colour))
    for obj in context.visible_objects:
        if obj.type != 'MESH' or DOMAIN_ATTRIBUTE not in obj.data.attributes:
            continue
        if obj.name not in _cache:
            _cache[obj.name] = domain_triangles(obj, depsgraph)
        points = _cache[obj.name]
        if len(points):
            points = toward_viewer(points, context.region_data)
            gpu_extras.batch.batch_for_shader(shader, 'TRIS', {"pos": points.astype(np.float32)}).draw(shader)
    gpu.state.depth_mask_set(True)
    gpu.state.depth_test_set('NONE')
    gpu.state.blend_set('NONE')


def _forget(*_):
    _cache.clear()  # geometry, marks or modifiers may have changed


_drawing = ViewportDrawing(_draw, 'POST_VIEW', forget=_forget)
register, unregister = _drawing.register, _drawing.unregister
