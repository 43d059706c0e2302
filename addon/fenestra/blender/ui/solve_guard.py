"""What stops a running solve besides Esc and Cancel, so that a result is only ever applied to the
scene it was computed for: an undo or a redo, another file loaded, and any change to what the solve
exported (goals, opening domain, sensors, geometry, materials, sky or solve settings). A change is
found by exporting the study again and comparing fingerprints (study_fingerprint.py), once a burst
of updates (a paint stroke, a drag) has settled; the solve operator compares them once more before
it applies a result. (A file loaded also frees the contributions kept for a re-solve.)"""

import bpy
from bpy.app.handlers import persistent

from ..com import contributions_cache, solve_job, study_fingerprint
from ..study import export

CHECK_DELAY_S = 0.25

UNDONE = "Solve cancelled: undo changed the scene it was solving"
REDONE = "Solve cancelled: redo changed the scene it was solving"
LOADED = "Solve cancelled: another file was loaded"
CHANGED = ("Solve cancelled: the scene changed while it was solved (goals, opening domain, sensors, "
           "geometry, materials, sky or solve settings)")

_state = {"exporting": False, "scheduled": False}


def export_quietly(context):
    """export.build(context), without the updates the export itself causes (it switches the previous
    result's modifiers off and on) being taken for a change. Raises StudyError (study_error.py)."""
    _state["exporting"] = True
    try:
        study = export.build(context)
        context.evaluated_depsgraph_get()  # evaluates the modifiers switched back on, here
        return study
    finally:
        _state["exporting"] = False


def current_fingerprint(context):
    """The fingerprint of the study the scene exports now; None when it no longer exports."""
    try:
        return study_fingerprint.fingerprint(export_quietly(context))
    except (ValueError, OSError):
        return None


def _check():
    _state["scheduled"] = False
    job = solve_job.running()
    if job is not None and current_fingerprint(bpy.context) != job.fingerprint:
        job.cancel(CHANGED)
    return None  # once


@persistent
def _on_depsgraph_update(scene, depsgraph=None):
    if _state["exporting"] or _state["scheduled"] or solve_job.running() is None:
        return
    _state["scheduled"] = True
    bpy.app.timers.register(_check, first_interval=CHECK_DELAY_S)


@persistent
def _on_undo(*args):
    solve_job.cancel_running(UNDONE)


@persistent
def _on_redo(*args):
    solve_job.cancel_running(REDONE)


@persistent
def _on_load(*args):
    solve_job.cancel_running(LOADED)
    contributions_cache.clear()  # another model: their memory is better free


_HANDLERS = (
    (bpy.app.handlers.depsgraph_update_post, _on_depsgraph_update),
    (bpy.app.handlers.undo_post, _on_undo),
    (bpy.app.handlers.redo_post, _on_redo),
    (bpy.app.handlers.load_pre, _on_load),
)


def register():
    for handlers, handler in _HANDLERS:
        if handler not in handlers:
            handlers.append(handler)


def unregister():
    for handlers, handler in _HANDLERS:
        if handler in handlers:
            handlers.remove(handler)
    if bpy.app.timers.is_registered(_check):
        bpy.app.timers.unregister(_check)
    _state["scheduled"] = False
