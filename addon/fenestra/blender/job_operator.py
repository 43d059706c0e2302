"""The modal half of an operator that runs a study job on a worker thread (Solve Openings, Annual
Daylight): progress in the panels, Esc or Cancel to stop, the job stopped when Blender ends the
operator. The operator provides _prepare(context) (sets self._job and self._staging),
_finish(context, check_scene) and execute(context), and names its CANCELLED_MESSAGE."""
import bpy

from . import solve_job, solve_progress

PROGRESS_INTERVAL_S = 0.1  # the end of a job is seen within this


class JobOperator:
    CANCELLED_MESSAGE = "Cancelled"

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
