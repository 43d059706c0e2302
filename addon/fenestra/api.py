"""NumPy-level API over the native core (no bpy here)."""

import json
import threading
import time
import warnings

import numpy as np

from ._core import Cancelled, Contributions, Progress, Scene
from . import _core
from . import arguments as _arg
from . import cost as _cost
from .cost import available_memory, check_cost, climate_reach, estimate_cost
from .json_values import json_text


def load_scene(path, progress=None, callback=None, max_memory=None):
    """Reads a scene file (JSON + OBJ). Raises ValueError naming the file and the problem.
    max_memory (bytes or "8G"; default what the system has available) bounds the cost checks
    made while reading (docs/cost.md). Runs like contributions(): on a worker thread without the
    GIL, a daylight sky's build reporting to `progress` / `callback` and stopping on cancel
    (raises Cancelled). A weather file's warnings (and a scene place more than 100 km from its
    station) are issued as RuntimeWarnings."""
    path = _arg.path(path)
    _check_run(progress, callback, max_memory)  # here, on the caller's thread

    def work(p):
        with _cost.loading(max_memory):  # on the thread that loads
            return Scene.load(path, p)

    return _warn_sky(_run(work, progress, callback))


def scene_from_dict(scene, base_dir=".", progress=None, callback=None, max_memory=None):
    """Builds a scene from a dict in the scene-file format; relative paths resolve against base_dir.
    progress and callback as for load_scene()."""
    _arg.instance(scene, dict, "scene", "a dict in the scene-file format")
    text, base_dir = json_text(scene, "scene '<dict>'"), _arg.path(base_dir, "base_dir")
    _check_run(progress, callback, max_memory)

    def work(p):
        with _cost.loading(max_memory):
            return Scene.from_json(text, base_dir, "<dict>", p)

    return _warn_sky(_run(work, progress, callback))


def _scene(scene):
    return _arg.instance(scene, Scene, "scene", "a fenestra.Scene (from load_scene or scene_from_dict)")


def _contributions(contributions):
    return _arg.optional_instance(contributions, Contributions, "contributions",
                                  "a fenestra.Contributions (from contributions(scene)) or None")


def _check_run(progress, callback, max_memory):
    """The arguments every long call shares, checked before any work."""
    _arg.optional_instance(progress, Progress, "progress", "a fenestra.Progress or None")
    _arg.callback(callback)
    _cost.memory_bytes(max_memory)


def read_openings(path):
    """The openings of an openings file (or a solve result): an (n, 4, 3) array of corners, or a
    list of dicts when any opening is given by "panel" and "parameter_rectangle"."""
    return _core.read_openings(_arg.path(path))


def write_image(path, image):
    """Writes a linear float image (height, width, channels), top row first, e.g. an environment
    map: .exr or .hdr, the formats that keep the values (others are refused, ValueError)."""
    _core.write_image(_arg.path(path), _arg.array(image, "image", "of shape (height, width, channels)", ndim=3))


def goal_error(goals, values, weights=None):
    """The solver's error measure of values against goals (lux; NaN or negative: no goal):
    {"relative_rms", "max_relative", "worst_sensor"}."""
    return _core.goal_error(_arg.array(goals, "goals", "(one per sensor)", ndim=1),
                            _arg.array(values, "values", "(one per sensor)", ndim=1),
                            None if weights is None else _arg.array(weights, "weights", "(one per sensor)", ndim=1))


def catalogues():
    """The built-in window catalogues (solver.constraints.catalogue by name): {name: {"walls":
    [(width, height), ...], "roofs": [...]}}, meters; walls' widths are horizontal."""
    return _core.catalogues()


def automatic_constraints(full_height=False, climate=False):
    """The solver.constraints keys that take an automatic value when not given: {key: (value,
    explanation)}, lengths in meters, areas in m^2. full_height: doors and floor-to-ceiling glazing
    allowed; climate: a study with climate goals (openings of at least 1 m^2)."""
    return _core.automatic_constraints(_arg.flag(full_height, "full_height"), _arg.flag(climate, "climate"))


def _warn_sky(scene):
    """A weather file's oddities and a scene place far from its station, as RuntimeWarnings."""
    for message in _core.sky_warnings(scene):
        warnings.warn(message, RuntimeWarning, stacklevel=3)
    return scene


def _check_finite(listed):
    """JSON has no NaN: a non-finite value of an opening is named here, as the native reader names
    the opening."""
    for i, o in enumerate(listed if isinstance(listed, (list, tuple)) else ()):
        if not isinstance(o, dict):
            continue
        rect = o.get("parameter_rectangle")
        for key, value in (rect.items() if isinstance(rect, dict) else ()):
            if isinstance(value, (float, np.floating)) and not np.isfinite(value):
                raise ValueError("opening %d: parameter_rectangle %s is %s, not a finite number of meters"
                                 % (i, key, value))
        try:
            corners = np.asarray(o.get("corners", []), dtype=np.float64)
        except (TypeError, ValueError):
            continue  # not numbers: the native reader names it
        for c, corner in enumerate(corners.reshape(-1, 3) if corners.size % 3 == 0 else ()):
            if not np.isfinite(corner).all():
                raise ValueError("opening %d, corner %d: has a non-finite coordinate, %s" % (i, c, list(corner)))


def openings_argument(openings):
    """What the native module takes for openings, from any form an openings file takes: an
    openings file's dict {"openings": [...]}, a list of openings (each {"corners": [...]},
    {"panel": ..., "parameter_rectangle": {...}}, both, or four corners), or an (n, 4, 3) array of
    corners. Returns an (n, 4, 3) array of corners, or, when the openings are an openings file's
    dict or any is a dict, the JSON text of an openings file: the native reader then checks its
    keys as it checks a file's, naming any it does not know. Every native call that takes openings
    converts them here."""
    if isinstance(openings, (str, bytes)):
        raise TypeError("openings: expected an openings file's dict, a list of openings or an (n, 4, 3) array of "
                        "corners, not a string (read a file with fenestra.read_openings)")
    if isinstance(openings, dict) and "openings" not in openings and {"corners", "panel", "parameter_rectangle"} & set(openings):
        raise ValueError("openings: a dict must be an openings file's {\"openings\": [...]} (docs/scene-format.md); "
                         "for one opening, pass a list holding it")
    listed = openings.get("openings", []) if isinstance(openings, dict) else openings
    if isinstance(listed, (str, bytes)) or not hasattr(listed, "__iter__"):
        raise TypeError("openings must be rectangles (an (n, 4, 3) array, a list of corner lists or of dicts), an "
                        "openings-file dict or read_openings(path), got %s" % _arg.shown(openings))
    if isinstance(openings, dict) or (not isinstance(listed, np.ndarray) and any(isinstance(o, dict) for o in listed)):
        if not isinstance(openings, dict):
            openings = {"openings": [o if isinstance(o, dict) else {"corners": o} for o in listed]}
        _check_finite(openings.get("openings"))
        return json_text(openings, "openings 'argument'")
    return openings_array(openings)


def openings_array(openings):
    """Rectangles as an (n, 4, 3) float array from an array, a list of corner lists, a list of
    {"corners": ...} dicts or an openings-file dict {"openings": [...]}."""
    if isinstance(openings, dict):
        openings = openings.get("openings", [])
    if isinstance(openings, np.ndarray):
        rects = openings
    elif isinstance(openings, (str, bytes)) or not hasattr(openings, "__iter__"):
        raise TypeError("openings must be rectangles (an (n, 4, 3) array, a list of corner lists or of dicts) or an "
                        "openings-file dict, got %s" % _arg.shown(openings))
    else:
        rects = [o.get("corners") if isinstance(o, dict) else o for o in openings]
    try:
        arr = np.asarray(rects, dtype=np.float64)
    except (TypeError, ValueError):
        raise ValueError("openings must be rectangles of four [x, y, z] corners (numbers), got %s"
                         % _arg.shown(openings)) from None
    if arr.size == 0:
        return np.zeros((0, 4, 3))
    if arr.ndim != 3 or arr.shape[1:] != (4, 3):
        raise ValueError("openings must be rectangles of four [x, y, z] corners, got shape %s" % (arr.shape,))
    return arr


def _wait_for(done):
    """Waits until the event `done` is set, through any KeyboardInterrupt meanwhile."""
    while True:
        try:
            while not done.is_set():
                time.sleep(0.02)
            return
        except BaseException:  # a further Ctrl-C: the work is already cancelled, keep waiting
            continue


def _run(work, progress, callback):
    """Runs `work(progress)` (native code that releases the GIL) on a worker thread, so that
    Ctrl-C reaches this thread at once; calls callback(fraction, status) about ten times a second
    from this thread; a callback returning False cancels (raises Cancelled).
    On any exception here (KeyboardInterrupt, or one from the callback) the work is cancelled and
    waited for, through further Ctrl-C, before the exception is raised: no native work is left
    running on a thread when the interpreter exits (that aborted the process).
    (Thread.join is not used to wait: in Python 3.11 an interrupted join can leave the thread
    marked as finished while it still runs.)

    Off the main thread, without a callback, the work runs on the caller's thread: Ctrl-C only
    reaches the main thread, and no Python wakes meanwhile (Blender's add-on solves on a thread of
    its own while a script may run operators on the main one: docs/blender.md, "Scripts and
    threads")."""
    progress = progress if progress is not None else Progress()
    if callback is None and threading.current_thread() is not threading.main_thread():
        return work(progress)
    outcome = {}
    done = threading.Event()

    def target():
        try:
            outcome["value"] = work(progress)
        except BaseException as exc:  # re-raised in the caller's thread
            outcome["error"] = exc
        finally:
            done.set()

    thread = threading.Thread(target=target, name="fenestra-worker", daemon=True)
    try:
        thread.start()
        while not done.wait(0.1):
            if callback is not None and callback(progress.fraction, progress.status) is False:
                progress.cancel()
    except BaseException:
        progress.cancel()
        if thread.ident is not None:  # started
            _wait_for(done)
        raise
    if "error" in outcome:
        raise outcome["error"]
    return outcome["value"]


def _warn_if_dark(scene):
    """A daylight sky with the sun never up gives every sensor 0: say so (solve() refuses it)."""
    message = _core.dark_sky_warning(scene)
    if message:
        warnings.warn(message, RuntimeWarning, stacklevel=3)


def check_setup(scene, command="solve"):
    """The setup checks for `command` ("solve", "contributions" or "evaluate"; docs/outputs.md,
    "Setup warnings"): setups that run but do not mean what they seem (goals all 0, sensors outdoors
    or facing down, a room open to the sky, domain panels seen from the side the solver does not
    take for the room). A list of dicts, one per problem found: "kind", "message", "sensors" (their
    indices), "checked" and "total" (sensors), and the kind's figures."""
    return _core.check_setup(_scene(scene), _arg.text(command, "command"))


def setup_messages(scene, command, strict=False):
    """The setup checks' messages for `command`; with strict, raises ValueError listing them when
    there are any (as --strict does)."""
    messages = [w["message"] for w in _core.check_setup(scene, command)]
    if strict and messages:
        raise ValueError("scene '%s': the setup checks found %d problem%s (strict); %s"
                         % (scene.source, len(messages), "" if len(messages) == 1 else "s", "; ".join(messages)))
    return messages


def _setup_warnings(scene, command, strict):
    """The setup checks before any work: raises ValueError listing them when strict, else issues
    each as a RuntimeWarning; returns their messages."""
    messages = setup_messages(scene, command, strict)
    for message in messages:
        warnings.warn(message, RuntimeWarning, stacklevel=3)
    return messages


def contributions(scene, progress=None, callback=None, max_memory=None, strict=False, checks=True):
    """One pass of paths per sensor: returns a Contributions with E, E_stderr, A, T, closed,
    all_open (and their standard errors) and evaluate(open_mask) for exact values of any set.
    Warns (RuntimeWarning) when the scene's daylight sky gives no light (the sun never up), and for
    each setup check's warning (check_setup(scene, "contributions"), also in the result's
    `warnings` and the summary its save() writes); strict=True makes those a ValueError before any
    work; checks=False skips them (the add-on runs them itself)."""
    _scene(scene)
    _check_run(progress, callback, max_memory)
    _arg.flag(strict, "strict")
    _arg.flag(checks, "checks")
    _warn_if_dark(scene)
    _cost.check_cost(scene, "contributions", max_memory)  # before any work (docs/cost.md)
    setup = _setup_warnings(scene, "contributions", strict) if checks else []
    result = _run(lambda p: _core.compute_contributions(scene, p), progress, callback)
    result.warnings = setup
    return result


def evaluate(scene, openings, progress=None, callback=None, max_memory=None):
    """Path-traces the scene with the openings really cut. Returns (value, stderr) arrays.
    Warns (RuntimeWarning) when the scene's daylight sky gives no light (the sun never up)."""
    _scene(scene)
    _check_run(progress, callback, max_memory)
    rects = openings_argument(openings)
    _warn_if_dark(scene)
    _cost.check_cost(scene, "evaluate", max_memory)
    return _run(lambda p: _core.evaluate(scene, rects, p), progress, callback)


def _annual_arguments(scene, openings, output, cutters, paths):
    """An annual study's arguments checked as annual() checks them, before any work: (output path or
    None, the openings as the native core takes them). Raises ValueError (TypeError for a flag
    that is not a bool) naming the argument."""
    _arg.flag(cutters, "cutters")
    out = None if output is None else _arg.path(output, "output")
    rects = openings_argument(openings)
    if not scene.has_climate:
        raise ValueError("annual needs a scene whose sky is \"climate\" (a weather file, docs/scene-format.md); "
                         "scene '%s' has another sky" % scene.source)
    if isinstance(paths, bool) or not isinstance(paths, (int, np.integer)) or paths < 0:
        raise ValueError("paths must be a whole number of paths per sensor, at least 0 (0: the scene's "
                         "render.paths_per_sensor), got %r" % (paths,))
    if paths and not cutters:
        raise ValueError("paths belongs to annual(cutters=True); the records' study has the contributions' paths "
                         "(render.paths_per_sensor)")
    return out, rects


def annual(scene, openings, contributions=None, output=None, progress=None, callback=None, max_memory=None,
           cutters=False, paths=0):
    """The annual study of a "climate" scene with the openings open (as for evaluate): every sensor's
    illuminance at every hour of the weather file's year and the climate-based metrics (docs/annual.md).

    Returns a dict: "illuminance" and "direct_sun" (sensors x hours, float32, lux; the direct part is
    the sun straight to the sensor, for ASE), "hour_month", "hour_day", "hour_clock" (local standard
    time, the instant each hour stands for), "occupied" (bool per hour) and "summary" (the metrics,
    as `fenestra annual` writes them to OUT.json). `contributions` (from contributions(scene)) are
    reused: a new set of openings then takes a fraction of a second. With `output`, also writes
    OUTPUT.npz and OUTPUT.json.

    With cutters=True the paths are traced with the openings really cut and no records are kept
    (`fenestra annual --cutters`): the ground truth of the records' study, and openings with edges
    anywhere in a thick wall. `paths` per sensor (0: the scene's render.paths_per_sensor); the
    contributions are not used."""
    _scene(scene)
    _contributions(contributions)
    _check_run(progress, callback, max_memory)
    out, rects = _annual_arguments(scene, openings, output, cutters, paths)
    if cutters:
        if contributions is not None:
            raise ValueError("annual(cutters=True) traces its own paths with the openings cut: "
                             "leave contributions out")
        _cost.check_cost(scene, "annual_cutters", max_memory, paths=int(paths) or None)  # no records are kept
        return _run(lambda p: _core.annual_with_cutters(scene, rects, int(paths), p, out or ""), progress, callback)
    _core.check_openings(scene, rects)  # before the long pass: openings the records cannot count
    if contributions is None:
        _cost.check_cost(scene, "contributions", max_memory)
        contributions = _run(lambda p: _core.compute_contributions(scene, p), progress, callback)
    result = _run(lambda p: contributions.annual_openings(scene, rects, p), progress, callback)
    if out is not None:
        contributions.save_annual(scene, rects, out)
    return result


def constraint_violations(scene, openings):
    """What the openings (as for evaluate) break of the scene's solver.constraints: a list of
    lines, empty when every opening is admissible."""
    return list(_core.constraint_violations(_scene(scene), openings_argument(openings)))


def sky(scene, max_memory=None):
    """The scene's sky as the tracer sees it: a dict with
    - "map": (height, width, 3) float32 equirectangular map, linear sRGB in cd/m^2, top row the
      zenith, Blender's world convention (a daylight sky's interval mean, sky above the horizon and
      ground below, without the sun);
    - "horizontal_illuminance": {"sky", "sun", "total"} in lux (interval means);
    - "suns": one dict per time step with the sun up: "utc", "direction" (toward the sun, +Z up,
      +Y north), "zenith_deg", "azimuth_deg" (clockwise from north), "weight" (share of the
      interval) and "normal_illuminance" (lux at that instant);
    - for daylight skies also "steps", "steps_with_sun", "map" size and "build_seconds"."""
    _scene(scene)
    _cost.check_cost(scene, "sky", max_memory)
    summary = json.loads(_core.sky_summary(scene))
    summary["map_size"] = summary.pop("map", None)
    summary["map"] = _core.sky_map(scene)
    return summary


def write_sky(scene, path, max_memory=None):
    """Writes the scene's sky map to path (.exr or .hdr, cd/m^2; other formats cannot keep the
    values and are refused with ValueError, before any work)."""
    _scene(scene)
    path = _arg.path(path)
    _cost.check_cost(scene, "sky", max_memory)
    _core.write_sky(scene, path)


def solve(scene, contributions=None, progress=None, callback=None, max_memory=None, strict=False, checks=True):
    """Solves for the openings that meet the scene's goals (docs/solver.md). Computes the
    contributions first unless given. Returns the result as a dict, the same as `fenestra solve`
    writes: "openings" (rectangles, corners in meters, accepted by evaluate()), "open_elements",
    "sensors" (per sensor "goal" and "predicted" in lux, input order), "error" ("relative_rms", ...),
    "timings_s", "stages" (each stage's "name", "seconds" and "stopped_because", in order; see
    docs/solver.md, "Stages"), "genetic" (with the convergence history), with climate goals (a
    "climate" sky and goals.climate: sDA, ASE, EN 17037, UDI, annual mean) "climate" (each goal's figure from
    the path records and with real cutters, "unmet", glazing area in m^2, per-sensor DA; see
    docs/solver.md, "Climate goals") and "warnings" (each also issued as a RuntimeWarning: too
    few paths for the elements, a prediction the real-cutter check contradicts, a climate goal
    not met; first the setup checks', check_setup(scene, "solve"), issued before any work).
    Refused (ValueError) before any work when no sensor has a goal and there is no climate goal,
    with strict=True when a setup check warns (checks=False skips them: the add-on runs them
    itself), and when the cost model (docs/cost.md) says it will not fit in max_memory (bytes or
    "8G"; default what the system has available) or a stage would exceed its time limit."""
    _scene(scene)
    _contributions(contributions)
    _check_run(progress, callback, max_memory)
    _arg.flag(strict, "strict")
    _arg.flag(checks, "checks")
    _cost.check_cost(scene, "solve" if contributions is None else "solver", max_memory)
    _core.require_goals(scene)
    setup = _setup_warnings(scene, "solve", strict) if checks else []
    result = json.loads(_run(lambda p: _core.solve(scene, contributions, p), progress, callback))
    for message in result.get("warnings", []):  # also in result["warnings"]
        warnings.warn(message, RuntimeWarning, stacklevel=2)
    result["warnings"] = setup + result.get("warnings", [])
    return result
