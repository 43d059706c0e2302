"""Annual Daylight: the climate-based metrics of the openings as their cutters stand now.

The study is exported as for a solve, the openings read back from the cutters as Evaluate reads
them (opening_cutters.py; none: the model as it stands, the domain closed), and the year of the
weather file is path-traced on a worker thread (annual_job.py), with the Solve panel's progress,
Esc and Cancel. The run gets a folder of its own, `annual/` in the study folder (scene.json,
scene.obj, openings.json, and annual.json / annual.npz as `fenestra annual` writes them), staged
and put in place only when the run succeeds. The contributions are kept (contributions_cache.py):
moving a cutter and running again takes a fraction of a second."""

import json
import os

import bpy
import numpy as np

from ..com import (annual_job, contributions_cache, native, native_messages, study_fingerprint, study_folder,
                   user_messages)
from ..result import annual_results
from ..study import export, opening_cutters
from . import job_operator, long_message, solve_guard
from ...wording import counted

FOLDER = "annual"  # in the study folder
FILES = ("scene.json", "scene.obj", "openings.json", "annual.json", "annual.npz")
NPZ_ARRAYS = ("illuminance", "direct_sun", "hour_month", "hour_day", "hour_clock", "occupied")


def _percent(fraction):
    return "%.0f %%" % (100.0 * fraction)


def summary_line(annual):
    """The run in one line, for the status bar."""
    line = "sDA300/50%% %s, DA %s, annual mean %.0f lx" % (
        _percent(annual.spatial_daylight_autonomy), _percent(annual.daylight_autonomy), annual.mean_illuminance)
    if annual.has_ase:
        line += ", ASE1000,250 %s" % _percent(annual.annual_sunlight_exposure)
    return line


def _write_outputs(directory, outcome):
    """annual.json (the metrics) and annual.npz (the hourly illuminance), as `fenestra annual` names them."""
    with open(os.path.join(directory, "annual.json"), "w") as f:
        json.dump(outcome["summary"], f, indent=1)
    np.savez(os.path.join(directory, "annual.npz"), **{k: np.asarray(outcome[k]) for k in NPZ_ARRAYS if k in outcome})


class FENESTRA_OT_annual_daylight(job_operator.JobOperator, bpy.types.Operator):
    """Compute a year of daylight from the weather file with the openings where their cutters stand: spatial daylight autonomy, sunlight exposure, daylight autonomy, useful daylight and EN 17037, and per-sensor metrics in false colour"""
    CANCELLED_MESSAGE = "Annual Daylight cancelled"
    RUNNING_MESSAGE = "A solve or an annual run is going: wait for it, or cancel it (Esc)"
    MODE_MESSAGE = "Annual Daylight needs Object Mode"
    bl_idname = "fenestra.annual_daylight"
    bl_label = "Annual Daylight"
    bl_options = {'REGISTER', 'UNDO'}

    @classmethod
    def poll(cls, context):
        if context.scene.fenestra.sky.type != 'CLIMATE':
            cls.poll_message_set("Annual Daylight needs the Climate (weather file) sky")
            return False
        return super().poll(context)

    def _refuse(self, message, staging=None):
        if staging is not None:
            staging.discard()
        long_message.report_error(self, message)
        return False

    def _prepare(self, context):
        """Exports the study and reads the openings (nothing is written on a bad setup), then stages
        the run's folder and makes its job; reports and returns False when refused."""
        reason = native.unavailable()
        if reason:
            return self._refuse(reason)
        cutters = opening_cutters.cutters(context.scene)
        names = self._names = [o.name for o in cutters]
        self._study = staging = None
        try:
            self._study = solve_guard.export_quietly(context)
            openings = opening_cutters.read(cutters, self._study)
            staging = study_folder.StagingFolder(os.path.join(export.study_directory(context.scene), FOLDER), FILES)
            path = self._study.write(staging.path)
            with open(os.path.join(staging.path, "openings.json"), "w") as f:
                json.dump({"openings": openings}, f, indent=1)
        except (ValueError, OSError) as exc:
            return self._refuse(user_messages.for_user(native_messages.for_the_panel(str(exc), ""), self._study, names),
                                staging)
        self._staging = staging
        reusable = study_fingerprint.contributions_fingerprint(self._study)
        self._job = annual_job.AnnualJob(path, study_fingerprint.fingerprint(self._study), reusable, openings,
                                         contributions_cache.take(reusable))
        return True

    def _finish(self, context, check_scene):
        """Puts the run into the model, or reports why not; the staging folder goes either way."""
        job = self._job
        for warning in job.weather_warnings:
            self.report({'WARNING'}, warning)
        ended = self._ended_without_result(context, check_scene, "The scene changed during the annual run: its result "
                                           "was discarded. Run Annual Daylight again", self._names)
        if ended is not None:
            return ended
        try:
            _write_outputs(self._staging.path, job.result)
            leftover = self._staging.commit()
        except OSError as exc:
            self._staging.discard()
            return self._tell(job, 'ERROR', "The annual folder could not be written: %s" % exc)
        if leftover:
            self.report({'WARNING'}, "Files of the previous annual run stayed in %s" % leftover)
        seconds = (job.ended or job.started) - job.started if job.started else 0.0
        study_path = os.path.join(self._staging.final, "scene.json")
        annual_results.apply(context.scene, self._study, job.result["summary"], len(job.openings), seconds,
                             job.reused, study_path)
        context.scene.fenestra.display.false_colour = 'ANNUAL'
        annual = context.scene.fenestra.annual
        reused = " (light paths reused)" if job.reused else ""
        return self._tell(job, 'INFO', "Annual Daylight, %s: %s; %.1f s%s" % (
            counted(annual.openings, "opening"), summary_line(annual), seconds, reused))


classes = (FENESTRA_OT_annual_daylight,)
