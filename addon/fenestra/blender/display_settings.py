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
)


def redraw_3d_views(_settings=None, _context=None):
    """Custom properties do not always redraw the viewport themselves (also an update callback)."""
    for window in getattr(bpy.context.window_manager, "windows", []):
        for area in window.screen.areas:
            if area.type == 'VIEW_3D':
                area.tag_redraw()


def _quantity_changed(display, context):
    if display.false_colour == 'DAYLIGHT_FACTOR':
        from . import sky_reference
        sky_reference.ensure_horizontal_illuminance(context.scene)
    redraw_3d_views()


class FenestraDisplaySettings(PropertyGroup):
    false_colour: EnumProperty(
        name="False Colour", items=QUANTITIES, default='ACHIEVED', update=_quantity_changed,
        description="What the colours drawn on the sensors show")
    colour_max: FloatProperty(
        name="Top of Scale", min=0.0, default=0.0, update=redraw_3d_views,
        description="The value at the top of the colour scale (lux or percent); 0: the largest value, "
                    "rounded up. Achieved / goal always spans 0.25 to 4")
    show_legend: BoolProperty(name="Legend", default=True, update=redraw_3d_views,
                              description="Draw the colour scale with its values and units in the viewport")
    show_sensor_labels: BoolProperty(
        name="Label Selected Sensors", default=True, update=redraw_3d_views,
        description="Write goal and achieved lux next to the selected vertices of a sensor object")
    domain_colour: FloatVectorProperty(
        name="Domain Colour", subtype='COLOR_GAMMA', size=4, min=0.0, max=1.0,
        default=(0.15, 0.75, 1.0, 0.35), update=redraw_3d_views,
        description="Colour and opacity of the opening domain's highlight")
