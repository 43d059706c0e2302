"""The Blender add-on over the fenestra API: the only part of the package that imports bpy.

Its rooms, bottom to top (each imports only its own and those below; docs/architecture.md):
- com/: plain logic, no Blender: the names given to Blender's data (names), StudyError, the solve
  and annual jobs, the study folder and fingerprints, the kept contributions, the native module as
  the add-on sees it, the core's messages in the user's words, false colour's scale, a cutter's solid;
- study/: the scene read as a study (export, climate goals, materials, sky, weather file, hidden
  objects), the checks before a solve, the openings read back from their cutters;
- result/: a result put into the scene (cutters, Booleans, achieved values, climate and annual
  figures) and what the viewport shows of it; Preview Sky's World;
- props/: scene.fenestra and object.fenestra;
- draw/: what the 3D View draws (domain, false colour, legend, sensor labels, Inspect Sensors);
- ui/: the operators, the panels, the Fenestra menu and its shortcuts, painting goals, a running
  job's modal half and progress.
compat.py (Blender versions' differences) serves every room but com/. This module registers the
classes in order (the panels' order in the sidebar is their registration order).
"""

import bpy

from .com import contributions_cache, solve_job
from .draw import false_colour_overlay, legend, overlay, sensor_hover, sensor_labels
from .props import properties
from .ui import (annual_operator, annual_panel, check_setup, climate_panel, evaluate_openings, goal_painting, menu,
                 operators, panels, result_operators, result_panels, shortcuts, solve_guard, solve_progress,
                 tradeoff_operators)

classes = (properties.classes + operators.classes + result_operators.classes + sensor_hover.classes
           + evaluate_openings.classes + solve_progress.classes + panels.classes + climate_panel.classes
           + result_panels.classes
           + check_setup.classes + tradeoff_operators.classes + annual_operator.classes + annual_panel.classes
           + menu.classes)
DRAWN = (overlay, false_colour_overlay, legend, sensor_labels)


def register():
    for cls in classes:
        bpy.utils.register_class(cls)
    properties.register()
    for module in DRAWN:
        module.register()
    solve_progress.register()
    solve_guard.register()
    menu.register()
    shortcuts.register()
    goal_painting.register()


def unregister():
    job = solve_job.cancel_running("Solve cancelled: the add-on was disabled")
    if job is not None:
        job.wait(solve_job.CANCEL_WAIT_AT_EXIT_S)
    contributions_cache.clear()
    goal_painting.unregister()
    shortcuts.unregister()
    menu.unregister()
    solve_guard.unregister()
    solve_progress.unregister()
    for module in reversed(DRAWN):
        module.unregister()
    properties.unregister()
    for cls in reversed(classes):
        bpy.utils.unregister_class(cls)
