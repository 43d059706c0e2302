"""Draws the opening domain highlighted in the 3D View (object mode), from the `fenestra_domain`
face attribute. Drawing only: no physics, no scene changes."""

import bpy

from .export import DOMAIN_ATTRIBUTE

COLOR = (1.0, 0.55, 0.1, 0.35)  # translucent orange
_handle = None
_cache = {}  # object name -> (key, batch)


def _domain_triangles(obj):
    """World-space triangles of the object's domain faces (a flat list of points)."""
    mesh = obj.data
    attribute = mesh.attributes.get(DOMAIN_ATTRIBUTE)
    if attribute is None or attribute.domain != 'FACE':
        return []
    marked = [d.value for d in attribute.data]
    if not any(marked):
        return []
    mesh.calc_loop_triangles()
    matrix, vertices = obj.matrix_world, mesh.vertices
    points = []
    for tri in mesh.loop_triangles:
        if marked[tri.polygon_index]:
            points.extend(matrix @ vertices[i].co for i in tri.vertices)
    return points


def _batch(obj, shader):
    import gpu_extras.batch
    key = (len(obj.data.polygons), tuple(map(tuple, obj.matrix_world)), obj.data.attributes.get(DOMAIN_ATTRIBUTE))
    cached = _cache.get(obj.name)
    if cached is not None and cached[0] == key:
        return cached[1]
    points = _domain_triangles(obj)
    batch = gpu_extras.batch.batch_for_shader(shader, 'TRIS', {"pos": points}) if points else None
    _cache[obj.name] = (key, batch)
    return batch


def _draw():
    context = bpy.context
    if context.mode != 'OBJECT' or not context.scene.fenestra.show_domain:
        return
    import gpu
    shader = gpu.shader.from_builtin('3D_UNIFORM_COLOR')
    gpu.state.blend_set('ALPHA')
    gpu.state.depth_test_set('LESS_EQUAL')
    shader.bind()
    shader.uniform_float("color", COLOR)
    for obj in context.visible_objects:
        if obj.type == 'MESH' and DOMAIN_ATTRIBUTE in obj.data.attributes:
            batch = _batch(obj, shader)
            if batch is not None:
                batch.draw(shader)
    gpu.state.depth_test_set('NONE')
    gpu.state.blend_set('NONE')


def _forget(*_):
    _cache.clear()  # geometry or marks may have changed


def register():
    global _handle
    if bpy.app.background:  # nothing to draw without a window
        return
    _handle = bpy.types.SpaceView3D.draw_handler_add(_draw, (), 'WINDOW', 'POST_VIEW')
    bpy.app.handlers.depsgraph_update_post.append(_forget)


def unregister():
    global _handle
    if _handle is not None:
        bpy.types.SpaceView3D.draw_handler_remove(_handle, 'WINDOW')
        _handle = None
    if _forget in bpy.app.handlers.depsgraph_update_post:
        bpy.app.handlers.depsgraph_update_post.remove(_forget)
    _cache.clear()
