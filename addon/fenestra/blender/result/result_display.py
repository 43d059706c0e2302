"""What the viewport shows of the current result: per sensor object, the chosen quantity at each
vertex, and the one colour scale for all of them (shared by the false colour and its legend). The
quantity is a solve's (achieved lux, achieved / goal, daylight factor; with climate goals, its
openings' DA300, annual mean or direct-sun hours) or, with *Annual Metric*, the chosen per-sensor
metric of the last Annual Daylight run."""

import numpy as np

from ..com import false_colour
from . import annual_results, climate_results, sensor_results


def sensor_objects(context):
    """The visible sensor objects whose values are shown: not one in Vertex Paint, whose goals are
    being painted (ui/goal_painting.py)."""
    return [o for o in context.visible_objects
            if o.type == 'MESH' and o.fenestra.is_sensor and o.mode != 'VERTEX_PAINT']


def _solve_values(context, settings, quantity):
    results = settings.results
    if not results.valid:
        return {}
    shown = {}
    for obj in sensor_objects(context):
        pair = sensor_results.per_vertex(results, obj.name, len(obj.data.vertices))
        if pair is not None:
            shown[obj.name] = false_colour.values(quantity, pair[0], pair[1], results.horizontal_illuminance)
    return shown


def _climate_values(context, settings, quantity):
    shown = {}
    for obj in sensor_objects(context):
        values = climate_results.per_vertex(settings.results, quantity, obj.name, len(obj.data.vertices))
        if values is not None:
            shown[obj.name] = values
    return shown


def _annual_values(context, settings, metric):
    shown = {}
    for obj in sensor_objects(context):
        values = annual_results.per_vertex(settings.annual, metric, obj.name, len(obj.data.vertices))
        if values is not None:
            shown[obj.name] = values
    return shown


def current(context):
    """(scale, {object name: values per vertex}) for the chosen false colour, or None when there
    is nothing to show."""
    settings = getattr(context.scene, "fenestra", None)
    if settings is None or settings.display.false_colour == 'NONE':
        return None
    display = settings.display
    if display.false_colour == 'ANNUAL':
        quantity = display.annual_metric
        shown = _annual_values(context, settings, quantity)
    elif display.false_colour in climate_results.QUANTITIES:
        quantity = display.false_colour
        shown = _climate_values(context, settings, quantity)
    else:
        quantity = display.false_colour
        shown = _solve_values(context, settings, quantity)
    if not shown:
        return None
    every = np.concatenate(list(shown.values()))
    return false_colour.scale_for(quantity, every, display.colour_max), shown
