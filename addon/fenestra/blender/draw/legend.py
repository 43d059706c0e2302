"""Draws the false colour's legend in the 3D View: a colour bar at the bottom left with its values
and units (`scene.fenestra.display.show_legend`). Drawing only."""

import blf
import bpy
import numpy as np

from .viewport_drawing import ViewportDrawing
from .. import compat
from ..result import result_display

STEPS = 64                        # colour samples along the bar
BAR = (240, 14)                   # pixels at UI scale 1
MARGIN, PADDING, TEXT = 16, 8, 12
BACKGROUND = (0.0, 0.0, 0.0, 0.55)


def _left(context, scale):
    """Left edge, clear of the toolbar when it overlaps the viewport."""
    x = MARGIN * scale
    if context.preferences.system.use_region_overlap:
        for region in context.area.regions:
            if region.type == 'TOOLS' and region.width > 1:
                x += region.width
    return x


def _text_size(size):
    blf.size(0, size)


def _rectangles(shader, boxes, colours):
    """Axis-aligned boxes (x0, y0, x1, y1) in pixels, each in its own colour."""
    import gpu_extras.batch
    pos, col = [], []
    for (x0, y0, x1, y1), c in zip(boxes, colours):
        pos += [(x0, y0), (x1, y0), (x1, y1), (x0, y0), (x1, y1), (x0, y1)]
        col += [tuple(c)] * 6
    gpu_extras.batch.batch_for_shader(shader, 'TRIS', {"pos": pos, "color": col}).draw(shader)


def layout(context):
    """(box of the whole legend, box of the colour bar) in region pixels."""
    scale = context.preferences.system.ui_scale
    w, h = BAR[0] * scale, BAR[1] * scale
    x0 = _left(context, scale) + PADDING * scale
    y0 = MARGIN * scale + PADDING * scale + 1.6 * TEXT * scale  # tick labels below the bar
    bar = (x0, y0, x0 + w, y0 + h)
    whole = (x0 - PADDING * scale, MARGIN * scale, bar[2] + 2 * TEXT * scale, bar[3] + 2.0 * TEXT * scale + PADDING * scale)
    return whole, bar


def _draw():
    context = bpy.context
    settings = getattr(context.scene, "fenestra", None)
    if settings is None or not settings.display.show_legend:
        return
    shown = result_display.current(context)
    if shown is None:
        return
    scale_info, values = shown
    import gpu
    scale = context.preferences.system.ui_scale
    whole, bar = layout(context)
    shader = gpu.shader.from_builtin(compat.FLAT_COLOR_SHADER)
    gpu.state.blend_set('ALPHA')
    _rectangles(shader, [whole], [BACKGROUND])
    t = np.linspace(0.0, 1.0, STEPS + 1)
    if scale_info.quantity == 'RATIO':
        samples = 2.0 ** ((t[:-1] + 0.5 / STEPS) * 4 - 2)
    else:
        samples = (t[:-1] + 0.5 / STEPS) * scale_info.top
    x = bar[0] + t * (bar[2] - bar[0])
    _rectangles(shader, [(x[i], bar[1], x[i + 1], bar[3]) for i in range(STEPS)], scale_info.colours(samples))
    ticks = scale_info.ticks()
    _rectangles(shader, [(bar[0] + p * (bar[2] - bar[0]) - scale * 0.5, bar[1] - 4 * scale,
                          bar[0] + p * (bar[2] - bar[0]) + scale * 0.5, bar[1]) for p, _ in ticks],
                [(1, 1, 1, 1)] * len(ticks))
    gpu.state.blend_set('NONE')

    _text_size(int(TEXT * scale))
    blf.color(0, 1.0, 1.0, 1.0, 1.0)
    for p, label in ticks:
        width = blf.dimensions(0, label)[0]
        blf.position(0, bar[0] + p * (bar[2] - bar[0]) - width / 2, bar[1] - 4 * scale - TEXT * scale, 0)
        blf.draw(0, label)
    title = scale_info.title_for(np.concatenate(list(values.values())))
    blf.position(0, bar[0], bar[3] + 0.6 * TEXT * scale, 0)
    blf.draw(0, title)


_drawing = ViewportDrawing(_draw, 'POST_PIXEL')
register, unregister = _drawing.register, _drawing.unregister
