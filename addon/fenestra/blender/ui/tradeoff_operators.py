"""Pick a simpler design: the cutters replaced by one of the solve's trade-offs (the best found
with fewer openings), without solving again. Ctrl-Z restores the previous ones."""

import json
import os

import bpy

from ..result import results
from ..com.study_error import StudyError
from ..study import export
from ...wording import counted


class FENESTRA_OT_apply_tradeoff(bpy.types.Operator):
    """Show this trade-off's openings (the best found with this many) in place of the current ones, with its predicted light and error"""
    bl_idname = "fenestra.apply_tradeoff"
    bl_label = "Apply Trade-off"
    bl_options = {'REGISTER', 'UNDO'}

    index: bpy.props.IntProperty(name="Trade-off", min=0, description="0: the answer; then one opening fewer each")

    @classmethod
    def poll(cls, context):
        r = context.scene.fenestra.results
        return r.valid and len(r.tradeoffs) > 1

    def execute(self, context):
        r = context.scene.fenestra.results
        directory = os.path.dirname(bpy.path.abspath(r.study_path))
        try:
            with open(os.path.join(directory, "result.json")) as f:
                result = json.load(f)
            if self.index >= len(result.get("tradeoffs", [])):
                raise ValueError("the study folder's result has no trade-off %d: solve again" % self.index)
            study = export.build(context)
            if sum(count for _, count in study.sensor_objects) != len(result["sensors"]):
                raise ValueError("the sensors changed since the solve: solve again")
        except (OSError, ValueError, KeyError, StudyError) as exc:
            self.report({'ERROR'}, "Cannot apply the trade-off: %s" % exc)
            return {'CANCELLED'}
        study.directory = directory
        results.apply(context, study, results.tradeoff_result(result, self.index))
        r.tradeoff_shown = self.index
        entry = result["tradeoffs"][self.index]
        self.report({'INFO'}, "%s, relative RMS error %.1f %% (predicted)"
                    % (counted(entry["openings_count"], "opening"), 100 * entry["error"]["relative_rms"]))
        return {'FINISHED'}


classes = (FENESTRA_OT_apply_tradeoff,)
