"""What the 3D View shows of a result: `scene.fenestra.display` (false colour on the sensors, its
legend, labels of the selected sensors, the domain highlight's colour)."""

import bpy
from bpy.props import BoolProperty, EnumProperty, FloatProperty, FloatVectorProperty
from bpy.types import PropertyGroup

QUANTITIES = (
    ('NONE', "None", "No false colour on the sensors"),
    ('ACHIEVED', "Achieved Illuminance", "Lux at each sensor with the openings of the result"),
    ('RATIO', "Achieved / Goal", "Achieved over goal: blue below the goal, white on it, red above "
                                 "(grey: no goal)"),
    ('DAYLIGHT_FACTOR', "Daylight Factor", "Achieved illuminance as a percentage of the solved sky's "
                                           "unobstructed horizontal illuminance"),
    ('ANNUAL', "Annual Metric", "The chosen metric of the last Annual Daylight run (climate sky)"),
    # A solve with climate goals: the year of its openings at each sensor (climate_results.py).
    ('CLIMATE_DA', "Daylight Autonomy", "Solve with climate goals: the share of the occupied hours with at least "
                                        "300 lx (DA300) with the solved openings, percent"),
    ('CLIMATE_MEAN', "Annual Mean (Solve)", "Solve with climate goals: the mean illuminance over the occupied "
                                            "hours with the solved openings, lux"),
    ('CLIMATE_ASE_HOURS', "Direct Sun Hours (Solve)", "Solve with climate goals: occupied hours with more than "
                                                      "1000 lx of direct sun with the solved openings, hours"),
)
# The quantities with a Top of Scale (the others have a fixed scale).
SCALED = frozenset({'ACHIEVED', 'DAYLIGHT_FACTOR', 'CLIMATE_MEAN', 'CLIMATE_ASE_HOURS'})
# Per-sensor metrics of an Annual Daylight run (docs/climate-metrics.md), for the false colour.
ANNUAL_METRICS = (
    ('DA', "Daylight Autonomy", "Share of the occupied hours with at least 300 lx (DA300), percent"),
    ('CDA', "Continuous Daylight Autonomy", "As DA, an hour below 300 lx counting for its share of 300 lx "
                                            "(cDA300), percent"),
    ('UDI_A', "UDI Autonomous", "Share of the occupied hours from 300 to 3000 lx: enough daylight, not too "
                                "much (UDI-a), percent"),
    ('MEAN', "Annual Mean Illuminance", "Mean illuminance over the occupied hours, lux"),
    ('ASE_HOURS', "Direct Sun Hours", "Occupied hours with more than 1000 lx of direct sun (ASE counts the "
                                      "sensors above 250 h), hours"),
)


def redraw_3d_views(_settings=None, _context=None):
    """Custom properties do not always redraw the viewport themselves (also an update callback)."""
    for window in getattr(bpy.context.window_manager, "windows", []):
        for area in window.screen.areas:
            if area.type == 'VIEW_3D':
                area.tag_redraw()


def _annual_metric_changed(display, context):
    """Choosing a metric shows it."""
    if display.false_colour != 'ANNUAL':
        display.false_colour = 'ANNUAL'  # its own update redraws
    else:
        redraw_3d_views()


def _quantity_changed(display, context):
    if display.false_colour == 'DAYLIGHT_FACTOR':
        from ..result import sky_reference
        sky_reference.ensure_horizontal_illuminance(context.scene)
    redraw_3d_views()


class FenestraDisplaySettings(PropertyGroup):
    false_colour: EnumProperty(
        name="False Colour", items=QUANTITIES, default='ACHIEVED', update=_quantity_changed,
        description="What the colours drawn on the sensors show")
    annual_metric: EnumProperty(
        name="Annual Metric", items=ANNUAL_METRICS, default='DA', update=_annual_metric_changed,
        description="Which per-sensor metric of the last Annual Daylight run the false colour shows")
    colour_max: FloatProperty(
        name="Top of Scale", min=0.0, default=0.0, update=redraw_3d_views,
        description="The value at the top of the colour scale (lux, percent or hours); 0: the largest "
                    "value, rounded up. Achieved / goal always spans 0.25 to 4, the annual shares of "
                    "hours 0 to 100 %")
    show_legend: BoolProperty(name="Legend", default=True, update=redraw_3d_views,
                              description="Draw the colour scale with its values and units in the viewport")
    show_sensor_labels: BoolProperty(
        name="Label Selected Sensors", default=True, update=redraw_3d_views,
        description="Write goal and achieved lux next to the selected vertices of a sensor object")
    domain_colour: FloatVectorProperty(
        name="Domain Colour", subtype='COLOR_GAMMA', size=4, min=0.0, max=1.0,
        default=(0.15, 0.75, 1.0, 0.35), update=redraw_3d_views,
        description="Colour and opacity of the opening domain's highlight")
