"""What the workers run (in a Dask worker process): each shard's contributions, computed and held in
the worker's memory by key, its evaluations, and a solve's state per shard (record queries and open
region searches) answered through an actor; the progress of the shards running, read and cancelled
by the client."""

import numpy as np

from .. import _core, api

# On a worker process: scenes by their spec's key, the shards' native contributions by key, and
# the progress of the shards it is computing (read and cancelled by the client).
_SCENES = {}
_HELD = {}
_RUNNING = {}


class ShardLost(KeyError):
    """The worker no longer holds the shard (it restarted): the client recomputes it."""


def _scene_of(spec):
    scene = _SCENES.get(spec["key"])
    if scene is None:
        import warnings

        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # the client has shown the scene's warnings
            if "path" in spec:
                scene = api.load_scene(spec["path"])
            else:
                scene = api.scene_from_dict(spec["dict"], spec["base_dir"])
        for name, value in spec["render"].items():
            setattr(scene.render, name, value)
        scene.render.threads = _worker_threads()  # the worker's share of its machine (results do not depend on it)
        _SCENES[spec["key"]] = scene
    return scene


def _worker_threads():
    """Threads of the Dask worker this runs on (its share of the machine)."""
    from distributed import get_worker

    worker = get_worker()
    return max(1, int(getattr(getattr(worker, "state", None), "nthreads", 0) or worker.nthreads))


def _worker_address():
    from distributed import get_worker

    return get_worker().address


def _compute_shard(spec, key, begin, end):
    """Runs on a worker: the shard's contributions, kept there; returns its rows and T's entries."""
    scene = _scene_of(spec)
    c = _tracked(key, lambda progress: _core.compute_contributions(scene, progress, (begin, end)))
    _HELD[key] = c
    part = {
        "worker": _worker_address(), "begin": begin, "end": end,
        "E": np.array(c.E), "E_stderr": np.array(c.E_stderr), "A": np.array(c.A),
        "closed": np.array(c.closed), "closed_stderr": np.array(c.closed_stderr),
        "all_open": np.array(c.all_open), "all_open_stderr": np.array(c.all_open_stderr),
        "transport": _core.transport_entries(c),
        "seconds": c.seconds, "events": c.events, "dropped": c.dropped,
        "paths_per_sensor": c.paths_per_sensor,
    }
    _core.keep_records_only(c)  # the rows travel to the client; the worker keeps what evaluations read
    part["memory_bytes"] = c.memory_bytes
    return part


def _tracked(key, work):
    """work(progress) with its progress readable (and cancellable) under `key` meanwhile."""
    progress = _core.Progress()
    _RUNNING[key] = progress
    try:
        return work(progress)
    finally:
        _RUNNING.pop(key, None)


def _progress_of(keys):
    """Fraction done of those of `keys` running here."""
    return {key: _RUNNING[key].fraction for key in keys if key in _RUNNING}


def _cancel(keys):
    for key in keys:
        if key in _RUNNING:
            _RUNNING[key].cancel()


def _held(key):
    c = _HELD.get(key)
    if c is None:
        raise ShardLost(key)
    return c


def _evaluate_shard(key, sensors, masks):
    c = _held(key)
    out = [c.evaluate(np.asarray(m, dtype=np.uint8)) for m in masks]
    return np.array([v for v, _ in out]), np.array([s for _, s in out])


def _evaluate_openings_shard(key, sensors, spec, openings):
    return _held(key).evaluate_openings(_scene_of(spec), openings, None, sensors)


def _release_shards(keys):
    for key in keys:
        _HELD.pop(key, None)
        for held in [k for k in _SESSIONS if k[0] == key]:
            del _SESSIONS[held]
    if not _HELD:
        _SCENES.clear()  # no study left here: its scenes (meshes, skies) go too
    return len(_HELD)


# A solve's state on a worker, per shard: the shard's record queries (whose exact values keep each
# sensor's reference) and its open region searches, with the count of state-changing calls applied.
_SESSIONS = {}


class SessionLost(ShardLost):
    """The worker does not hold the solve's state for the shard as the client expects it."""


def _session_state(key, sensors, spec, session, applied):
    state = _SESSIONS.get((key, session))
    if state is None:
        if applied:  # calls were made that this worker has not seen: the shard moved here
            raise SessionLost(key)
        state = {"queries": _core.RecordQueries(_scene_of(spec), _held(key), tuple(sensors)), "searches": {},
                 "applied": 0}
        _SESSIONS[(key, session)] = state
    elif state["applied"] != applied:
        raise SessionLost(key)
    return state


def _apply(state, op, args, sensors):
    """One query of the solver on a shard's records (solve/record_queries.h); `sensors`: the
    shard's (begin, end)."""
    queries, searches = state["queries"], state["searches"]
    if op == "evaluate":
        return queries.evaluate(args[0])
    if op == "sampled":  # reads the references, leaves them
        return queries.sampled(args[0])
    if op == "climate_tally":
        return queries.climate_tally(*args)
    if op == "climate_flip_tallies":
        return queries.climate_flip_tallies(*args)
    if op == "climate_model_bytes":  # counts from the records before the model is built
        return queries.climate_model_bytes(*args)
    if op == "annual_parts":
        return queries.annual_parts(args[0])
    if op == "flip_effects":
        return _sparse(queries.flip_effects(args[0]))
    if op == "record_bytes":
        return queries.record_bytes
    if op == "sensors_reached":  # positions among the shard's sensors
        return queries.sensors_reached(args[0], args[1])
    if op == "try":
        return searches[args[0]].try_region(args[1])
    state["applied"] += 1  # the others change the state
    if op == "exact":
        return queries.exact(args[0])
    if op == "search":
        searches[args[0]] = queries.region_search(args[1])
        return searches[args[0]].values
    if op == "accept":
        return searches[args[0]].accept()
    if op == "close":
        searches.pop(args[0], None)
        return None
    if op == "climate_model":
        return queries.climate_model(*args)
    if op == "climate_settle":
        return queries.climate_settle(*args)
    if op == "climate_close":
        return queries.climate_close()
    raise ValueError("unknown record query %r" % (op,))


def _sparse(matrix):
    """A matrix as its shape and the entries whose bits are not all zero (a sensor's flip effects
    are zero for the elements its paths never met: most of a floor's): (shape, rows, columns, values)."""
    rows, columns = np.nonzero(np.ascontiguousarray(matrix).view(np.uint64))
    return matrix.shape, rows.astype(np.int32), columns.astype(np.int32), matrix[rows, columns]


def _dense(parts):
    """The matrices _sparse gave, stacked by rows, bit for bit."""
    out = np.zeros((sum(p[0][0] for p in parts), parts[0][0][1]))
    at = 0
    for shape, rows, columns, values in parts:
        out[at + rows, columns] = values
        at += shape[0]
    return out


def _session_call(key, sensors, spec, session, applied, op, args):
    return _apply(_session_state(key, sensors, spec, session, applied), op, args, sensors)


class _SessionActor:
    """Lives on a worker during a solve (a Dask actor): answers the solver's questions for the shards
    held there. An actor call goes to its worker directly, without the scheduler: a few
    milliseconds, against a task's ten or more."""

    def call(self, shards, spec, session, applied, op, args):
        out = {}
        for i, key, sensors in shards:
            try:
                out[i] = ("ok", _session_call(key, sensors, spec, session, applied, op, args))
            except ShardLost:
                out[i] = ("lost", None)
        return out


def _session_replay(key, sensors, spec, session, log, pending):
    """Brings a recomputed shard's solve state to where the client's log says: the same calls in the
    same order (an accepted region as its try, then accept), then each open search's last try."""
    _SESSIONS.pop((key, session), None)
    state = _session_state(key, sensors, spec, session, 0)
    for op, args in log:
        if op == "accept":
            state["searches"][args[0]].try_region(args[1])
        _apply(state, op, args, sensors)
    for search, rectangles in pending.items():
        state["searches"][search].try_region(rectangles)
    return state["applied"]


def _end_session(session):
    for held in [k for k in _SESSIONS if k[1] == session]:
        del _SESSIONS[held]


def _held_bytes():
    return sum(c.memory_bytes for c in _HELD.values())


def _evaluate_cut_shard(spec, key, openings, begin, end):
    scene = _scene_of(spec)
    return _tracked(key, lambda progress: _core.evaluate(scene, openings, progress, (begin, end)))


def _evaluate_cut_session(key, sensors, spec, openings, paths, stream=0):
    """The shard's sensors path-traced with the openings cut (the solver's checks with real cutters,
    and its cut searches on their own `stream`)."""
    return _core.evaluate(_scene_of(spec), openings, None, sensors, paths, stream)


def _annual_cut_session(key, sensors, spec, openings, paths):
    """The shard's sensors' year path-traced with the openings cut (the climate goals' check)."""
    return _core.annual_cut_coefficients(_scene_of(spec), openings, None, sensors, paths)


def _annual_parts_shard(key, sensors, spec, openings):
    """The shard's daylight coefficients and occupied hours' mean with the openings open, from its records."""
    return _held(key).annual_parts(_scene_of(spec), openings)


def _annual_cut_shard(spec, key, openings, begin, end, paths):
    """The shard's sensors' year path-traced with the openings cut, no records kept (annual --cutters)."""
    scene = _scene_of(spec)
    return _tracked(key, lambda progress: _core.annual_cut_coefficients(scene, openings, progress, (begin, end), paths))


def _sky_of(spec):
    """The scene's sky as `fenestra sky` writes it: the map and the summary's JSON text."""
    scene = _scene_of(spec)
    return _core.sky_map(scene), _core.sky_summary(scene)
