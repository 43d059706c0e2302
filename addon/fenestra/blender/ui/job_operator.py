"""An operator that runs a study job (Solve Openings, Annual Daylight): on a worker thread from the
panel (the modal half: progress in the panels, Esc or Cancel to stop, the job stopped when Blender
ends the operator), or on the caller's thread from scripts and in background mode (execute). The
operator provides _prepare(context) (sets self._job, self._staging and self._study) and
_finish(context, check_scene), which starts with _ended_without_result and ends with _tell, and names
its CANCELLED_MESSAGE and the messages of poll() (RUNNING_MESSAGE, MODE_MESSAGE)."""
import time

import bpy

from ..com import contributions_cache, native_messages, solve_job, user_messages
from . import long_message, solve_guard, solve_progress

PROGRESS_INTERVAL_S = 0.1  # the end of a job is seen within this


class JobOperator:
    CANCELLED_MESSAGE = "Cancelled"
    RUNNING_MESSAGE = "A job is running"  # poll() refuses while one runs (one job at a time)
    MODE_MESSAGE = "Needs Object Mode"

    _timer = None
    _job = None

    @classmethod
    def poll(cls, context):
        if solve_job.running() is not None:
            cls.poll_message_set(cls.RUNNING_MESSAGE)
            return False
        if context.mode != 'OBJECT':
            cls.poll_message_set(cls.MODE_MESSAGE)
            return False
        return True

    def execute(self, context):
        """Runs the job on this thread (scripts and background mode)."""
        if not self._prepare(context):
            return {'CANCELLED'}
        try:
            self._job.result = self._job.run()
        except Exception as exc:  # the native message, for the user
            self._job.error = exc
        self._job.ended = time.monotonic()
        return self._finish(context, check_scene=False)

    def _ended_without_result(self, context, check_scene, changed_message, openings=()):
        """The start of _finish: keeps the contributions the job computed (valid for what they were
        computed from, whatever followed); then, for a job that failed, was cancelled or whose scene
        changed meanwhile (`changed_message`), discards the staging folder, reports why and returns
        what the operator returns. None when there is a result to apply. `openings` names the
        cutters in the core's messages."""
        job = self._job
        if job.computed_contributions is not None:
            contributions_cache.keep(job.contributions_fingerprint, job.computed_contributions)
        if job.error is not None:
            self._staging.discard()
            if job.cancelled:  # the guard's reasons speak of a solve: said as this operator's
                reason = (job.cancel_reason or "Solve cancelled").replace("Solve cancelled", self.CANCELLED_MESSAGE, 1)
                return self._tell(job, 'WARNING', reason)
            return self._tell(job, 'ERROR', user_messages.for_user(
                native_messages.for_the_panel(str(job.error), job.scene_path), self._study, openings))
        if check_scene and solve_guard.current_fingerprint(context) != job.fingerprint:
            self._staging.discard()
            return self._tell(job, 'WARNING', changed_message)
        return None

    def _tell(self, job, kind, message):
        """Reports the job's outcome, keeps it on the job and lets the job's memory go."""
        if kind == 'ERROR':
            long_message.report_error(self, message)
        else:
            self.report({kind}, message)
        job.outcome = message
        job.release()
        return {'FINISHED'} if kind == 'INFO' else {'CANCELLED'}

    def invoke(self, context, event):
        """Runs on a worker thread; the panels show progress, Esc or Cancel stops it, and a change
        to the study meanwhile stops it too (solve_guard.py)."""
        if bpy.app.background:
            return self.execute(context)
        if not self._prepare(context):
            return {'CANCELLED'}
        self._job.start()
        wm = context.window_manager
        self._timer = wm.event_timer_add(PROGRESS_INTERVAL_S, window=context.window)
        wm.modal_handler_add(self)
        self._display = solve_progress.Display()
        self._display.update(context, self._job)
        return {'RUNNING_MODAL'}

    def _end(self, context):
        context.window_manager.event_timer_remove(self._timer)
        self._display.clear(context)

    def modal(self, context, event):
        job = self._job
        if job.done.is_set():
            self._end(context)
            return self._finish(context, check_scene=True)
        if event.type == 'ESC' and event.value == 'PRESS':
            job.cancel(self.CANCELLED_MESSAGE)
            return {'RUNNING_MODAL'}
        if event.type == 'TIMER':
            self._display.update(context, job)
        return {'PASS_THROUGH'}

    def cancel(self, context):
        """Blender ends the operator (a file is loaded, the window closes): the job stops too."""
        self._job.cancel(self.CANCELLED_MESSAGE)
        self._job.wait(solve_job.CANCEL_WAIT_AT_EXIT_S)
        self._job.release()
        self._staging.discard()
        self._end(context)
