"""The Blender add-on over the fenestra API: the only part of the package that imports bpy.

properties (scene.fenestra, object.fenestra), export (scene -> study files), materials, sky,
results (cutters, Booleans, achieved lux), cutter (an opening's cutter as a solid), operators,
panels (3D View sidebar, "Fenestra" tab), overlay (the domain drawn highlighted in the viewport),
user_messages (the core's messages in the user's words), visibility (hidden marked objects),
goal_bounds (the goal fields' ranges), setup_checks and check_setup (warnings before a solve),
opening_cutters and evaluate_openings (the cutters as the user moved them, path-traced).
"""

import bpy

from . import check_setup, evaluate_openings, operators, overlay, panels, properties

classes = (properties.classes + operators.classes + evaluate_openings.classes + panels.classes
           + check_setup.classes)


def register():
    for cls in classes:
        bpy.utils.register_class(cls)
    properties.register()
    overlay.register()


def unregister():
    overlay.unregister()
    properties.unregister()
    for cls in reversed(classes):
        bpy.utils.unregister_class(cls)
