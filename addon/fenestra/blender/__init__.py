"""The Blender add-on over the fenestra API: the only part of the package that imports bpy.

properties (scene.fenestra, object.fenestra), export (scene -> study files), materials, sky,
results (cutters, Booleans, achieved lux), cutter (an opening's cutter as a solid), operators,
panels (3D View sidebar, "Fenestra" tab), overlay (the domain drawn highlighted in the viewport).
A solve: solve_job (the worker), solve_progress (its bar and Cancel button), solve_guard (what
cancels it), study_folder (replaced only on success), study_fingerprint and contributions_cache
(the contributions reused when only goals or solver settings changed).
"""

import bpy

from . import contributions_cache, operators, overlay, panels, properties, solve_guard, solve_job, solve_progress

classes = properties.classes + operators.classes + solve_progress.classes + panels.classes


def register():
    for cls in classes:
        bpy.utils.register_class(cls)
    properties.register()
    overlay.register()
    solve_progress.register()
    solve_guard.register()


def unregister():
    job = solve_job.cancel_running("Solve cancelled: the add-on was disabled")
    if job is not None:
        job.wait(solve_job.CANCEL_WAIT_AT_EXIT_S)
    contributions_cache.clear()
    solve_guard.unregister()
    solve_progress.unregister()
    overlay.unregister()
    properties.unregister()
    for cls in reversed(classes):
        bpy.utils.unregister_class(cls)
