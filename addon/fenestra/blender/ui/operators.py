"""Operators: opening domain, sensor grid, sky preview, Solve Openings, Clear Results."""

import json
import os

import bpy
import numpy as np

from ..com import (contributions_cache, names, native, native_messages, solve_job, study_fingerprint, study_folder,
                   user_messages)
from ..result import results, sky_preview
from ..study import export, sensor_grid_objects, setup_checks
from . import check_setup, job_operator, long_message, solve_guard
from ...wording import counted


def _native_or_report(op):
    reason = native.unavailable()
    if reason:
        op.report({'ERROR'}, reason)
    return reason is None


# Opening domain ---------------------------------------------------------------------------------

def _mark_selected(context, value):
    """Sets `fenestra_domain` on the selected faces of the meshes in Edit Mode; returns how many
    faces changed (marked that were not, or unmarked that were)."""
    objects = [o for o in context.objects_in_mode if o.type == 'MESH']
    bpy.ops.object.mode_set(mode='OBJECT')
    changed = 0
    try:
        for obj in objects:
            mesh = obj.data
            n = len(mesh.polygons)
            selected = np.zeros(n, bool)
            mesh.polygons.foreach_get("select", selected)
            attr = mesh.attributes.get(names.DOMAIN_ATTRIBUTE)
            if attr is None:
                if not value or not selected.any():
                    continue
                attr = mesh.attributes.new(names.DOMAIN_ATTRIBUTE, 'BOOLEAN', 'FACE')
            flags = np.zeros(n, bool)
            attr.data.foreach_get("value", flags)
            changed += int((selected & (flags != value)).sum())
            flags[selected] = value
            attr.data.foreach_set("value", flags)
            mesh.update()
        _count_domain(context.scene)
    finally:
        bpy.ops.object.mode_set(mode='EDIT')
    return changed


def _count_domain(scene):
    """Domain faces and area over the scene's meshes (undeformed, world scale)."""
    faces, area = 0, 0.0
    for obj in scene.objects:
        if obj.type != 'MESH' or names.DOMAIN_ATTRIBUTE not in obj.data.attributes:
            continue
        flags = export._face_flags(obj.data, names.DOMAIN_ATTRIBUTE)
        areas = np.zeros(len(flags))
        obj.data.polygons.foreach_get("area", areas)
        scale = abs(obj.matrix_world.to_3x3().determinant()) ** (2.0 / 3.0)
        faces += int(flags.sum())
        area += float(areas[flags].sum()) * scale
    scene.fenestra.domain_faces, scene.fenestra.domain_area = faces, area


class FENESTRA_OT_mark_domain(bpy.types.Operator):
    """Mark the selected faces as opening domain: openings may be cut there"""
    bl_idname = "fenestra.mark_domain"
    bl_label = "Mark Selected Faces"
    bl_options = {'REGISTER', 'UNDO'}

    @classmethod
    def poll(cls, context):
        return context.mode == 'EDIT_MESH'

    def execute(self, context):
        n = _mark_selected(context, True)
        self.report({'INFO'}, "%s marked as opening domain" % counted(n, "face"))
        return {'FINISHED'}


class FENESTRA_OT_clear_domain(bpy.types.Operator):
    """Remove the selected faces from the opening domain"""
    bl_idname = "fenestra.clear_domain"
    bl_label = "Clear"
    bl_options = {'REGISTER', 'UNDO'}

    @classmethod
    def poll(cls, context):
        return context.mode == 'EDIT_MESH'

    def execute(self, context):
        n = _mark_selected(context, False)
        self.report({'INFO'}, "%s removed from the opening domain" % counted(n, "face"))
        return {'FINISHED'}


# Sensors ----------------------------------------------------------------------------------------

class FENESTRA_OT_add_sensor_grid(bpy.types.Operator):
    """Add a grid of upward sensors over each room's floor in the selected objects (a floor, or a whole room or building), at the set height above the floor's upper face, kept off the walls: one sensor object per room"""
    bl_idname = "fenestra.add_sensor_grid"
    bl_label = "Add Sensor Grid"
    bl_options = {'REGISTER', 'UNDO'}

    @classmethod
    def poll(cls, context):
        obj = context.active_object
        return context.mode == 'OBJECT' and obj is not None and obj.type == 'MESH'

    def execute(self, context):
        if not _native_or_report(self):
            return {'CANCELLED'}
        from ... import sensor_grids
        settings = context.scene.fenestra
        chosen = [o for o in context.selected_objects if o.type == 'MESH'] or [context.active_object]
        height, spacing = settings.sensor_height, settings.sensor_spacing
        inset = None if settings.sensor_inset_auto else settings.sensor_inset
        vertices, triangles, floors = sensor_grid_objects.model_faces(context, chosen)
        try:
            grid = sensor_grids.sensor_grid(vertices, triangles, floors, height, spacing, inset)
        except ValueError as exc:
            long_message.report_error(self, user_messages.for_user(str(exc)))
            return {'CANCELLED'}
        rooms = grid["rooms"]
        if not rooms:
            long_message.report_error(self, "No floor of %s has room for sensors %.2f m above it and %.2f m off the walls "
                        "(a face within 45\u00b0 of horizontal, its ceiling higher than that)"
                        % (", ".join("'%s'" % o.name for o in chosen), height, grid["inset"]))
            return {'CANCELLED'}
        level = min(settings.goals.level, 1.0) if settings.goals.units == 'NORMALIZED' else 0.5
        objects = sensor_grid_objects.add_rooms(context, rooms, level)
        self.report({'INFO'}, grid_report(grid, objects, height))
        return {'FINISHED'}


def grid_report(grid, objects, height):
    """'80 sensors in 1 room, 0.80 m above the floor's upper face (z = 0.00 m), 0.25 m off the walls'."""
    rooms = grid["rooms"]
    count = sum(len(r["points"]) for r in rooms)
    low = min(float(r["floor_z"].min()) for r in rooms)
    high = max(float(r["floor_z"].max()) for r in rooms)
    floors = "z = %.2f m" % low if abs(high - low) < 0.005 else "z = %.2f to %.2f m" % (low, high)
    text = "%s in %s, %.2f m above the floor's upper face (%s), %.2f m off the walls" % (
        counted(count, "sensor"), counted(len(rooms), "room"), height, floors, grid["inset"])
    if not grid["enclosed"]:
        text += "; no ceiling over the floor"
    if len(objects) > 1:
        text += ": " + ", ".join("'%s'" % o.name for o in objects)
    return text


# Sky --------------------------------------------------------------------------------------------

class FENESTRA_OT_preview_sky(bpy.types.Operator):
    """Compute the study's sky map and light the World with it (the sun is not in the map), exposed so that the zenith is mid grey"""
    bl_idname = "fenestra.preview_sky"
    bl_label = "Preview Sky"
    bl_options = {'REGISTER', 'UNDO'}

    def execute(self, context):
        if not _native_or_report(self):
            return {'CANCELLED'}
        try:
            summary, exposure = sky_preview.preview(context.scene)
        except (ValueError, OSError) as exc:
            self.report({'ERROR'}, user_messages.for_user(exc))
            return {'CANCELLED'}
        # The screen the button was pressed in; from a script without one, every window's.
        screens = [context.screen] if context.screen else [w.screen for w in context.window_manager.windows]
        turned_on = sky_preview.show_world_in_viewports(screens)
        light = summary["horizontal_illuminance"]
        self.report({'INFO'}, "Sky %.0f lux + sun %.0f lux on the horizontal (mean over the interval)%s%s"
                    % (light["sky"], light["sun"], "" if exposure is None else ", exposure %+.1f" % exposure,
                       "" if not turned_on else "; Scene World turned on in Material Preview and Rendered "
                       "shading of %s" % counted(turned_on, "3D View")))
        return {'FINISHED'}


# Solve ------------------------------------------------------------------------------------------


class FENESTRA_OT_solve_openings(job_operator.JobOperator, bpy.types.Operator):
    """Compute the openings that meet the sensors' daylight goals and cut them into the domain"""
    CANCELLED_MESSAGE = "Solve cancelled"
    RUNNING_MESSAGE = "A solve is running: wait for it, or cancel it (Esc, or Cancel in the Solve panel)"
    MODE_MESSAGE = "Solve needs Object Mode"
    bl_idname = "fenestra.solve_openings"
    bl_label = "Solve Openings"
    bl_options = {'REGISTER', 'UNDO'}

    def _prepare(self, context):
        """Exports the study into a staging folder beside the study folder (study_folder.py) and
        makes its job, with the previous solve's contributions when they still apply; reports and
        returns False on a bad setup."""
        if not _native_or_report(self):
            return False
        staging = None
        try:
            self._study = solve_guard.export_quietly(context)
            check_setup.show(self, context, setup_checks.run(context, self._study))
            staging = study_folder.StagingFolder(export.study_directory(context.scene))
            path = self._study.write(staging.path)
        except (ValueError, OSError) as exc:
            if staging is not None:
                staging.discard()
            long_message.report_error(self, user_messages.for_user(native_messages.for_the_panel(str(exc), ""),
                                                                   getattr(self, "_study", None)))
            return False
        self._staging = staging
        reusable = study_fingerprint.contributions_fingerprint(self._study)
        self._job = solve_job.SolveJob(path, study_fingerprint.fingerprint(self._study), reusable,
                                       contributions_cache.take(reusable))
        return True

    def _finish(self, context, check_scene):
        """Applies the job's result, or reports why not; the staging folder goes either way."""
        job = self._job
        ended = self._ended_without_result(context, check_scene, "The scene changed during the solve: its result was "
                                           "discarded, the model and the study folder are as they were. Solve again")
        if ended is not None:
            return ended
        result = job.result
        try:
            with open(os.path.join(self._staging.path, "result.json"), "w") as f:
                json.dump(result, f, indent=1)
            leftover = self._staging.commit()
        except OSError as exc:
            self._staging.discard()
            return self._tell(job, 'ERROR', "The study folder could not be replaced: %s" % exc)
        self._study.directory = self._staging.final
        results.apply(context, self._study, result)
        r = context.scene.fenestra.results
        for warning in result.get("warnings", []):
            self.report({'WARNING'}, warning)
        if leftover:
            self.report({'WARNING'}, "Files of the previous study folder stayed in %s" % leftover)
        reused = " (contributions reused)" if job.reused else ""
        if r.climate.valid:  # climate goals: whether they are met is the news, and the glazing it takes
            met = sum(1 for g in r.climate.goals if g.has_achieved and g.met)
            return self._tell(job, 'INFO', "%s, %d of %d climate goals met, glazing %.2f m², %.1f s%s (study in %s)"
                              % (counted(r.openings, "opening"), met, len(r.climate.goals), r.climate.glazing_area, r.seconds_total,
                                 reused, self._study.directory))
        return self._tell(job, 'INFO', "%s, relative RMS error %.1f %%, %.1f s%s (study in %s)"
                          % (counted(r.openings, "opening"), 100 * r.relative_rms, r.seconds_total, reused, self._study.directory))


class FENESTRA_OT_clear_results(bpy.types.Operator):
    """Remove what Solve Openings made: the cutters and their collection, the Boolean and Geometry Nodes modifiers, the sensors' achieved values and the result's figures"""
    bl_idname = "fenestra.clear_results"
    bl_label = "Clear Results"
    bl_options = {'REGISTER', 'UNDO'}

    def execute(self, context):
        n = results.clear(context.scene)
        self.report({'INFO'}, "Result cleared: %d cutters removed" % n)
        return {'FINISHED'}


classes = (
    FENESTRA_OT_mark_domain,
    FENESTRA_OT_clear_domain,
    FENESTRA_OT_add_sensor_grid,
    FENESTRA_OT_preview_sky,
    FENESTRA_OT_solve_openings,
    FENESTRA_OT_clear_results,
)
