"""A running solve in the Solve panel: its progress bar and its Cancel button.

The bar is a read-only window-manager property whose getter reads the job: nothing is written to
Blender's data while a solve runs, so the progress makes no undo step and no scene update."""

import time

import bpy

from ..com import solve_job


def _percent(wm):
    job = solve_job.running()
    return 100.0 * job.fraction if job is not None else 0.0


def _keep(wm, value):
    """Dragging the bar changes nothing; with a setter Blender shows the bar's description as its
    tooltip, not "Disabled: This property is for internal use only"."""


class FENESTRA_OT_cancel_solve(bpy.types.Operator):
    """Stop the running solve: the model and the study folder stay as they were"""
    bl_idname = "fenestra.cancel_solve"
    bl_label = "Cancel"

    @classmethod
    def poll(cls, context):
        if solve_job.running() is None:
            cls.poll_message_set("No solve is running")
            return False
        return True

    def execute(self, context):
        solve_job.cancel_running("Solve cancelled")
        return {'FINISHED'}


def stage(job):
    return job.status[:1].upper() + job.status[1:]


def status_line(job):
    return "%s %d %%" % (stage(job), int(100 * job.fraction))


def draw(layout):
    """The bar and Cancel when a solve runs (returns True), nothing otherwise."""
    job = solve_job.running()
    if job is None:
        return False
    col = layout.column(align=True)
    col.prop(bpy.context.window_manager, "fenestra_solve_progress", text=stage(job), slider=True)
    col.operator(FENESTRA_OT_cancel_solve.bl_idname, icon='CANCEL')
    return True


def redraw_panels(context):
    for window in context.window_manager.windows:
        for area in window.screen.areas:
            if area.type == 'VIEW_3D':
                for region in area.regions:
                    if region.type == 'UI':
                        region.tag_redraw()


class Display:
    """Shows a running job: its stage in the status bar, its bar in the sidebars. Redraws are
    rationed: the status bar's redraws the whole window, and the sidebar's the 3D View beneath it
    (region overlap), which takes a good part of a second with software OpenGL."""

    REDRAW_S = 0.25

    def __init__(self):
        self.stage = self.line = None
        self.drawn_at = 0.0

    def update(self, context, job):
        if job.status != self.stage:
            self.stage = job.status
            context.workspace.status_text_set("Fenestra: %s (Esc to cancel)" % self.stage)
        line, now = status_line(job), time.monotonic()
        if line != self.line and now - self.drawn_at >= self.REDRAW_S:
            self.line, self.drawn_at = line, now
            redraw_panels(context)

    def clear(self, context):
        if context.workspace is not None:
            context.workspace.status_text_set(None)
        redraw_panels(context)


classes = (FENESTRA_OT_cancel_solve,)


def register():
    bpy.types.WindowManager.fenestra_solve_progress = bpy.props.FloatProperty(
        name="Solve Progress", subtype='PERCENTAGE', min=0.0, max=100.0, precision=0, get=_percent, set=_keep,
        options=set(), description="How much of the solve's current stage is done (its name is on the bar). Esc, "
        "or Cancel below, stops the solve and leaves the model and the study folder as they were")


def unregister():
    del bpy.types.WindowManager.fenestra_solve_progress
