"""An Annual Daylight run of an exported climate study with given openings, on a worker thread (from
the panel) or on the caller's thread (scripts, background mode). It is a SolveJob in all but its
work: one job at a time, the same progress, Cancel and Esc, and the same guard against changes to
the scene (solve_guard.py). No bpy here."""

from . import solve_job


class AnnualJob(solve_job.SolveJob):
    """Reads `scene_path` (its sky "climate"), computes the contributions unless given (a solve's or
    a previous run's of the same study are reused: only the openings differ), then the year's hourly
    illuminance with `openings` open and its metrics (fenestra.annual)."""

    def __init__(self, scene_path, fingerprint, contributions_fingerprint, openings, contributions=None):
        super().__init__(scene_path, fingerprint, contributions_fingerprint, contributions)
        self.openings = openings
        self.phase = "reading the study and its weather file"
        self.weather_warnings = []

    def run(self):
        """Returns fenestra.annual()'s dict. Raises ValueError for a study that cannot be run (the
        cost model's refusals included) and fenestra.Cancelled after cancel(). Openings the path
        records cannot count (edges between the element grid's lines of a thick wall) are traced
        really cut instead, and the summary's note says so."""
        import time
        from ... import api as fenestra
        from ... import _core
        self.started = self.started or time.monotonic()
        scene = fenestra.load_scene(self.scene_path, progress=self.progress)
        self.weather_warnings = list(_core.sky_warnings(scene))
        try:
            _core.check_openings(scene, fenestra.openings_argument(self.openings))
        except ValueError:
            return self._run_cut(fenestra, scene)
        contributions = self.given_contributions
        if contributions is None or not contributions.has_annual:
            self.reused = False
            fenestra.check_cost(scene, "contributions")  # before anything large is allocated
            self.phase = "tracing the light paths"
            contributions = fenestra.contributions(scene, progress=self.progress)
            self.computed_contributions = contributions
        self.phase = "computing the hourly illuminance"
        return fenestra.annual(scene, self.openings, contributions=contributions, progress=self.progress)

    def _run_cut(self, fenestra, scene):
        self.reused = False
        fenestra.check_cost(scene, "annual_cutters")  # before anything large is allocated
        self.phase = "tracing the year with the openings really cut"
        result = fenestra.annual(scene, self.openings, cutters=True, progress=self.progress)
        result["summary"]["note"] = CUT_NOTE
        return result


# Said with the figures of a run traced with the openings cut.
CUT_NOTE = ("Traced with the openings really cut: an opening reaches where the light paths' records cannot count it "
            "(an edge between the element grid's lines of a thick wall, or beyond the domain's elements)")
