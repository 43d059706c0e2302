"""The Fenestra sidebar tab of the 3D View: domain, sensors, sky, solve, results."""

import bpy

from ..com import names, native, user_messages
from ..result import climate_results, sensor_results
from ..study import sky, visibility, weather_file
from . import constraint_defaults, solve_progress
from ...wording import counted

SHOWN = 12  # sensors listed in the Results panel


def draw_warning(layout, text):
    """A plainly visible warning, wrapped over several lines to the sidebar's width."""
    box = layout.box()
    region = getattr(bpy.context, "region", None)
    scale = bpy.context.preferences.system.ui_scale if bpy.context.preferences else 1.0
    # About 7 pixels a character at scale 1, less the icon and the box margins.
    width = max(20, int(((region.width if region else 320) - 60) / (7 * scale)))
    words, line, first = text.split(), "", True
    for word in words:
        if line and len(line) + len(word) > width:
            box.label(text=line, icon='ERROR' if first else 'BLANK1')
            line, first = "", False
        line = (line + " " + word).strip()
    if line:
        box.label(text=line, icon='ERROR' if first else 'BLANK1')


class FenestraPanel:
    bl_space_type = 'VIEW_3D'
    bl_region_type = 'UI'
    bl_category = "Fenestra"


class FENESTRA_PT_main(FenestraPanel, bpy.types.Panel):
    bl_label = "Fenestra"

    def draw(self, context):
        reason = native.unavailable()
        if reason:
            draw_warning(self.layout, reason)


class FENESTRA_PT_domain(FenestraPanel, bpy.types.Panel):
    bl_label = "Opening Domain"
    bl_parent_id = "FENESTRA_PT_main"

    def draw(self, context):
        layout, settings = self.layout, context.scene.fenestra
        row = layout.row(align=True)
        row.operator("fenestra.mark_domain")
        row.operator("fenestra.clear_domain")
        if context.mode != 'EDIT_MESH':
            layout.label(text="Select faces in Edit Mode", icon='INFO')
        layout.label(text="%s, %.2f m²" % (counted(settings.domain_faces, "face"), settings.domain_area))
        for obj, faces, reason in visibility.hidden_domain(context):
            draw_warning(layout, "%d on '%s': %s; left out of the study" % (faces, obj.name, reason))
        row = layout.split(factor=0.8)
        row.prop(settings, "show_domain")
        row.prop(settings.display, "domain_colour", text="")
        size = settings.solve.element_size
        layout.label(text="About %d elements of %.2f m" % (settings.domain_area / size ** 2, size))


class FENESTRA_PT_sensors(FenestraPanel, bpy.types.Panel):
    bl_label = "Sensors"
    bl_parent_id = "FENESTRA_PT_main"

    def draw(self, context):
        layout, settings = self.layout, context.scene.fenestra
        col = layout.column(align=True)
        col.prop(settings, "sensor_height")
        col.prop(settings, "sensor_spacing")
        row = col.row(align=True)
        row.prop(settings, "sensor_inset_auto", text="", icon='AUTO')
        sub = row.row(align=True)
        sub.active = not settings.sensor_inset_auto
        sub.prop(settings, "sensor_inset")
        col.operator("fenestra.add_sensor_grid", icon='MESH_GRID')
        obj = context.active_object
        if obj is not None and obj.type == 'MESH':
            layout.prop(obj.fenestra, "is_sensor", text="Sensor Object (%s)" % obj.name)
        sensors = [o for o in context.scene.objects if o.fenestra.is_sensor and o.type == 'MESH']
        layout.label(text="%s in %s" % (counted(sum(len(o.data.vertices) for o in sensors), "sensor"),
                                          counted(len(sensors), "object")))
        for obj, count, reason in visibility.hidden_sensors(context):
            draw_warning(layout, "%d in '%s': %s; left out of the study" % (count, obj.name, reason))
        goals = settings.goals
        layout.prop(goals, "source")
        if goals.source == 'NONE':
            layout.label(text="Climate goals below", icon='INFO')
            return
        layout.prop(goals, "units")
        if goals.source == 'UNIFORM':
            layout.prop(goals, "level")
            for flag, value in (("use_min", "min"), ("use_max", "max")):
                row = layout.row(align=True)
                row.prop(goals, flag, text="")
                sub = row.row()
                sub.active = getattr(goals, flag)
                sub.prop(goals, value)
        else:
            layout.prop(goals, "scale")
            layout.label(text="Paint '%s' in Vertex Paint" % names.GOAL_ATTRIBUTE, icon='BRUSH_DATA')


def draw_climate(layout, context, s):
    """The climate sky: the weather file (the place is the file's), north, occupied hours, patches."""
    layout.label(text="Weather File (.epw, .wea):")
    layout.prop(s, "weather_file", text="")
    problem = weather_file.problem(s)
    if problem:
        draw_warning(layout, problem)
    else:
        layout.label(text="Place: the weather file's", icon='WORLD')
    sp = sky.sun_position(context.scene)
    if sp is not None:
        layout.prop(s, "use_sun_position")
    if sp is not None and s.use_sun_position:
        layout.label(text="North %.1f° (Sun Position)" % sky.place_and_date(context.scene)[3], icon='LIGHT_SUN')
    else:
        layout.prop(s, "north_offset")
    layout.label(text="Occupied hours:")
    row = layout.row(align=True)
    row.prop(s, "occupied_start", text="From")
    row.prop(s, "occupied_end", text="To")
    layout.label(text="%s-%s local standard time" % (sky.clock(s.occupied_start), sky.clock(s.occupied_end)))
    problem = sky.occupied_problem(s)
    if problem:
        draw_warning(layout, problem)
    layout.prop(s, "patches")
    layout.label(text="Run: Results > Annual Daylight", icon='TIME')


class FENESTRA_PT_sky(FenestraPanel, bpy.types.Panel):
    bl_label = "Sky"
    bl_parent_id = "FENESTRA_PT_main"

    def draw(self, context):
        layout, s = self.layout, context.scene.fenestra.sky
        layout.prop(s, "type")
        if s.type == 'CLIMATE':
            draw_climate(layout, context, s)
        elif s.type in {'UNIFORM', 'CIE_OVERCAST'}:
            layout.prop(s, "horizontal_illuminance")
        else:
            sp = sky.sun_position(context.scene)
            if sp is not None:
                layout.prop(s, "use_sun_position")
            col = layout.column(align=True)
            if sp is not None and s.use_sun_position:
                lat, lon, utc, north, (y, m, d) = sky.place_and_date(context.scene)
                col.label(text="Sun Position: %.3f°, %.3f°, UTC%+g" % (lat, lon, utc), icon='LIGHT_SUN')
                col.label(text="%04d-%02d-%02d, north %.1f°" % (y, m, d, north))
            else:
                col.prop(s, "latitude")
                col.prop(s, "longitude")
                col.prop(s, "utc_offset")
                col.prop(s, "north_offset")
                row = col.row(align=True)
                row.prop(s, "year", text="")
                row.prop(s, "month", text="")
                row.prop(s, "day", text="")
            layout.prop(s, "use_date_end")
            if s.use_date_end:
                row = layout.row(align=True)
                row.prop(s, "end_year", text="")
                row.prop(s, "end_month", text="")
                row.prop(s, "end_day", text="")
            row = layout.row(align=True)
            row.prop(s, "start_time")
            row.prop(s, "end_time")
            layout.prop(s, "step_minutes")
            layout.prop(s, "turbidity")
        if s.type != 'UNIFORM':
            layout.prop(s, "ground_reflectance")
        if s.type not in {'UNIFORM', 'CLIMATE'}:  # the climate sky's map keeps the core's size
            layout.prop(s, "map_width")
        layout.prop(s, "preview_strength")
        layout.prop(context.scene.view_settings, "exposure")  # set by Preview Sky, yours to change
        layout.operator("fenestra.preview_sky", icon='WORLD')


class FENESTRA_PT_solve(FenestraPanel, bpy.types.Panel):
    bl_label = "Solve"
    bl_parent_id = "FENESTRA_PT_main"

    def draw(self, context):
        layout, s = self.layout, context.scene.fenestra.solve
        col = layout.column(align=True)
        col.prop(s, "element_size")
        col.prop(s, "wall_thickness")
        layout.prop(s, "quality")
        if s.quality == 'CUSTOM':
            col = layout.column(align=True)
            col.prop(s, "paths")
            col.prop(s, "generations")
            col.prop(s, "population")
        layout.prop(s, "seed")
        layout.prop(s, "edges_on_grid")
        layout.prop(s, "use_booleans")
        layout.prop(s, "study_directory")
        layout.separator()
        if not solve_progress.draw(layout):  # while a solve runs: its progress and Cancel
            layout.operator("fenestra.solve_openings", icon='MOD_BOOLEAN')


class FENESTRA_PT_constraints(FenestraPanel, bpy.types.Panel):
    bl_label = "Constraints"
    bl_parent_id = "FENESTRA_PT_solve"
    bl_options = {'DEFAULT_CLOSED'}

    def draw(self, context):
        layout, c = self.layout, context.scene.fenestra.solve.constraints
        row = layout.row(align=True)
        row.prop(c, "automatic")
        row.prop(c, "full_height", text="Full Height")
        layout.prop(c, "catalogue")
        layout.label(text="0 = unset, automatic greyed" if c.automatic else "0 = unset")
        settings = context.scene.fenestra
        climate = settings.sky.type == 'CLIMATE' and len(settings.goals.climate) > 0
        automatic = constraint_defaults.automatic_values(c, climate)
        col = layout.column(align=True)
        for key in c.KEYS:
            if key in automatic:  # left at 0: greyed, named with the value the solver will use
                row = col.row(align=True)
                row.active = False
                row.prop(c, key, text="%s (%s)" % (c.bl_rna.properties[key].name, automatic[key]))
            else:
                col.prop(c, key)
        layout.label(text="Facade Composition")
        aligned_by_default = constraint_defaults.aligned_by_default(c)
        grid = layout.grid_flow(row_major=True, columns=0, even_columns=True, align=True)  # as many as fit
        for key in c.COMPOSITION:
            if key in aligned_by_default:  # greyed, named with what the solver will do
                row = grid.row(align=True)
                row.active = False
                row.prop(c, key, text="%s (auto where cheap)" % c.bl_rna.properties[key].name)
            else:
                grid.prop(c, key)
        layout.label(text="Sill Heights (m, e.g. 0.9, 1.2):")
        layout.prop(c, "sill_heights", text="")
        try:
            chosen = c.as_dict()
        except ValueError as exc:
            draw_warning(layout, str(exc))
            chosen = True
        if native.unavailable() is None and chosen and not native.accepts_constraints():
            draw_warning(layout, "This build of the solver does not take constraints yet: they are not used.")


def draw_tradeoffs(box, r, per_sensor_goals):
    """The answer and the best found with fewer openings, each a button that shows it: openings,
    glazing and the predicted error; with climate goals, each goal's figure and whether it is met."""
    box.label(text="Trade-offs (predicted)" if per_sensor_goals else "Trade-offs")
    col = box.column(align=True)
    for i, t in enumerate(r.tradeoffs):
        text = "%s, %.2f m\u00b2" % (counted(t.openings, "opening"), t.glazing_area)
        icon = 'NONE'
        if per_sensor_goals:
            text += ", %.1f %%" % (100 * t.relative_rms)
        else:  # met or not at a glance; each goal's figure below, a line each (the sidebar is narrow)
            icon = {1: 'CHECKMARK', 0: 'X'}.get(t.climate_met, 'NONE')
        op = col.operator("fenestra.apply_tradeoff", depress=(i == r.tradeoff_shown), text=text, icon=icon)
        op.index = i
        if not per_sensor_goals and t.climate_line:
            for goal_line, met in climate_results.tradeoff_rows(t.climate_line):
                row = col.row()
                row.active = False
                row.label(text=goal_line, icon={True: 'CHECKMARK', False: 'X'}.get(met, 'BLANK1'))
            if t.climate_by_cutters:
                row = col.row()
                row.active = False
                row.label(text="    (real cutters)")


class FENESTRA_PT_results(FenestraPanel, bpy.types.Panel):
    bl_label = "Results"
    bl_parent_id = "FENESTRA_PT_main"

    def draw(self, context):
        layout, r = self.layout, context.scene.fenestra.results
        if not r.valid:
            layout.label(text="No result yet")
            return
        col = layout.column(align=True)
        glazing = r.tradeoffs[r.tradeoff_shown].glazing_area if r.tradeoff_shown < len(r.tradeoffs) else None
        col.label(text=counted(r.openings, "opening") + ("" if glazing is None else ", %.2f m\u00b2 of glazing" % glazing))
        if r.open_elements >= 0:  # (a trade-off's openings are rectangles, not elements)
            col.label(text="%d of %s open" % (r.open_elements, counted(r.elements, "element")))
        if r.tradeoff_shown > 0:
            col.label(text="A trade-off: the best found with %s" % counted(r.openings, "opening"), icon='INFO')
        # A climate solve's per-sensor goals are its own element answer's light: its figures are the
        # climate goals' (their sub-panel), not these errors.
        per_sensor_goals = not r.climate.valid
        if per_sensor_goals:
            col.label(text="Error %.1f %% RMS" % (100 * r.relative_rms))
        if r.evaluated:
            col.label(text="Evaluated as placed", icon='CHECKMARK')
        worst = sensor_results.worst_sensor_lines(r) if per_sensor_goals else None
        if worst:
            col.label(text=worst[0])
            col.label(text="    " + worst[1])
        if r.verified_rms >= 0 and per_sensor_goals:
            col.label(text="Checked: %.1f %% (noise %.1f %%)" % (100 * r.verified_rms, 100 * r.verified_noise))
        for warning in filter(None, r.warnings.split("\n")):
            if not (r.climate.valid and climate_results.is_unmet_warning(warning)):  # (listed with the goals)
                draw_warning(layout, user_messages.for_user(warning))  # the constraints by their labels
        if len(r.tradeoffs) > 1:
            draw_tradeoffs(layout.box(), r, per_sensor_goals)
        col.label(text="Time %.1f s (solver %.1f s)" % (r.seconds_total, r.seconds_solver))
        if not per_sensor_goals:
            layout.operator("fenestra.evaluate_openings", icon='PLAY')
            layout.operator("fenestra.clear_results", icon='X')
            return
        box = layout.box()
        box.label(text="Farthest from their goals:" if len(r.sensors) > SHOWN else "Sensors:")
        col = box.column(align=True)
        one_object = len({s.object_name for s in r.sensors}) == 1
        for cells in [("Vertex" if one_object else "Sensor", "Goal lx", "Got lx")] + [
                (sensor_results.name(s, one_object), "-" if s.goal < 0 else "%.0f" % s.goal, "%.0f" % s.achieved)
                for s in sensor_results.farthest_from_goal(r, SHOWN)]:
            row = col.row(align=True)
            for text in cells:
                row.label(text=text)
        if len(r.sensors) > SHOWN:
            box.label(text="%d more: select a vertex" % (len(r.sensors) - SHOWN))
        layout.operator("fenestra.evaluate_openings", icon='PLAY')
        layout.operator("fenestra.clear_results", icon='X')


classes = (
    FENESTRA_PT_main,
    FENESTRA_PT_domain,
    FENESTRA_PT_sensors,
    FENESTRA_PT_sky,
    FENESTRA_PT_solve,
    FENESTRA_PT_constraints,
    FENESTRA_PT_results,
)
