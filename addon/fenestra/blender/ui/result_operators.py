"""Operators on a result: the goal-versus-achieved plot."""

import bpy

from ..result import goal_plot


class FENESTRA_OT_show_goal_plot(bpy.types.Operator):
    """Plot achieved against goal lux per sensor into goals_vs_achieved.png in the study folder, and show it in an Image Editor"""
    bl_idname = "fenestra.show_goal_plot"
    bl_label = "Goals vs Achieved Plot"
    bl_options = {'REGISTER'}

    @classmethod
    def poll(cls, context):
        return context.scene.fenestra.results.valid

    def execute(self, context):
        try:
            path = goal_plot.write_for_study(context.scene.fenestra.results.study_path)
        except (goal_plot.PlotUnavailable, OSError, ValueError, KeyError) as exc:
            self.report({'ERROR'}, str(exc))
            return {'CANCELLED'}
        image = goal_plot.load(path)
        if not bpy.app.background and context.area is not None:
            goal_plot.show(context, image)
        self.report({'INFO'}, "Plot written to %s" % path)
        return {'FINISHED'}


classes = (FENESTRA_OT_show_goal_plot,)
