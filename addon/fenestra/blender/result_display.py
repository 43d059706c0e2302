"""What the viewport shows of the current result: per sensor object, the chosen quantity at each
vertex, and the one colour scale for all of them (shared by the false colour and its legend)."""

import numpy as np

from . import false_colour, sensor_results


def sensor_objects(context):
    return [o for o in context.visible_objects if o.type == 'MESH' and o.fenestra.is_sensor]


def current(context):
    """(scale, {object name: values per vertex}) for the chosen false colour, or None when there
    is nothing to show."""
    scene = context.scene
    settings = getattr(scene, "fenestra", None)
    if settings is None or not settings.results.valid or settings.display.false_colour == 'NONE':
        return None
    results, display = settings.results, settings.display
    quantity = display.false_colour
    shown = {}
    for obj in sensor_objects(context):
        pair = sensor_results.per_vertex(results, obj.name, len(obj.data.vertices))
        if pair is not None:
            shown[obj.name] = false_colour.values(quantity, pair[0], pair[1], results.horizontal_illuminance)
    if not shown:
        return None
    every = np.concatenate(list(shown.values()))
    return false_colour.scale_for(quantity, every, display.colour_max), shown
