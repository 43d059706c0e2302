"""The Blender add-on over the fenestra API: the only part of the package that imports bpy.

properties (scene.fenestra, object.fenestra; display_settings: scene.fenestra.display), export
(scene -> study files), materials, sky, sky_preview (Preview Sky's World and exposure), results
(cutters, Booleans, achieved lux), cutter (an opening's cutter as a solid), operators,
result_operators and sensor_hover (Inspect Sensors), panels and result_panels (3D View sidebar,
"Fenestra" tab). Drawn in the viewport: overlay (the domain highlighted), false_colour_overlay
(the sensors in false colour), legend (its colour bar), sensor_labels (goal and achieved next to
the selected or pointed-at sensors). user_messages (the core's messages in the user's words),
visibility (hidden marked objects), goal_bounds (the goal fields' ranges), setup_checks and
check_setup (warnings before a solve), opening_cutters and evaluate_openings (the cutters as the
user moved them, path-traced).
"""

import bpy

from . import (check_setup, evaluate_openings, false_colour_overlay, legend, operators, overlay, panels, properties,
               result_operators, result_panels, sensor_hover, sensor_labels)

classes = (properties.classes + operators.classes + result_operators.classes + sensor_hover.classes
           + evaluate_openings.classes + panels.classes + result_panels.classes + check_setup.classes)
DRAWN = (overlay, false_colour_overlay, legend, sensor_labels)


def register():
    for cls in classes:
        bpy.utils.register_class(cls)
    properties.register()
    for module in DRAWN:
        module.register()


def unregister():
    for module in reversed(DRAWN):
        module.unregister()
    properties.unregister()
    for cls in reversed(classes):
        bpy.utils.unregister_class(cls)
