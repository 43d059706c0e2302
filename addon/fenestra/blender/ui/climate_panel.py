"""Climate goals in the sidebar: their list (add, remove, each goal's metric, thresholds and sensor
group) under Sensors, and what a solve reached under Results. Drawing and list editing only: the
figures are the native core's (scene.fenestra.results.climate)."""

import bpy

from ..result import climate_results
from .panels import FenestraPanel, draw_warning

SENSE = {"at_least": "≥", "at_most": "≤", "target": "≈"}


class FENESTRA_UL_climate_goals(bpy.types.UIList):
    """One row per climate goal: its metric and thresholds, and its sensors."""

    def draw_item(self, context, layout, data, item, icon, active_data, active_property, index=0, flt_flag=0):
        split = layout.split(factor=0.75, align=True)
        split.label(text=item.summary())
        sub = split.row()
        sub.active = False
        sub.label(text=item.sensor_group or "all")


class FENESTRA_OT_climate_goal_add(bpy.types.Operator):
    """Add a climate goal (an sDA goal first, then an ASE goal, with the defaults of IES LM-83 and LEED v4)"""
    bl_idname = "fenestra.climate_goal_add"
    bl_label = "Add Climate Goal"
    bl_options = {'REGISTER', 'UNDO'}

    def execute(self, context):
        goals = context.scene.fenestra.goals
        metrics = {g.metric for g in goals.climate}
        goal = goals.climate.add()
        goal.metric = 'ASE' if 'SDA' in metrics and 'ASE' not in metrics else 'SDA'
        goals.climate_index = len(goals.climate) - 1
        return {'FINISHED'}


class FENESTRA_OT_climate_goal_remove(bpy.types.Operator):
    """Remove the selected climate goal"""
    bl_idname = "fenestra.climate_goal_remove"
    bl_label = "Remove Climate Goal"
    bl_options = {'REGISTER', 'UNDO'}

    @classmethod
    def poll(cls, context):
        return len(context.scene.fenestra.goals.climate) > 0

    def execute(self, context):
        goals = context.scene.fenestra.goals
        index = min(goals.climate_index, len(goals.climate) - 1)
        goals.climate.remove(index)
        goals.climate_index = max(0, min(index, len(goals.climate) - 1))
        return {'FINISHED'}


def draw_goal(layout, goal):
    """The selected goal's fields: metric, thresholds (units in their labels), sensor group, weight."""
    col = layout.column(align=True)
    col.prop(goal, "metric")
    for key in goal.fields():
        prop = goal.bl_rna.properties[key]
        unit = {"sda_lux": "lx", "ase_lux": "lx", "udi_lower": "lx", "udi_upper": "lx", "mean_lux": "lx",
                "ase_hours": "h"}.get(key)
        col.prop(goal, key, text="%s (%s)" % (prop.name, unit) if unit else prop.name)
    layout.prop(goal, "sensor_group", text="Group", icon='GROUP_VERTEX')
    layout.prop(goal, "weight")


class FENESTRA_PT_climate_goals(FenestraPanel, bpy.types.Panel):
    bl_label = "Climate Goals"
    bl_parent_id = "FENESTRA_PT_sensors"

    @classmethod
    def poll(cls, context):  # the climate sky, or goals left in the list (to be removed or kept)
        settings = context.scene.fenestra
        return settings.sky.type == 'CLIMATE' or len(settings.goals.climate) > 0

    def draw(self, context):
        layout, settings = self.layout, context.scene.fenestra
        goals = settings.goals
        if settings.sky.type != 'CLIMATE':
            draw_warning(layout, "Climate goals need the Climate sky (Sky panel): choose it, or remove them")
        row = layout.row()
        row.template_list("FENESTRA_UL_climate_goals", "", goals, "climate", goals, "climate_index", rows=3)
        col = row.column(align=True)
        col.operator("fenestra.climate_goal_add", icon='ADD', text="")
        col.operator("fenestra.climate_goal_remove", icon='REMOVE', text="")
        if 0 <= goals.climate_index < len(goals.climate):
            draw_goal(layout.box(), goals.climate[goals.climate_index])
        layout.prop(goals, "least_glazing")
        if not len(goals.climate):
            row = layout.row()
            row.active = False
            row.label(text="+ adds sDA, then ASE", icon='INFO')


def _figure(goal, value):
    return climate_results.text(value, goal.unit)


def draw_note(layout, text):
    row = layout.row()
    row.active = False
    row.label(text=text, icon='INFO')


def draw_goal_result(box, goal):
    """A goal's figures: the real cutters' first where they exist, the path records' beside them,
    and a warning where the two disagree beyond the noise."""
    figure, met, source = goal.lead()
    known = goal.has_achieved or goal.has_verified
    box.label(text=goal.description, icon='CHECKMARK' if known and met else 'X')
    col = box.column(align=True)
    col.label(text="Required %s %s" % (SENSE.get(goal.sense, ""), _figure(goal, goal.required)))
    col.label(text="%s: %s" % ("Real cutters" if source == "real cutters" else "Path records",
                               _figure(goal, figure) if known else "-"))
    if source == "real cutters" and goal.has_records:
        row = col.row()
        row.active = False
        row.label(text="Path records: %s" % _figure(goal, goal.records))
    if goal.apart:
        draw_warning(box, "The path records and real cutters disagree beyond the noise: trust the cutters' figure")


class FENESTRA_PT_climate_results(FenestraPanel, bpy.types.Panel):
    bl_label = "Climate Goals"
    bl_parent_id = "FENESTRA_PT_results"

    @classmethod
    def poll(cls, context):
        r = context.scene.fenestra.results
        return r.valid and r.climate.valid

    def draw(self, context):
        layout, settings = self.layout, context.scene.fenestra
        c, display = settings.results.climate, settings.display
        leads = [g.lead() for g in c.goals if g.has_achieved or g.has_verified]
        met = sum(1 for _, goal_met, _ in leads if goal_met)
        all_met = met == len(c.goals) and len(leads) == len(c.goals)
        layout.label(text="All %d goals met" % len(c.goals) if all_met else "%d of %d goals met" % (met, len(c.goals)),
                     icon='CHECKMARK' if all_met else 'ERROR')
        if c.tradeoff:
            draw_note(layout, "A trade-off's figures (Results > Trade-offs); rooms and the year are the answer's")
        for goal in c.goals:
            draw_goal_result(layout.box(), goal)
        if len(c.rooms):  # each room (sensor group) the goals name, with the solved year's figures
            box = layout.box()
            box.label(text="Rooms", icon='HOME')
            for room in c.rooms:
                col = box.column(align=True)
                col.label(text="%s (%d sensors)" % (room.name, room.sensors))
                row = col.row()
                row.active = False
                row.label(text="sDA %.0f %%  ASE %.0f %%  %.0f lx" % (
                    100 * room.spatial_daylight_autonomy, 100 * room.annual_sunlight_exposure, room.mean_illuminance))
        share = c.glazing_area / c.domain_area if c.domain_area > 0 else 0.0
        col = layout.column(align=True)
        col.label(text="Glazing %.2f m² (%.0f %%)" % (c.glazing_area, 100 * share), icon='MOD_BOOLEAN')
        row = col.row()
        row.active = False
        row.label(text="of %.2f m² of opening domain" % c.domain_area)
        if c.least_glazing:
            row = col.row()
            row.active = False
            row.label(text="Least glazing that meets the goals")
        for line in filter(None, c.unmet.split("\n")):
            draw_warning(layout, line)
        row = layout.row(align=True)
        row.label(text="Show:")
        row.prop(display, "false_colour", text="")


classes = (FENESTRA_UL_climate_goals, FENESTRA_OT_climate_goal_add, FENESTRA_OT_climate_goal_remove,
           FENESTRA_PT_climate_goals, FENESTRA_PT_climate_results)
