"""The setup checks (setup_checks.py) in the Fenestra tab: the Check Setup operator, the Checks
panel under Solve, and show(), which Solve Openings calls before it solves."""

import bpy

from ..com import user_messages
from ..study import export, setup_checks
from ...wording import counted
from . import long_message


def show(operator, context, warnings):
    """Reports each warning and keeps them for the Checks panel."""
    for warning in warnings:
        operator.report({'WARNING'}, warning)
    settings = context.scene.fenestra
    settings.setup_warnings = "\n".join(warnings)
    settings.setup_checked = True


class FENESTRA_OT_check_setup(bpy.types.Operator):
    """Look for setups that solve but do not mean what they seem: hidden objects, goals all 0, sensors outdoors, facing down or lying on a wall or the domain, rooms open to the sky, domain faces the solver cannot tell the room of"""
    bl_idname = "fenestra.check_setup"
    bl_label = "Check Setup"

    @classmethod
    def poll(cls, context):
        return context.mode == 'OBJECT'

    def execute(self, context):
        try:
            study = export.build(context)
            warnings = setup_checks.run(context, study)
        except ValueError as exc:
            long_message.report_error(self, user_messages.for_user(exc))
            return {'CANCELLED'}
        show(self, context, warnings)
        if not warnings:
            count = sum(n for _, n in study.sensor_objects)
            self.report({'INFO'}, "No problem found (%s, %s)" % (counted(count, "sensor"),
                                                                  counted(study.domain_faces, "domain face")))
        return {'FINISHED'}


class FENESTRA_PT_checks(bpy.types.Panel):
    bl_space_type = 'VIEW_3D'
    bl_region_type = 'UI'
    bl_category = "Fenestra"
    bl_label = "Checks"
    bl_parent_id = "FENESTRA_PT_solve"

    def draw_header(self, context):
        count = len(list(filter(None, context.scene.fenestra.setup_warnings.split("\n"))))
        if count:
            self.layout.label(text="%d" % count, icon='ERROR')

    def draw(self, context):
        from .panels import draw_warning
        settings = context.scene.fenestra
        warnings = list(filter(None, settings.setup_warnings.split("\n")))
        for warning in warnings:
            draw_warning(self.layout, warning)
        if not warnings:
            self.layout.label(text="No problem found at the last check" if settings.setup_checked else "Not checked yet",
                              icon='CHECKMARK' if settings.setup_checked else 'INFO')
        self.layout.operator("fenestra.check_setup", icon='VIEWZOOM')


classes = (FENESTRA_OT_check_setup, FENESTRA_PT_checks)
