"""Sub-panels of Results: how the result is shown (false colour, legend, labels, the plot) and the
selected sensor's goal and achieved values."""

import math

import bpy

from ..com import false_colour
from ..result import sensor_results
from ..props.display_settings import SCALED
from .panels import FenestraPanel


class ResultSubPanel(FenestraPanel):
    bl_parent_id = "FENESTRA_PT_results"

    @classmethod
    def poll(cls, context):
        return context.scene.fenestra.results.valid


class FENESTRA_PT_result_display(ResultSubPanel, bpy.types.Panel):
    bl_label = "Display"

    @classmethod
    def poll(cls, context):  # a solve's result or an Annual Daylight run
        settings = context.scene.fenestra
        return settings.results.valid or settings.annual.valid

    def draw(self, context):
        layout, display = self.layout, context.scene.fenestra.display
        layout.label(text="False Colour:")
        layout.prop(display, "false_colour", text="")
        if display.false_colour == 'ANNUAL':
            layout.prop(display, "annual_metric", text="")
        if display.false_colour in SCALED or (
                display.false_colour == 'ANNUAL' and display.annual_metric not in false_colour.SHARES_OF_TIME):
            layout.prop(display, "colour_max")
        row = layout.row()
        row.prop(display, "show_legend")
        row.prop(display, "show_sensor_labels", text="Labels")
        layout.operator("fenestra.inspect_sensors", icon='EYEDROPPER')
        layout.operator("fenestra.show_goal_plot", icon='GRAPH')


class FENESTRA_PT_selected_sensor(ResultSubPanel, bpy.types.Panel):
    bl_label = "Selected Sensor"

    def draw(self, context):
        found = sensor_results.active_sensor(context)
        if found is None:
            self.layout.label(text="Select one vertex of a sensor object", icon='INFO')
            return
        obj, vertex, goal, achieved = found
        col = self.layout.column(align=True)
        col.label(text="%s, vertex %d" % (obj.name, vertex), icon='MESH_GRID')
        col.label(text="Goal: %s" % ("none" if math.isnan(goal) else "%.0f lx" % goal))
        col.label(text="Achieved: %.0f lx" % achieved)
        if not math.isnan(goal) and goal > 0:
            col.label(text="Achieved / goal: %.2f" % (achieved / goal))


classes = (FENESTRA_PT_result_display, FENESTRA_PT_selected_sensor)
