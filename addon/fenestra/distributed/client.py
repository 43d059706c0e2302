"""The study's side of a cluster (the client process): a scene split into shards of sensors, the
shards' work submitted to the workers (worker.py), gathered with progress, cancellation and lost
work recomputed, and assembled bit for bit as one process would: contributions
(DistributedContributions), evaluate and solve, with the memory checks before any work."""

import collections
import hashlib
import itertools
import json
import math
import os
import threading
import time
import warnings

import numpy as np

from .. import _core, api
from ..json_values import json_text
from .cluster import ClusterError
from .worker import (ShardLost, _annual_cut_session, _cancel, _compute_shard, _dense, _end_session,
                     _evaluate_cut_session, _evaluate_cut_shard, _evaluate_openings_shard, _evaluate_shard, _held_bytes,
                     _progress_of, _release_shards, _session_replay, _SessionActor)

def _spec(scene, base_dir):
    """What a worker needs to build the same scene: its file (or dict) and render settings, and the
    client's own copy of the scene."""
    if isinstance(scene, dict):
        local = api.scene_from_dict(scene, base_dir)
        # As plain JSON values (NumPy ones too): the spec is hashed as JSON and sent to the workers.
        spec = {"dict": json.loads(json_text(scene, "scene '<dict>'")), "base_dir": os.path.abspath(os.fspath(base_dir))}
    elif isinstance(scene, (str, os.PathLike)):
        local = api.load_scene(os.fspath(scene))
        spec = {"path": os.path.abspath(os.fspath(scene))}
    elif isinstance(scene, _core.Scene):
        if not os.path.isfile(scene.source):
            raise ValueError("scene %r was not read from a file the workers could read: pass the scene file's path, "
                             "or its dict with base_dir" % scene.source)
        local = scene
        spec = {"path": os.path.abspath(scene.source)}
    else:
        raise TypeError("scene must be a scene file's path, a dict in the scene-file format or a fenestra.Scene, "
                        "got %s" % type(scene).__name__)
    _set_render(spec, local)
    return spec, local


def _set_render(spec, local, **settings):
    """Sets the local scene's render `settings`, and the spec's render settings and key to match."""
    for name, value in settings.items():
        setattr(local.render, name, value)
    render = local.render
    spec["render"] = {"paths_per_sensor": render.paths_per_sensor, "seed": render.seed,
                      "max_bounces": render.max_bounces, "sampler": render.sampler}
    spec.pop("key", None)
    spec["key"] = hashlib.sha256(json.dumps(spec, sort_keys=True).encode()).hexdigest()[:16]


def _blocks(sensors, shards):
    """`shards` blocks of consecutive sensors, as even as can be."""
    if not isinstance(shards, int) or isinstance(shards, bool) or shards < 1:
        raise ValueError("shards must be a positive integer, got %r" % (shards,))
    shards = min(shards, sensors)
    edges = [round(i * sensors / shards) for i in range(shards + 1)]
    return list(zip(edges[:-1], edges[1:]))


_counter = itertools.count()


def _shard_keys(kind, spec, count):
    """Dask keys of one study's shards, unique in this client."""
    study = "fenestra-%s-%s-%d" % (kind, spec["key"], next(_counter))
    return ["%s-shard-%d" % (study, i) for i in range(count)]


def _gather(cluster, futures, keys, callback, what):
    """Results of `futures` (the tasks of shards `keys`) in order. About once a second,
    callback(fraction, what) with the fraction of the work done over all workers (returning False
    cancels). A cluster left without workers, or with a worker not heard from, for its timeout is a
    ClusterError (Cluster.check). On any exception (Ctrl-C included) the shards still running are
    cancelled on their workers, and their tasks on the cluster, before it propagates."""
    try:
        last = 0.0
        while True:
            if any(f.status == "error" for f in futures) or all(f.done() for f in futures):
                break  # gather returns the results or raises the shard's error
            cluster.check()
            now = time.monotonic()
            if callback is not None and now - last >= 1.0:
                last = now
                running = {}
                for fractions in cluster._run_on_heard(_progress_of, keys).values():
                    running.update(fractions)
                done = sum((1.0 if f.done() else running.get(k, 0.0)) for f, k in zip(futures, keys))
                if callback(done / len(futures), what) is False:
                    raise api.Cancelled("cancelled while %s" % what)
            time.sleep(0.02)
        return cluster.client.gather(futures)
    except BaseException:
        _cancel_shards(cluster, futures, keys)
        raise


def _cancel_shards(cluster, futures, keys):
    """Cancels the shards' tasks and their native work on the workers that answer (a cancelled
    task's native work stops only so); a closed cluster has none left."""
    if cluster.closed:
        return
    try:
        cluster.client.cancel(futures)
        cluster._run_on_heard(_cancel, keys)
    except Exception:
        pass


def _result(cluster, future, cancelled=None):
    """future.result(), checking the cluster meanwhile (Cluster.check) and, when given, cancelled()
    (True raises Cancelled)."""
    while True:
        try:
            return future.result(timeout=0.25)
        except TimeoutError:
            pass
        cluster.check()
        if cancelled is not None and cancelled():
            future.cancel()
            raise api.Cancelled("cancelled while asking the shards")


def _mib(n):
    return "%.0f MiB" % (n / 2**20) if n < 2**30 else "%.1f GiB" % (n / 2**30)


class ClimateShare(collections.namedtuple("ClimateShare", "model years sensors element_size")):
    """What each climate goal sensor adds to the worker holding it, by the cost model: `model` (bytes
    per goal sensor) its rows of the hourly model (the elements its light is estimated to meet,
    fenestra.climate_reach), `years` its part of the search's years; `sensors` the goal sensors
    (ascending); `element_size` the scene's (meters)."""

    @property
    def bytes(self):
        return self.model + self.years


def climate_share(scene):
    """For a solve with climate goals, a ClimateShare: each goal sensor's part of the cost model's
    `climate_model` (in proportion to the elements it is estimated to reach) and of
    `climate_population` (docs/cost.md). None without climate goals."""
    sensors = np.asarray(scene.climate_goal_sensors if scene.has_climate else [], dtype=np.int64)
    if not len(sensors):
        return None
    memory = api.estimate_cost(scene, "solve")["memory"]
    reach = api.climate_reach(scene)[sensors]
    model = memory.get("climate_model", 0.0) * reach / max(reach.sum(), 1.0)
    years = np.full(len(sensors), memory.get("climate_population", 0.0) / len(sensors))
    return ClimateShare(model, years, sensors, scene.element_size)


def _goal_bytes(climate, begin, end, part="bytes"):
    """The climate share (its `part`: bytes, model or years) of the goal sensors in [begin, end)."""
    return float(getattr(climate, part)[(climate.sensors >= begin) & (climate.sensors < end)].sum())


def _element_size_that_fits(element_size, model_bytes, other_bytes, limit):
    """The element size (meters, rounded up to 0.01 m) at which `model_bytes` (the hourly model,
    which goes as the elements a sensor's light meets: 1 / size^2 on a wall, with a fifth to spare
    for the cells at the panels' edges) and `other_bytes` fit in `limit`; None when the rest alone
    does not."""
    room = limit - other_bytes
    if model_bytes <= 0 or room <= 0:
        return None
    return math.ceil(100.0 * element_size * math.sqrt(1.2 * model_bytes / room)) / 100.0


def shard_needs(estimate, blocks, climate=None):
    """Bytes each shard's worker holds for it: its path records while they are assembled, its rows of
    E, E_stderr and A, the ray-tracing scene and tables every shard builds, and with `climate`
    (a ClimateShare) its goal sensors' part of the hourly model and of the search's years."""
    memory, sensors = estimate["memory"], estimate["sensors"]
    per_sensor = (memory["path_records"] + memory["path_records_assembly"] + memory["portal_selection"]
                  + memory["E"] + memory["E_stderr"] + memory["A"]) / sensors
    fixed = memory["ray_scene"] + memory["analysis"]
    return [fixed + per_sensor * (end - begin) + (_goal_bytes(climate, begin, end) if climate is not None else 0.0)
            for begin, end in blocks]


def solve_memory(scene, workers, shards=None):
    """What a solve of `scene` (a fenestra.Scene, its solver's paths per sensor applied) holds on a
    cluster of `workers` workers in `shards` shards (default one per worker), by the cost model, in
    bytes: "worker", the most a worker holds (its shards' records and, with climate goals, their
    part of the hourly model and of the search's years); "client", what this process holds
    (check_client_fits); "one_process", what the solve would hold in one process."""
    blocks = _blocks(scene.sensor_count, shards if shards is not None else workers)
    largest = max(shard_needs(api.estimate_cost(scene, "contributions"), blocks, climate_share(scene)))
    whole = api.estimate_cost(scene, "solve")
    client = sum(_client_parts(scene, whole).values())
    return {"worker": -(-len(blocks) // workers) * largest, "client": client, "one_process": whole["total_bytes"]}


def check_shards_fit(estimate, blocks, worker_limits, climate=None):
    """Raises ClusterError, before any work, when the largest shard would not fit in the smallest
    worker's memory limit (bytes; 0 or None: no limit), naming the workers of that memory, one
    shard each, that would hold the study, and with climate goals the element size that would fit
    (docs/distributed.md). `estimate`: fenestra.estimate_cost(scene, "contributions") of the whole
    study; `climate`: climate_share(scene) for a solve with climate goals. Returns the largest
    shard's bytes."""
    needs = shard_needs(estimate, blocks, climate)
    need = max(needs)
    largest = blocks[needs.index(need)]
    limits = {w: m for w, m in worker_limits.items() if m}
    if limits and need > min(limits.values()):
        worker = min(limits, key=limits.get)
        sensors = estimate["sensors"]
        goal = 0 if climate is None else int(np.count_nonzero((climate.sensors >= largest[0])
                                                             & (climate.sensors < largest[1])))
        what = ("a shard of %d sensors%s needs about %s (path records while they are assembled, its rows of E, "
                "E_stderr and A%s), more than worker %s's memory limit of %s"
                % (largest[1] - largest[0], " (%d of them climate goal sensors)" % goal if climate is not None else "",
                   _mib(need), "; its part of the climate goals' hourly model and of the search's years"
                   if climate is not None else "", worker, _mib(limits[worker])))
        fits = next((count for count in range(len(blocks) + 1, sensors + 1)
                     if max(shard_needs(estimate, _blocks(sensors, count), climate)) <= limits[worker]), None)
        size = None
        if climate is not None:
            model = _goal_bytes(climate, *largest, "model")
            size = _element_size_that_fits(climate.element_size, model, need - model, limits[worker])
        larger = " or a larger element_size (%.2f m or more)" % size if size is not None else ""
        if fits is None:
            raise ClusterError(what + ": even one sensor per shard does not fit; use fewer paths%s, %sor workers with "
                               "more memory" % (larger, "fewer sensors in the climate goals, "
                                                if climate is not None else ""))
        raise ClusterError(what + ": use at least %d workers of this memory, one shard each (shards=, --shards)%s, "
                                  "or fewer paths" % (fits, larger))
    return need


def check_climate_model_fits(model_bytes, shards, climate, held, worker_limits):
    """Raises ClusterError, before the climate goals' hourly model is built, when a worker's shards
    would not fit its memory limit with their parts of it. `model_bytes`: per shard, the bytes its
    part of the model will hold, counted from its records (exact); `shards`: (begin, end, worker)
    of each; `climate`: climate_share(scene) (the search's years per goal sensor are its
    population's part, the model's part is replaced by the count); `held`: per shard, the bytes its
    records hold; `worker_limits`: {worker: bytes, 0 or None: no limit}. Names the number of workers
    of that memory, one shard each, and the element size that would fit. Returns {worker: bytes}."""
    parts = {}  # worker -> [the model's rows, the search's years, the records]
    for counted, (begin, end, worker), records in zip(model_bytes, shards, held):
        part = parts.setdefault(worker, [0.0, 0.0, 0.0])
        part[0] += counted
        part[1] += _goal_bytes(climate, begin, end, "years")
        part[2] += records
    for worker, (model, years, records) in parts.items():
        limit = worker_limits.get(worker) or 0
        need = model + years + records
        if limit and need > limit:
            whole = sum(sum(p) for p in parts.values())
            workers = max(len(parts) + 1, math.ceil(whole / limit))
            size = _element_size_that_fits(climate.element_size, model, years + records, limit)
            raise ClusterError(
                "the climate goals' hourly model: worker %s would hold about %s (its shards' rows of the model %s, "
                "counted from their path records; the search's years %s; the records %s), more than its memory "
                "limit of %s: use at least %d workers of this memory, one shard each (shards=, --shards)%s, or fewer "
                "sensors in the climate goals" % (worker, _mib(need), _mib(model), _mib(years), _mib(records),
                                                   _mib(limit), workers,
                                                   " or a larger element_size (%.2f m or more)" % size
                                                   if size is not None else ""))
    return {worker: sum(p) for worker, p in parts.items()}


def contributions(scene, cluster, shards=None, base_dir=".", callback=None):
    """One pass of paths per sensor, sharded over `cluster` (a Cluster) in `shards` blocks of
    sensors (default: one per worker). Returns a DistributedContributions: the same E, E_stderr,
    A, T, closed and all-open values as fenestra.contributions, bit for bit; its path records stay
    on the workers. `scene`: a scene file's path, a dict in the scene-file format (relative paths
    against base_dir) or a fenestra.Scene read from a file (its render settings are used).
    callback(fraction, status) is called about once a second with the fraction done over all
    workers; returning False cancels (fenestra.Cancelled), stopping the shards on their workers."""
    spec, local = _spec(scene, base_dir)
    return _contributions(spec, local, cluster, shards, callback)


def _contributions(spec, local, cluster, shards, callback, climate=None):
    api._warn_if_dark(local)
    blocks = _blocks(local.sensor_count, shards if shards is not None else len(cluster.workers()))
    workers = cluster._scheduler_workers()
    check_shards_fit(api.estimate_cost(local, "contributions"), blocks,
                     {w: info.get("memory_limit", 0) for w, info in workers.items()}, climate)
    keys = _shard_keys("contributions", spec, len(blocks))
    futures = [cluster.client.submit(_compute_shard, spec, key, b, e, pure=False, key=key)
               for key, (b, e) in zip(keys, blocks)]
    parts = _gather(cluster, futures, keys, callback, "tracing contribution paths")
    del futures
    return DistributedContributions(cluster, spec, local, keys, parts)


class DistributedContributions:
    """Contributions whose path records stay in the workers' memory, shard by shard. E, E_stderr,
    A, T, closed, closed_stderr, all_open, all_open_stderr and paths_per_sensor are as for
    fenestra.Contributions (NumPy arrays); evaluate(), evaluate_batch() and evaluate_openings()
    map over the shards. close() (or a with block) frees the workers' records."""

    def __init__(self, cluster, spec, scene, keys, parts):
        self._cluster, self._spec, self.scene = cluster, spec, scene
        self._keys = keys
        self._shards = [dict(begin=p["begin"], end=p["end"], worker=p["worker"], all_open=p["all_open"]) for p in parts]
        stack = lambda name: np.concatenate([p[name] for p in parts])
        self.E, self.E_stderr, self.A = stack("E"), stack("E_stderr"), stack("A")
        self.closed, self.closed_stderr = stack("closed"), stack("closed_stderr")
        self.all_open, self.all_open_stderr = stack("all_open"), stack("all_open_stderr")
        self.paths_per_sensor = parts[0]["paths_per_sensor"]
        self.T = _core.transport_matrix_from_entries([p["transport"] for p in parts], scene.element_count,
                                                     self.paths_per_sensor)
        self.seconds = max(p["seconds"] for p in parts)
        self.events = sum(p["events"] for p in parts)
        self.dropped = {key: sum(p["dropped"][key] for p in parts) for key in ("non_finite", "truncated_conditions")}
        self.shard_memory_bytes = [p["memory_bytes"] for p in parts]
        self.memory_bytes = sum(self.shard_memory_bytes)
        self.recomputed_shards = 0
        self._closed = False

    @property
    def shards(self):
        """(begin, end, worker address) of every shard."""
        return [(s["begin"], s["end"], s["worker"]) for s in self._shards]

    def _map(self, function, *args, cancelled=None):
        """function(key, (begin, end), *args) on every shard's worker, results in shard order. A
        shard whose worker is gone (or restarted) is recomputed on another worker, then asked again.
        cancelled(): polled while waiting; True raises Cancelled."""
        self._check_open()
        client = self._cluster.client
        pending = {i: None for i in range(len(self._shards))}
        results = [None] * len(self._shards)
        for attempt in range(4):
            alive = set(self._cluster.workers())
            for i in list(pending):
                if self._shards[i]["worker"] not in alive:
                    self._recompute(i)
            futures = {i: client.submit(function, self._keys[i], (self._shards[i]["begin"], self._shards[i]["end"]),
                                        *args, workers=[self._shards[i]["worker"]], allow_other_workers=False,
                                        pure=False) for i in pending}
            try:
                lost = self._wait(futures, cancelled)
            except BaseException:
                client.cancel(list(futures.values()))
                raise
            for i, future in futures.items():
                if i in lost:
                    continue
                results[i] = future.result()
                del pending[i]
            if not pending:
                return results
            for i in pending:
                self._recompute(i)
        raise ClusterError("shards %s were lost four times in a row" % sorted(pending))

    def _wait(self, futures, cancelled=None):
        """Waits for the futures; returns the shards whose worker left or lost the shard."""
        finished = threading.Event()
        for future in futures.values():
            future.add_done_callback(lambda _: finished.set())
        lost, waiting = set(), dict(futures)
        while waiting:
            finished.wait(0.25)
            finished.clear()
            self._cluster.check()
            if cancelled is not None and cancelled():
                raise api.Cancelled("cancelled while asking the shards")
            alive = None
            for i, future in list(waiting.items()):
                if future.done():
                    if future.status == "error" and isinstance(future.exception(), ShardLost):
                        lost.add(i)
                    else:
                        future.result()  # raises the shard's error here
                    del waiting[i]
                    continue
                alive = alive if alive is not None else set(self._cluster.workers())
                if self._shards[i]["worker"] not in alive:
                    future.cancel()
                    lost.add(i)
                    del waiting[i]
        return lost

    def _recompute(self, i):
        s = self._shards[i]
        key = self._keys[i]
        future = self._cluster.client.submit(_compute_shard, self._spec, key, s["begin"], s["end"], pure=False)
        part = _result(self._cluster, future)
        if not np.array_equal(part["all_open"], s["all_open"]):
            raise ClusterError("shard %d (sensors %d..%d) came out different when recomputed" % (i, s["begin"], s["end"]))
        s["worker"] = part["worker"]
        self.recomputed_shards += 1

    def evaluate(self, open_mask):
        """Exact (value, stderr) per sensor with the elements where open_mask is true open."""
        mask = _core.check_open_masks(open_mask, self.E.shape[1])
        values, errors = self.evaluate_batch(mask[np.newaxis])
        return values[0], errors[0]

    def evaluate_batch(self, masks):
        """Exact values of several sets at once (one genetic generation): arrays (sets, sensors)
        of values and standard errors."""
        masks = _core.check_open_masks(masks, self.E.shape[1], batch=True)  # 0 and 1 only, as Contributions
        parts = self._map(_evaluate_shard, masks)
        return np.concatenate([p[0] for p in parts], axis=1), np.concatenate([p[1] for p in parts], axis=1)

    def evaluate_openings(self, openings):
        """Exact (value, stderr) per sensor with `openings` open (as Contributions.evaluate_openings)."""
        self._check_open()
        openings = api.openings_argument(openings)
        parts = self._map(_evaluate_openings_shard, self._spec, openings)
        return np.concatenate([p[0] for p in parts]), np.concatenate([p[1] for p in parts])

    def solve(self, progress=None, callback=None):
        """The opening solver on these contributions (fenestra.solve's result dict, the same bit for
        bit as one process gives). Its exact evaluations, flip effects, edge searches, cuts
        (thick walls' edges are searched with them) and, with climate goals, the hourly models' rows and
        the years of openings run on the shards; the linear and genetic stages in this process.
        callback(fraction, status) as for fenestra.solve; returning False cancels."""
        self._check_open()
        summary = self.as_contributions()
        progress = progress if progress is not None else _core.Progress()
        records = _ShardedRecords(self, progress)
        try:
            text = api._run(lambda p: _core.solve_with_records(self.scene, summary, records, p), progress, callback)
        finally:
            records.close()
        result = json.loads(text)
        for message in result.get("warnings", []):
            warnings.warn(message, RuntimeWarning, stacklevel=2)
        return result

    def as_contributions(self):
        """A fenestra.Contributions with these arrays and no path records (save(), solve's inputs)."""
        return _core.contributions_from_arrays(
            self.scene, self.paths_per_sensor, self.E, self.E_stderr, self.A, self.T, self.closed, self.closed_stderr,
            self.all_open, self.all_open_stderr, self.seconds, self.events, self.dropped["non_finite"],
            self.dropped["truncated_conditions"])

    def save(self, path):
        """Writes PATH.npz and PATH.json as fenestra.Contributions.save does."""
        return self.as_contributions().save(self.scene, os.fspath(path))

    def _check_open(self):
        """ClusterError when the records are gone: these contributions, or their cluster, were closed.
        The arrays (E, A, T, the values) stay, and so do save() and as_contributions()."""
        if self._closed:
            raise ClusterError("these contributions were closed (close(), or the end of their with block): their path "
                               "records on the workers were freed; compute them again (distributed.contributions) to "
                               "evaluate or solve (E, A, T, the values, save() and as_contributions() still work)")
        if self._cluster.closed:
            raise ClusterError("this study's cluster was closed (Cluster.close(), or the end of its with block): the "
                               "path records went with it; start a new Cluster and compute the contributions again "
                               "(E, A, T, the values, save() and as_contributions() still work)")

    def close(self):
        """Frees the shards' records on the workers; evaluations and solves are refused after."""
        keys, self._keys, self._closed = self._keys, [], True
        if keys and not self._cluster.closed:
            try:
                self._cluster._run_on_heard(_release_shards, keys)
            except Exception:  # the cluster is gone: nothing is held any more
                pass

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def __repr__(self):
        return "DistributedContributions(%d sensors x %d elements, %d paths per sensor, %d shards)" % (
            self.E.shape[0], self.E.shape[1], self.paths_per_sensor, len(self._shards))


class _ShardedRecords:
    """What the native solver asks of the path records (solve/record_queries.h), asked of every
    shard for its sensors and concatenated. The calls that change a shard's state (exact values keep
    each sensor's reference; region searches keep their region) are logged, so that a shard
    recomputed on another worker is brought to the same state before it answers again: the answers
    stay bit for bit those of one process."""

    def __init__(self, study, progress):
        self._study, self._progress = study, progress
        self._session = "fenestra-solve-%d-%d" % (os.getpid(), next(_counter))
        self._log = []        # (op, args) of every state-changing call, in order
        self._pending = {}    # open search -> the rectangles of its last try
        self._searches = itertools.count()
        self._actors = {}     # worker -> (its actor's future, the actor)
        self.calls = 0

    def _ask(self, op, *args):
        self.calls += 1
        changes = op not in (
            "evaluate", "sampled", "flip_effects", "record_bytes", "try", "annual_parts", "sensors_reached",
            "climate_flip_tallies", "climate_tally", "climate_model_bytes")
        parts = self._ask_shards(op, args)
        if changes:
            self._log.append((op, args))
        return parts

    def _ask_shards(self, op, args):
        """The answers of every shard, in shard order. Each worker is asked once for all its shards,
        through its _SessionActor (a direct call, without the scheduler). A shard whose worker is
        gone, or which its worker no longer holds, is recomputed elsewhere, brought to the solve's
        state, and asked again."""
        study = self._study
        results, pending = [None] * len(study._shards), set(range(len(study._shards)))
        for attempt in range(4):
            alive = set(study._cluster.workers())
            for i in sorted(pending):
                if study._shards[i]["worker"] not in alive:
                    self._recover(i)
            plan = {}
            for i in sorted(pending):
                s = study._shards[i]
                plan.setdefault(s["worker"], []).append((i, study._keys[i], (s["begin"], s["end"])))
            calls = {}
            for worker, shards in plan.items():
                actor = self._actor(worker)
                if actor is not None:  # else its worker left: its shards stay pending, recovered below
                    calls[worker] = actor.call(shards, study._spec, self._session, len(self._log), op, args)
            for worker, call in calls.items():
                answer = self._answer(worker, call)
                for i, (status, value) in (answer or {}).items():
                    if status == "ok":
                        results[i] = value
                        pending.discard(i)
            if not pending:
                return results
            for i in sorted(pending):
                self._recover(i)
        raise ClusterError("shards %s were lost four times in a row" % sorted(pending))

    def _answer(self, worker, call):
        """The actor call's answer; None when its worker died meanwhile (the call is abandoned).
        Polls cancellation (raising Cancelled) and the worker's presence while it waits."""
        while True:
            try:
                return call.result(timeout=0.25)
            except TimeoutError:
                pass
            except (OSError, ValueError) as exc:  # "Unable to contact Actor's worker", "Worker holding Actor was lost"
                if worker in self._study._cluster.workers() and "Actor" not in str(exc):
                    raise
                self._actors.pop(worker, None)
                return None
            self._study._cluster.check()
            if self._progress.cancelled:
                raise api.Cancelled("cancelled while asking the shards")
            if worker not in self._study._cluster.workers():
                self._actors.pop(worker, None)
                return None

    def _actor(self, worker):
        """The worker's _SessionActor, started on first use; None when the worker left before it
        started (a task bound to a worker that is gone would wait for ever)."""
        if worker not in self._actors:
            client = self._study._cluster.client
            future = client.submit(_SessionActor, workers=[worker], allow_other_workers=False, actor=True, pure=False)
            while True:
                try:
                    with client.as_current():  # the actor's handle finds its client so (this one is not Dask's default)
                        self._actors[worker] = (future, future.result(timeout=0.25))
                    break
                except TimeoutError:
                    pass
                self._study._cluster.check()
                if self._progress.cancelled or worker not in self._study._cluster.workers():
                    future.cancel()
                    if self._progress.cancelled:
                        raise api.Cancelled("cancelled while asking the shards")
                    return None
        return self._actors[worker][1]

    def _recover(self, i):
        self._study._recompute(i)
        self._replay(i)

    def _replay(self, i):
        s = self._study
        _result(s._cluster, s._cluster.client.submit(
            _session_replay, s._keys[i], (s._shards[i]["begin"], s._shards[i]["end"]), s._spec, self._session,
            self._log, dict(self._pending), workers=[s._shards[i]["worker"]], allow_other_workers=False,
            pure=False))

    @staticmethod
    def _pairs(parts):
        return np.concatenate([p[0] for p in parts]), np.concatenate([p[1] for p in parts])

    def exact(self, open_mask):
        return self._pairs(self._ask("exact", np.asarray(open_mask, dtype=np.uint8)))

    def sampled(self, open_mask):
        return self._pairs(self._ask("sampled", np.asarray(open_mask, dtype=np.uint8)))

    def evaluate(self, rectangles):
        return self._pairs(self._ask("evaluate", np.asarray(rectangles, dtype=np.float64)))

    def flip_effects(self, about):
        return _dense(self._ask("flip_effects", np.asarray(about, dtype=np.uint8)))

    def region_search(self, rectangles):
        search = next(self._searches)
        values = np.concatenate(self._ask("search", search, np.asarray(rectangles, dtype=np.float64)))
        return _ShardedSearch(self, search, values)

    def cut(self, openings, paths, stream=0):
        s = self._study
        return self._pairs(s._map(_evaluate_cut_session, s._spec, openings, paths, stream,
                                  cancelled=lambda: self._progress.cancelled))

    def record_bytes(self):
        return float(sum(self._ask("record_bytes")))

    def sensors_reached(self, before, after):
        """The study's sensors (ascending) a change of openings from the rectangles `before` to
        `after` can reach, from each shard's records: the sensors one process's cuts would trace
        (the others keep their values)."""
        parts = self._ask("sensors_reached", np.asarray(before, dtype=np.float64), np.asarray(after, dtype=np.float64))
        return np.concatenate([np.asarray(p, dtype=np.int64) + s["begin"]
                               for s, p in zip(self._study._shards, parts)] + [np.zeros(0, dtype=np.int64)])

    def climate_model(self, about, excluded, goals):
        """Each shard builds its part of the climate goals' hourly model from its records and keeps it
        (with the search's states) on its worker; the native search asks it through the returned
        object and adds the shards' tallies."""
        goals, excluded = np.asarray(goals, dtype=np.float64), np.asarray(excluded, dtype=np.uint8)
        self._check_climate_model_fits(excluded, goals)
        parts = self._ask("climate_model", np.asarray(about, dtype=np.uint8), excluded, goals)
        return _ClimateModelOnShards(self, float(sum(parts)))

    def _check_climate_model_fits(self, excluded, goals):
        """The shards count their parts of the model from their records (the same whatever the
        state) and the workers' limits are checked before any is built."""
        study = self._study
        climate = climate_share(study.scene)
        if climate is None:
            return
        limits = {w: info.get("memory_limit", 0) for w, info in study._cluster._scheduler_workers().items()}
        check_climate_model_fits(self._ask("climate_model_bytes", excluded, goals), study.shards, climate,
                                 study.shard_memory_bytes, limits)

    def climate_tally(self, open_mask, goals):
        """Per shard, the tally of the exact year of `open_mask` at its goal sensors."""
        return self._ask("climate_tally", np.asarray(open_mask, dtype=np.uint8), np.asarray(goals, dtype=np.float64))

    def annual_parts(self, rectangles):
        parts = self._ask("annual_parts", np.asarray(rectangles, dtype=np.float64))
        return tuple(np.concatenate([p[j] for p in parts]) for j in range(4))

    def annual_cut(self, openings, paths):
        s = self._study
        parts = s._map(_annual_cut_session, s._spec, openings, paths, cancelled=lambda: self._progress.cancelled)
        return tuple(np.concatenate([p[j] for p in parts]) for j in range(4)) + (parts[0][4],)

    def close(self):
        self._actors.clear()  # their futures released: the workers drop them
        try:
            self._study._cluster._run_on_heard(_end_session, self._session)
        except Exception:  # the cluster is gone: so is the state
            pass


class _ClimateModelOnShards:
    """The climate goals' hourly model held in the shards (solve/climate_model.h): the search's
    batches of states go to every shard, and each answers with its sensors' tallies. Settling
    changes the shards' state (their slots' years), so it is logged for a recomputed shard."""

    def __init__(self, records, model_bytes):
        self._records, self.model_bytes = records, model_bytes

    def settle(self, slots, bases, states):
        return self._records._ask("climate_settle", np.asarray(slots, dtype=np.int32),
                                  np.asarray(bases, dtype=np.int32), np.asarray(states, dtype=np.uint8))

    def flip_tallies(self, slot, elements):
        return self._records._ask("climate_flip_tallies", int(slot), np.asarray(elements, dtype=np.int32))

    def close(self):
        self._records._ask("climate_close")


class _ShardedSearch:
    """A region search on every shard (RegionSearch), for the native solver's edge searches."""

    def __init__(self, records, search, values):
        self._records, self._search, self.values = records, search, values

    def try_region(self, rectangles):
        rectangles = np.asarray(rectangles, dtype=np.float64)
        values = np.concatenate(self._records._ask("try", self._search, rectangles))
        self._records._pending[self._search] = rectangles
        return values

    def accept(self):
        self._records._ask("accept", self._search, self._records._pending.pop(self._search))

    def close(self):
        self._records._pending.pop(self._search, None)
        self._records._ask("close", self._search)


def solve(scene, cluster, shards=None, base_dir=".", callback=None, max_memory=None):
    """fenestra.solve on a cluster: the contributions sharded by sensors (as contributions()), then
    the solver on them (DistributedContributions.solve); the shards' records are freed afterwards.
    The result dict is the one fenestra.solve returns for the same scene and seed, bit for bit,
    except its timings. Refused (ValueError) before any work under a sky without light, or when
    what this process holds would not fit in max_memory (bytes or "8G"; default what this machine
    has available): see check_client_fits."""
    spec, local = _spec(scene, base_dir)
    dark = _core.dark_sky_warning(local)
    if dark:  # as one process refuses it, before any tracing
        raise ValueError("scene '%s': sky: %s; the goals cannot be met: choose a date and time interval with daylight"
                         % (local.source, dark))
    check_client_fits(local, max_memory)
    _core.require_goals(local)  # as one process refuses it, before any tracing
    if local.solver_paths > 0:  # as fenestra.solve traces them
        if local is scene:  # the caller's Scene keeps its settings
            local = api.load_scene(spec["path"])
            for name in spec["render"]:
                setattr(local.render, name, getattr(scene.render, name))
        _set_render(spec, local, paths_per_sensor=local.solver_paths)
    with _contributions(spec, local, cluster, shards, callback, climate_share(local)) as study:
        result = study.solve(callback=callback)
        # As fenestra.solve lists the tracing it did first.
        result["stages"].insert(0, {"name": "contributions", "seconds": study.seconds, "stopped_because": "done"})
        return result


# What the client of a solve on a cluster holds, by the cost model's names (docs/cost.md): the
# contributions' arrays (and T's margin while the shards' entries are summed) and the solver's own
# state. The records, their indexes and the tracing stay on the workers.
_CLIENT_PARTS = ("E", "E_stderr", "A", "T", "T_symmetrised", "solver_copies", "flip_effects_kept", "population",
                 "genetic_history", "result_history")
# The client process itself: Python, NumPy, fenestra and Dask's client, with a local cluster's
# scheduler (66 MiB measured once the cluster has started).
_CLIENT_PROCESS_BYTES = 80 << 20


def _client_parts(scene, estimate):
    """Bytes the client of a solve holds, by part: the cost model's _CLIENT_PARTS; the native copy
    of E, E_stderr, A and T the solver reads (the arrays stay with the study); the flip-effect
    matrix the shards' answers are assembled into (sensors x elements, 8 bytes each); the process."""
    held = {name: estimate["memory"].get(name, 0.0) for name in _CLIENT_PARTS}
    held["contributions_copy"] = sum(estimate["memory"].get(name, 0.0) for name in ("E", "E_stderr", "A", "T"))
    held["flip_effects"] = 8.0 * scene.sensor_count * scene.element_count
    held["process"] = float(_CLIENT_PROCESS_BYTES)
    return held


def check_client_fits(scene, max_memory=None):
    """Raises ValueError, naming the figures, when what the client of a solve on a cluster holds
    would not fit in max_memory (default: what this machine has available): E, E_stderr, A and T
    (with T's margin while it is summed, and the native copy the solver reads), the solver's
    copies, the flip effects it keeps, its population, the flip-effect matrix the shards' answers
    are assembled into (sensors x elements, 8 bytes each) and the process itself. The climate
    goals' hourly model stays in the shards (check_shards_fit, check_climate_model_fits)."""
    estimate = api.estimate_cost(scene, "solve", max_memory)
    held = _client_parts(scene, estimate)
    total = sum(held.values())
    if total > estimate["available_bytes"]:
        largest = max(held, key=held.get)
        raise ValueError("scene %r: the client of a solve on a cluster holds about %s (E, E_stderr, A, T and the "
                         "solver's state; the largest part, %s, %s), more than the %s %s here: use a larger "
                         "element_size or fewer sensors, or run the client on a machine with more memory"
                         % (scene.source, _mib(total), largest, _mib(held[largest]), _mib(estimate["available_bytes"]),
                            estimate["available_source"]))
    return total


def evaluate(scene, openings, cluster, shards=None, base_dir=".", callback=None):
    """fenestra.evaluate sharded by sensors: the scene path-traced with the openings really cut;
    (value, stderr) per sensor, bit for bit as one process gives them."""
    spec, local = _spec(scene, base_dir)
    openings = api.openings_argument(openings)
    blocks = _blocks(local.sensor_count, shards if shards is not None else len(cluster.workers()))
    keys = _shard_keys("evaluate", spec, len(blocks))
    futures = [cluster.client.submit(_evaluate_cut_shard, spec, key, openings, b, e, pure=False, key=key)
               for key, (b, e) in zip(keys, blocks)]
    parts = _gather(cluster, futures, keys, callback, "tracing the scene with its openings")
    return np.concatenate([p[0] for p in parts]), np.concatenate([p[1] for p in parts])


def worker_memory(cluster):
    """Bytes of shard records each worker holds, by address."""
    return cluster.client.run(_held_bytes)
