"""Evaluate: the openings where their cutters stand now, path-traced.

After a solve the user may move, scale or turn a cutter in its wall (the Boolean modifiers follow
it). Evaluate reads the openings back from the cutters (opening_cutters.py), exports the study as
the solve does, path-traces it with those openings (fenestra.evaluate) and puts the sensors'
values and the error against the solve's goals into the results. The study folder gets
openings.json (`fenestra evaluate scene.json --openings openings.json` runs it again) and
evaluation.json (per sensor goal, value and standard error; the error).
"""

import json
import os

import bpy
import numpy as np

from ..com import native, user_messages
from ..result import climate_results, results
from ..study import export, opening_cutters
from ...wording import counted
from . import long_message


def goal_error(goals, values):
    """(relative RMS error, largest relative error) of values against goals (lux; negative: no
    goal): the solve's own measure, every weight 1 as the add-on exports no weights."""
    from ...api import goal_error as solver_error
    goals = np.asarray(goals, np.float64)
    if not np.any(goals >= 0):  # no sensor has a goal (goal_error refuses that): no error to show
        return 0.0, 0.0
    error = solver_error(goals, np.asarray(values, np.float64))
    return error["relative_rms"], error["max_relative"]


class FENESTRA_OT_evaluate_openings(bpy.types.Operator):
    """Path-trace the study with the openings where their cutters stand now (moved, scaled or turned in their wall) and show the sensors' values and the error against the goals"""
    bl_idname = "fenestra.evaluate_openings"
    bl_label = "Evaluate"
    bl_options = {'REGISTER', 'UNDO'}

    @classmethod
    def poll(cls, context):
        return context.mode == 'OBJECT' and any(o.fenestra.is_opening for o in context.scene.objects)

    def execute(self, context):
        reason = native.unavailable()
        if reason:
            self.report({'ERROR'}, reason)
            return {'CANCELLED'}
        from ... import api as fenestra
        scene, r = context.scene, context.scene.fenestra.results
        if not r.valid or len(r.sensors) == 0:
            self.report({'ERROR'}, "No solve to compare with: solve first, then move the cutters and evaluate")
            return {'CANCELLED'}
        cutters = opening_cutters.cutters(scene)
        names = [o.name for o in cutters]
        study = None
        try:
            study = export.build(context)
            openings = opening_cutters.read(cutters, study)
            path = study.write(export.study_directory(scene))
            native_scene = fenestra.load_scene(path)
            fenestra.check_cost(native_scene, "evaluate")
            values, stderr = fenestra.evaluate(native_scene, openings)
        except (ValueError, OSError) as exc:
            long_message.report_error(self, user_messages.for_user(exc, study, names))
            return {'CANCELLED'}
        if len(values) != len(r.sensors):
            self.report({'ERROR'}, "The sensors changed since the solve (%d now, %d then): solve again"
                        % (len(values), len(r.sensors)))
            return {'CANCELLED'}
        goals = np.array([s.goal for s in r.sensors])
        solved = r.relative_rms
        rms, worst = goal_error(goals, values)
        with open(os.path.join(study.directory, "openings.json"), "w") as f:
            json.dump({"openings": openings}, f, indent=1)
        with open(os.path.join(study.directory, "evaluation.json"), "w") as f:
            json.dump({"openings": names, "error": {"relative_rms": rms, "max_relative": worst},
                       "sensors": [{"goal": float(g) if g >= 0 else None, "value": float(v), "stderr": float(e)}
                                   for g, v, e in zip(goals, values, stderr)]}, f, indent=1)
        for item, value in zip(r.sensors, values):
            item.achieved = value
        results.write_achieved(study, np.asarray(values, np.float64))
        r.relative_rms, r.max_relative, r.verified_rms = rms, worst, -1.0
        r.openings, r.evaluated = len(cutters), True
        if r.climate.valid:  # its climate figures were of the solved openings (Annual Daylight gives these)
            climate_results.apply(r, None)
            display = context.scene.fenestra.display
            if display.false_colour in climate_results.QUANTITIES:
                display.false_colour = 'ACHIEVED'
        self.report({'INFO'}, "%s as they stand: relative RMS error %.1f %% (before: %.1f %%), worst "
                    "sensor %.1f %%" % (counted(len(cutters), "opening"), 100 * rms, 100 * solved, 100 * worst))
        return {'FINISHED'}


classes = (FENESTRA_OT_evaluate_openings,)
