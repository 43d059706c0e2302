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
user moved them, path-traced), tradeoff_operators (a simpler design from the solve's list).
A solve: solve_job (the worker), solve_progress (its bar and Cancel button), solve_guard (what
cancels it), study_folder (replaced only on success), study_fingerprint and contributions_cache
(the contributions reused when only goals or solver settings changed).
Climate-based daylight: weather_file (the climate sky's file), annual_operator and annual_job (Annual
Daylight on the cutters as they stand, a job like a solve's), annual_properties and annual_results
(its figures in scene.fenestra.annual), annual_panel (the metrics under Results). Climate goals: climate_goal_properties (the goals and a
solve's figures), climate_goals (their part of the study), climate_results (the result's figures in
the model), climate_panel (their list under Sensors, what was reached under Results); sensor_table
(a per-sensor figure by object and vertex).
"""

import bpy

from . import (annual_operator, annual_panel, check_setup, climate_panel, contributions_cache, evaluate_openings,
               false_colour_overlay,
               legend, operators, overlay, panels, properties, result_operators, result_panels, sensor_hover,
               sensor_labels, solve_guard, solve_job, solve_progress, tradeoff_operators)

classes = (properties.classes + operators.classes + result_operators.classes + sensor_hover.classes
           + evaluate_openings.classes + solve_progress.classes + panels.classes + climate_panel.classes
           + result_panels.classes
           + check_setup.classes + tradeoff_operators.classes + annual_operator.classes + annual_panel.classes)
DRAWN = (overlay, false_colour_overlay, legend, sensor_labels)


def register():
    for cls in classes:
        bpy.utils.register_class(cls)
    properties.register()
    for module in DRAWN:
        module.register()
    solve_progress.register()
    solve_guard.register()


def unregister():
    job = solve_job.cancel_running("Solve cancelled: the add-on was disabled")
    if job is not None:
        job.wait(solve_job.CANCEL_WAIT_AT_EXIT_S)
    contributions_cache.clear()
    solve_guard.unregister()
    solve_progress.unregister()
    for module in reversed(DRAWN):
        module.unregister()
    properties.unregister()
    for cls in reversed(classes):
        bpy.utils.unregister_class(cls)
