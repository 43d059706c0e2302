"""NumPy-level API over the native core (no bpy here)."""

import json
import os
import threading

import numpy as np

from ._core import Cancelled, Contributions, Progress, Scene, read_openings, write_image
from . import _core


def load_scene(path):
    """Reads a scene file (JSON + OBJ). Raises ValueError naming the file and the problem."""
    return Scene.load(os.fspath(path))


def scene_from_dict(scene, base_dir="."):
    """Builds a scene from a dict in the scene-file format; relative paths resolve against base_dir."""
    return Scene.from_json(json.dumps(scene), os.fspath(base_dir), "<dict>")


def openings_array(openings):
    """Rectangles as an (n, 4, 3) float array from an array, a list of corner lists, a list of
    {"corners": ...} dicts or an openings-file dict {"openings": [...]}."""
    if isinstance(openings, dict):
        openings = openings.get("openings", [])
    if isinstance(openings, np.ndarray):
        rects = openings
    else:
        rects = [o["corners"] if isinstance(o, dict) else o for o in openings]
    arr = np.asarray(rects, dtype=np.float64)
    if arr.size == 0:
        return np.zeros((0, 4, 3))
    if arr.ndim != 3 or arr.shape[1:] != (4, 3):
        raise ValueError("openings must be rectangles of four [x, y, z] corners, got shape %s" % (arr.shape,))
    return arr


def _run(work, progress, callback):
    """Runs `work(progress)` (which releases the GIL); calls callback(fraction, status) about ten
    times a second from this thread; a callback returning False cancels (raises Cancelled)."""
    progress = progress if progress is not None else Progress()
    if callback is None:
        return work(progress)
    result, error = {}, {}

    def target():
        try:
            result["value"] = work(progress)
        except BaseException as exc:  # re-raised in the caller's thread
            error["value"] = exc

    thread = threading.Thread(target=target, daemon=True)
    thread.start()
    try:
        while thread.is_alive():
            thread.join(0.1)
            if callback(progress.fraction, progress.status) is False:
                progress.cancel()
    except BaseException:
        progress.cancel()
        thread.join()
        raise
    if "value" in error:
        raise error["value"]
    return result["value"]


def contributions(scene, progress=None, callback=None):
    """One pass of paths per sensor: returns a Contributions with E, E_stderr, A, T, closed,
    all_open (and their standard errors) and evaluate(open_mask) for exact values of any set."""
    return _run(lambda p: _core.compute_contributions(scene, p), progress, callback)


def evaluate(scene, openings, progress=None, callback=None):
    """Path-traces the scene with the openings really cut. Returns (value, stderr) arrays."""
    rects = openings_array(openings)
    return _run(lambda p: _core.evaluate(scene, rects, p), progress, callback)


def sky(scene):
    """The scene's sky as the tracer sees it: a dict with
    - "map": (height, width, 3) float32 equirectangular map, linear sRGB in cd/m^2, top row the
      zenith, Blender's world convention (a daylight sky's interval mean, sky above the horizon and
      ground below, without the sun);
    - "horizontal_illuminance": {"sky", "sun", "total"} in lux (interval means);
    - "suns": one dict per time step with the sun up: "utc", "direction" (toward the sun, +Z up,
      +Y north), "zenith_deg", "azimuth_deg" (clockwise from north), "weight" (share of the
      interval) and "normal_illuminance" (lux at that instant);
    - for daylight skies also "steps", "steps_with_sun", "map" size and "build_seconds"."""
    summary = json.loads(_core.sky_summary(scene))
    summary["map_size"] = summary.pop("map", None)
    summary["map"] = _core.sky_map(scene)
    return summary


def write_sky(scene, path):
    """Writes the scene's sky map to path (.exr or .hdr, cd/m^2)."""
    _core.write_sky(scene, os.fspath(path))


def solve(scene, contributions=None, progress=None, callback=None):
    """Solves for the openings that meet the scene's goals (docs/solver.md). Computes the
    contributions first unless given. Returns the result as a dict, the same as `fenestra solve`
    writes: "openings" (rectangles, corners in meters, accepted by evaluate()), "open_elements",
    "sensors" (per sensor "goal" and "predicted" in lux, input order), "error" ("relative_rms", ...),
    "timings_s" and "genetic" (with the convergence history)."""
    return json.loads(_run(lambda p: _core.solve(scene, contributions, p), progress, callback))
