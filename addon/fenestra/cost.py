"""The cost model (docs/cost.md): memory and time a computation will need, estimated from the
scene's sizes and settings before anything large is allocated, and the `max_memory` argument
of the API's functions (no bpy here)."""

from . import _core
from . import arguments as _arg

MAX_MEMORY_BYTES = 2 ** 63  # the native side counts bytes in 64 bits


def memory_bytes(max_memory):
    """0 (the limit the system sets: MemAvailable, ulimit -v / -d, a cgroup's limit) for None,
    else bytes from an int or a string such as "8G", "512M", "1.5GB" or "2GiB"."""
    if max_memory is None:
        return 0
    if isinstance(max_memory, str):
        return _core.parse_memory_size(max_memory)
    if (isinstance(max_memory, bool) or not isinstance(max_memory, (int, float))
            or not 1 <= max_memory < MAX_MEMORY_BYTES):
        raise ValueError("max_memory expects a number of bytes from 1 to 2**63 - 1 or a size such as '8G', got %r"
                         % (max_memory,))
    return int(max_memory)


def available_memory():
    """What this process may still allocate: {"bytes", "source"} (the smallest of MemAvailable,
    the headroom under ulimit -v and ulimit -d, and a cgroup's memory limit)."""
    return _core.available_memory()


def estimate_cost(scene, command="solve", max_memory=None, paths=None):
    """The cost model's estimate for running `command` ("contributions", "evaluate", "solve",
    "solver" (solve with contributions given), "sky" or "annual_cutters" (annual(cutters=True)))
    on the scene, with `paths` per sensor instead of the scene's when given: a dict with
    "memory" (bytes per component: "E", "E_stderr", "A", "T", "path_records", ...),
    "memory_phase" ("" for what the result keeps, else the stage it exists in),
    "kept_bytes", "total_bytes" (the peak that must fit), "available_bytes" and "available_source",
    "seconds" (per stage, on the 2-core reference machine) and "seconds_limit",
    the sizes ("sensors", "elements", "triangles", "paths_per_sensor", "bytes_per_path"),
    "fits" and "problem" (the refusal message, or None)."""
    return _core.estimate_cost(*_scene_and_command(scene, command), memory_bytes(max_memory), _paths(paths))


def check_cost(scene, command="solve", max_memory=None, paths=None):
    """Raises ValueError, naming the figure and the setting to change, when `command` on the
    scene would not fit in memory (or max_memory) or a stage would exceed its time limit (with
    `paths` per sensor instead of the scene's when given)."""
    _core.check_cost(*_scene_and_command(scene, command), memory_bytes(max_memory), _paths(paths))


def climate_reach(scene):
    """Per sensor of the scene, the opening elements its rows of the climate goals' hourly model
    are estimated to hold before any path is traced: those it sees with the whole domain open, times
    1.25 for what only bounces reach, at most the domain's (docs/cost.md); 0 for the sensors no
    climate goal looks at. A NumPy array of floats."""
    import numpy as np

    _arg.instance(scene, _core.Scene, "scene", "a fenestra.Scene (from load_scene or scene_from_dict)")
    return np.asarray(_core.climate_reach(scene), dtype=np.float64)


def _paths(paths):
    """Paths per sensor for the native estimate: -1 for the scene's own."""
    return -1 if paths is None else _arg.integer(paths, "paths", 1, 1 << 30)


def _scene_and_command(scene, command):
    _arg.instance(scene, _core.Scene, "scene", "a fenestra.Scene (from load_scene or scene_from_dict)")
    return scene, _arg.text(command, "command")


def loading(max_memory=None, command="any"):
    """Context manager: scene loads inside it (on this thread) check against max_memory."""
    return _core.CostScope(memory_bytes(max_memory), command)
