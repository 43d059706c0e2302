"""Digests of an exported study (export.Study): of all of it, to tell whether the scene a result was
computed for is still the scene in Blender, and of what its contributions depend on, to reuse
them when only the goals or the solver's settings changed. No bpy here."""

import hashlib
import json
import os

# The solver's settings that do not change the contributions (docs/scene-format.md): its paths and
# element size do, so they are not listed; an unknown key counts as one that does.
SOLVER_ONLY_KEYS = frozenset({
    "population", "generations", "seed", "time_budget_s", "shape_weights", "bound_weight", "coarse_to_fine",
    "elite", "constraints", "panel_constraints", "improve_iterations", "search_evaluations", "verify", "verify_paths",
    "refine_edges",
})
GOAL_KEYS = frozenset({"goals", "goal_units", "groups"})  # of the sensors section (groups: of climate goals)


def _weather_stamp(scene_dict):
    """A climate sky's weather file by size and time of change: the study names it by path only,
    and a file replaced under the same name brings other suns (and other contributions)."""
    weather = (scene_dict.get("sky") or {}).get("weather")
    if not weather:
        return b""
    try:
        info = os.stat(weather)
    except OSError:
        return b"missing"
    return ("%d:%d" % (info.st_size, info.st_mtime_ns)).encode()


def _digest(scene_dict, obj_text):
    h = hashlib.sha256(json.dumps(scene_dict, sort_keys=True, separators=(",", ":")).encode())
    h.update(b"\0")
    h.update(obj_text.encode())
    stamp = _weather_stamp(scene_dict)
    if stamp:
        h.update(b"\0" + stamp)
    return h.hexdigest()


def fingerprint(study):
    """Everything the study says: equal fingerprints, equal results."""
    return _digest(study.scene, study.obj_text)


def contributions_fingerprint(study):
    """What the contributions depend on: the study without its goals and the solver-only settings."""
    scene = {k: v for k, v in study.scene.items() if k != "goals"}
    if "sensors" in scene:
        scene["sensors"] = {k: v for k, v in scene["sensors"].items() if k not in GOAL_KEYS}
    if "solver" in scene:
        scene["solver"] = {k: v for k, v in scene["solver"].items() if k not in SOLVER_ONLY_KEYS}
    return _digest(scene, study.obj_text)
