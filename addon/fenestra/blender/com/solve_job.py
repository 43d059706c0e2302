"""A solve of an exported study, from reading its scene file to the result, on a worker thread (from
the panel) or on the caller's thread (scripts, background mode). No bpy here: the worker never
touches Blender's data, and Blender's side (operators.py) decides what to do with the outcome.

At most one job runs at a time; `running()` is it. Every stage stops soon after cancel(): the
native core polls its Progress (docs/blender.md, "Cancelling")."""

import atexit
import threading
import time

from . import stage_words

_current = None  # the job last started on a worker thread

CANCEL_WAIT_AT_EXIT_S = 5.0


class SolveJob:
    """Reads `scene_path`, checks the cost model, computes the contributions unless given, solves.

    `fingerprint` and `contributions_fingerprint` identify the exported study
    (study_fingerprint.py); Blender's side compares them with the scene before using the result."""

    def __init__(self, scene_path, fingerprint, contributions_fingerprint, contributions=None):
        from ... import api as fenestra
        self.scene_path = scene_path
        self.fingerprint = fingerprint
        self.contributions_fingerprint = contributions_fingerprint
        self.given_contributions = contributions
        self.reused = contributions is not None
        self.computed_contributions = None  # by this job, for the next solve to reuse
        self.progress = fenestra.Progress()
        self.phase = "reading the study"
        self._words = stage_words.StageWords()
        self._words_lock = threading.Lock()
        self.result = None
        self.error = None
        self.cancel_reason = None
        self.outcome = None  # what Blender's side made of it, in the words it reported
        self.started = self.cancel_requested = self.ended = None  # time.monotonic()
        self.done = threading.Event()
        self._thread = None

    # -- the work (any thread) ------------------------------------------------------------------

    def run(self):
        """Solves on this thread; returns the result dict (as fenestra.solve). Raises ValueError
        for a study that cannot be solved (the cost model's refusals included) and
        fenestra.Cancelled after cancel()."""
        from ... import api as fenestra
        self.started = self.started or time.monotonic()
        scene = fenestra.load_scene(self.scene_path, progress=self.progress)
        contributions = self.given_contributions
        if contributions is None:
            # Before anything large is allocated: what would not fit is refused here (docs/cost.md).
            fenestra.check_cost(scene, "solve")
            self.phase = "computing the contributions"
            # checks=False: the operator ran the setup checks and showed them in the user's words.
            contributions = fenestra.contributions(scene, progress=self.progress, checks=False)
            self.computed_contributions = contributions
        self.phase = "solving"
        result = fenestra.solve(scene, contributions=contributions, progress=self.progress, checks=False)
        if self.computed_contributions is not None:  # as `fenestra solve` reports a solve from scratch
            timings = result.setdefault("timings_s", {})
            timings["contributions"] = contributions.seconds
            timings["total"] = timings.get("total", 0.0) + contributions.seconds
            result.setdefault("stages", []).insert(
                0, {"name": "contributions", "seconds": contributions.seconds, "stopped_because": "done"})
        return result

    def _work(self):
        try:
            self.result = self.run()
        except BaseException as exc:  # handed to Blender's side
            self.error = exc
        finally:
            self.ended = time.monotonic()
            self.done.set()

    # -- control (Blender's main thread) ---------------------------------------------------------

    def start(self):
        """Runs on a worker thread; refused while another job runs."""
        global _current
        if running() is not None:
            raise RuntimeError("A solve is already running")
        _current = self
        self.started = time.monotonic()
        self._thread = threading.Thread(target=self._work, name="fenestra-solve", daemon=True)
        self._thread.start()

    def cancel(self, reason="Solve cancelled"):
        """Asks every stage to stop; the first reason given is the one reported."""
        if self.cancel_reason is None:
            self.cancel_reason, self.cancel_requested = reason, time.monotonic()
        self.progress.cancel()

    @property
    def cancelled(self):
        from ... import api as fenestra
        return isinstance(self.error, fenestra.Cancelled)

    def _see(self):
        status = self.progress.status
        if not status:
            return None
        with self._words_lock:
            return self._words.see(status)

    @property
    def status(self):
        """What it does now, in words: the native stage (stage_words.py), else the job's own phase."""
        return self._see() or self.phase

    @property
    def fraction(self):
        return min(max(self.progress.fraction, 0.0), 1.0)

    def wait(self, timeout=None):
        return self.done.wait(timeout)

    def release(self):
        """Drops what it holds in memory (the contributions, the result): an ended job stays
        reachable as the last one, and its contributions must not outlive the kept ones."""
        self.given_contributions = self.computed_contributions = self.result = None


def running():
    """The job running on a worker thread, or None."""
    job = _current
    return job if job is not None and not job.done.is_set() else None


def last():
    """The job last started on a worker thread (running or ended), or None."""
    return _current


def cancel_running(reason):
    """Cancels the running job, if any; returns it."""
    job = running()
    if job is not None:
        job.cancel(reason)
    return job


@atexit.register
def _stop_at_exit():
    # Native work left running on a thread while the interpreter shuts down aborts the process.
    job = cancel_running("Blender is quitting")
    if job is not None:
        job.wait(CANCEL_WAIT_AT_EXIT_S)
