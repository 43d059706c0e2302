"""Studies past one machine: contributions and evaluation sharded by sensors over a Dask cluster.

Each sensor's paths are independent and seeded by the sensor's index in the scene, so a study
splits into blocks of consecutive sensors (shards). Every shard runs the native core on a Dask
worker and keeps its path records in that worker's memory; the client gathers the rows of E, A,
the closed and all-open values, and T's entries, and assembles them bit for bit as one process
would. Exact evaluations of any set of open elements map over the shards and concatenate.

    from fenestra import distributed
    with distributed.Cluster(workers=2) as cluster:             # or scheduler="tcp://host:8786"
        c = distributed.contributions("scene.json", cluster)
        values, stderr = c.evaluate(open_mask)
        batch, batch_stderr = c.evaluate_batch(masks)          # one genetic generation
        c.save("contributions.npz")

docs/distributed.md explains running a cluster on several machines.
"""

import hashlib
import itertools
import json
import logging
import os
import re
import sys
import time

import numpy as np

from . import _core, api

# What client and workers must agree on: the package version and the shard protocol.
PROTOCOL = 1
_ADDON_DIR = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


class ClusterError(RuntimeError):
    """The cluster cannot run the study: the scheduler is unreachable, a worker cannot import
    Fenestra or runs another version, or work was lost and could not be recomputed."""


def _version():
    from . import bl_info

    return ".".join(str(v) for v in bl_info["version"])


def _identity():
    """What a process runs: compared between the client and every worker."""
    return {"fenestra": _version(), "protocol": PROTOCOL, "python": "%d.%d" % sys.version_info[:2]}


def _worker_identity():
    return _identity()


# ---- the cluster -------------------------------------------------------------------------------


class Cluster:
    """A Dask client with workers able to run Fenestra: an existing cluster (`scheduler`, an
    address such as "tcp://host:8786") or a local one of `workers` processes (each with
    `threads_per_worker` threads; `memory_limit` per worker, Dask's format, e.g. "4GB").
    Raises ClusterError within `timeout` seconds when the scheduler cannot be reached, has no
    worker, or a worker cannot import Fenestra or runs another version of it."""

    def __init__(self, scheduler=None, workers=None, threads_per_worker=None, memory_limit="auto", timeout=10.0):
        try:
            import distributed
        except ImportError as exc:
            raise ClusterError("Dask distributed is not installed (Debian: python3-distributed): %s" % exc) from None
        if scheduler is not None and workers is not None:
            raise ValueError("give either scheduler (an existing cluster) or workers (a local one), not both")
        self._local = None
        if scheduler is not None:
            _check_address(scheduler)
            try:
                self.client = distributed.Client(scheduler, timeout=timeout, set_as_default=False)
            except (OSError, TimeoutError) as exc:
                raise ClusterError("cannot reach the Dask scheduler at %s within %g s: %s" % (scheduler, timeout, exc)) from None
        else:
            workers = (os.cpu_count() or 1) if workers is None else workers
            if not isinstance(workers, int) or isinstance(workers, bool) or not 1 <= workers <= 1024:
                raise ValueError("workers must be an integer from 1 to 1024, got %r" % (workers,))
            threads = threads_per_worker or max(1, (os.cpu_count() or 1) // workers)
            path = os.pathsep.join(p for p in (_ADDON_DIR, os.environ.get("PYTHONPATH")) if p)
            self._local = distributed.LocalCluster(
                n_workers=workers, threads_per_worker=threads, processes=True, protocol="tcp://",
                host="127.0.0.1", dashboard_address=":0", memory_limit=memory_limit,
                silence_logs=logging.ERROR, env={"PYTHONPATH": path})
            self.client = distributed.Client(self._local, set_as_default=False)
        try:
            self._check_workers(timeout)
        except BaseException:
            self.close()
            raise

    def _check_workers(self, timeout):
        try:
            self.client.wait_for_workers(1, timeout=timeout)
        except (TimeoutError, OSError):
            raise ClusterError("the Dask scheduler at %s has no worker after %g s: start some with "
                               "'dask worker %s' (docs/distributed.md)" % (self.address, timeout, self.address)) from None
        mine = _identity()
        for address in self.workers():
            try:
                theirs = self.client.run(_worker_identity, workers=[address])[address]
            except Exception as exc:  # the worker could not unpickle or run it: no Fenestra there
                raise ClusterError(
                    "worker %s cannot run Fenestra (%s: %s): install Fenestra's dependencies there and put its "
                    "addon directory on the worker's PYTHONPATH (docs/distributed.md)"
                    % (address, type(exc).__name__, exc)) from None
            if theirs != mine:
                raise ClusterError("worker %s runs %s, this client %s: use the same Fenestra build on every machine"
                                   % (address, _describe(theirs), _describe(mine)))

    @property
    def address(self):
        return self.client.scheduler.address

    def workers(self):
        """Addresses of the workers now connected."""
        return sorted(self.client.scheduler_info()["workers"])

    def close(self):
        try:
            self.client.close()
        finally:
            if self._local is not None:
                self._local.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()


_ADDRESS = re.compile(r"^(tcp|tls|ws|wss|ucx)://(\[[0-9A-Fa-f:.]+\]|[^:/\s\[\]]+):(\d{1,5})$")


def _check_address(scheduler):
    """A Dask address, SCHEME://HOST:PORT (checked here: Dask's own errors leave a client behind
    that hangs the interpreter's exit)."""
    match = _ADDRESS.match(scheduler) if isinstance(scheduler, str) else None
    if not match or not 1 <= int(match.group(3)) <= 65535:
        raise ValueError("scheduler address %r: expected SCHEME://HOST:PORT with SCHEME tcp, tls, ws, wss or ucx and "
                         "PORT 1 to 65535, e.g. 'tcp://host:8786'" % (scheduler,))


def _describe(identity):
    return "Fenestra %s (shard protocol %s) on Python %s" % (identity["fenestra"], identity["protocol"], identity["python"])


# ---- what the workers run ----------------------------------------------------------------------

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
    frm, to, value, sensors = _core.transport_entries(c)
    part = {
        "worker": _worker_address(), "begin": begin, "end": end,
        "E": np.array(c.E), "E_stderr": np.array(c.E_stderr), "A": np.array(c.A),
        "closed": np.array(c.closed), "closed_stderr": np.array(c.closed_stderr),
        "all_open": np.array(c.all_open), "all_open_stderr": np.array(c.all_open_stderr),
        "transport": (frm, to, value, sensors), "seconds": c.seconds, "events": c.events,
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
    if not _HELD:
        _SCENES.clear()  # no study left here: its scenes (meshes, skies) go too
    return len(_HELD)


def _held_bytes():
    return sum(c.memory_bytes for c in _HELD.values())


def _evaluate_cut_shard(spec, key, openings, begin, end):
    scene = _scene_of(spec)
    return _tracked(key, lambda progress: _core.evaluate(scene, openings, progress, (begin, end)))


# ---- the client side ---------------------------------------------------------------------------


def _spec(scene, base_dir):
    """What a worker needs to build the same scene: its file (or dict) and render settings, and the
    client's own copy of the scene."""
    if isinstance(scene, dict):
        local = api.scene_from_dict(scene, base_dir)
        spec = {"dict": scene, "base_dir": os.path.abspath(os.fspath(base_dir))}
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
    render = local.render
    spec["render"] = {"paths_per_sensor": render.paths_per_sensor, "seed": render.seed,
                      "max_bounces": render.max_bounces, "sampler": render.sampler}
    spec["key"] = hashlib.sha256(json.dumps(spec, sort_keys=True).encode()).hexdigest()[:16]
    return spec, local


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
    cancels). On any exception (Ctrl-C included) the shards still running are cancelled on their
    workers, and their tasks on the cluster, before it propagates."""
    try:
        last = 0.0
        while True:
            if any(f.status == "error" for f in futures) or all(f.done() for f in futures):
                break  # gather returns the results or raises the shard's error
            now = time.monotonic()
            if callback is not None and now - last >= 1.0:
                last = now
                running = {}
                for fractions in cluster.client.run(_progress_of, keys).values():
                    running.update(fractions)
                done = sum((1.0 if f.done() else running.get(k, 0.0)) for f, k in zip(futures, keys))
                if callback(done / len(futures), what) is False:
                    raise api.Cancelled("cancelled while %s" % what)
            time.sleep(0.02)
        return cluster.client.gather(futures)
    except BaseException:
        cluster.client.cancel(futures)
        try:
            cluster.client.run(_cancel, keys)  # a cancelled task's native work stops only so
        except Exception:
            pass
        raise


def _mib(n):
    return "%.0f MiB" % (n / 2**20) if n < 2**30 else "%.1f GiB" % (n / 2**30)


def check_shards_fit(estimate, blocks, worker_limits):
    """Raises ClusterError when the largest shard would not fit in the smallest worker's memory
    limit (bytes; 0 or None: no limit): its records while they are assembled, its rows of E,
    E_stderr and A, and the ray-tracing scene and tables every shard builds (docs/distributed.md).
    `estimate`: fenestra.estimate_cost(scene, "contributions") of the whole study."""
    memory, sensors = estimate["memory"], estimate["sensors"]
    per_sensor = (memory["path_records"] + memory["path_records_assembly"] + memory["portal_selection"]
                  + memory["E"] + memory["E_stderr"] + memory["A"]) / sensors
    fixed = memory["ray_scene"] + memory["analysis"]
    largest = max(e - b for b, e in blocks)
    need = fixed + per_sensor * largest
    limits = {w: m for w, m in worker_limits.items() if m}
    if limits and need > min(limits.values()):
        worker = min(limits, key=limits.get)
        most = int((limits[worker] - fixed) // per_sensor)  # sensors a shard may hold there
        what = ("a shard of %d sensors needs about %s (path records while they are assembled, its rows of E, E_stderr "
                "and A), more than worker %s's memory limit of %s" % (largest, _mib(need), worker, _mib(limits[worker])))
        if most < 1:
            raise ClusterError(what + ": even one sensor per shard does not fit; use fewer paths or workers with more "
                               "memory")
        raise ClusterError(what + ": use at least %d shards (shards=, --shards), more workers, or fewer paths"
                           % -(-sensors // most))
    return need


def contributions(scene, cluster, shards=None, base_dir=".", callback=None):
    """One pass of paths per sensor, sharded over `cluster` (a Cluster) in `shards` blocks of
    sensors (default: one per worker). Returns a DistributedContributions: the same E, E_stderr,
    A, T, closed and all-open values as fenestra.contributions, bit for bit; its path records stay
    on the workers. `scene`: a scene file's path, a dict in the scene-file format (relative paths
    against base_dir) or a fenestra.Scene read from a file (its render settings are used).
    callback(fraction, status) is called about once a second with the fraction done over all
    workers; returning False cancels (fenestra.Cancelled), stopping the shards on their workers."""
    spec, local = _spec(scene, base_dir)
    api._warn_if_dark(local)
    blocks = _blocks(local.sensor_count, shards if shards is not None else len(cluster.workers()))
    workers = cluster.client.scheduler_info()["workers"]
    check_shards_fit(api.estimate_cost(local, "contributions"), blocks,
                     {w: info.get("memory_limit", 0) for w, info in workers.items()})
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
        self.shard_memory_bytes = [p["memory_bytes"] for p in parts]
        self.memory_bytes = sum(self.shard_memory_bytes)
        self.recomputed_shards = 0

    @property
    def shards(self):
        """(begin, end, worker address) of every shard."""
        return [(s["begin"], s["end"], s["worker"]) for s in self._shards]

    def _map(self, function, *args):
        """function(key, (begin, end), *args) on every shard's worker, results in shard order. A
        shard whose worker is gone (or restarted) is recomputed on another worker, then asked again."""
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
                lost = self._wait(futures)
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

    def _wait(self, futures):
        """Waits for the futures; returns the shards whose worker left or lost the shard."""
        lost, waiting = set(), dict(futures)
        while waiting:
            time.sleep(0.01)
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
        part = future.result()
        if not np.array_equal(part["all_open"], s["all_open"]):
            raise ClusterError("shard %d (sensors %d..%d) came out different when recomputed" % (i, s["begin"], s["end"]))
        s["worker"] = part["worker"]
        self.recomputed_shards += 1

    def evaluate(self, open_mask):
        """Exact (value, stderr) per sensor with the elements where open_mask is true open."""
        values, errors = self.evaluate_batch([open_mask])
        return values[0], errors[0]

    def evaluate_batch(self, masks):
        """Exact values of several sets at once (one genetic generation): arrays (sets, sensors)
        of values and standard errors."""
        masks = np.asarray(masks, dtype=np.uint8)
        if masks.ndim != 2 or masks.shape[1] != self.E.shape[1]:
            raise ValueError("masks must have shape (sets, %d), got %s" % (self.E.shape[1], masks.shape))
        parts = self._map(_evaluate_shard, masks)
        return np.concatenate([p[0] for p in parts], axis=1), np.concatenate([p[1] for p in parts], axis=1)

    def evaluate_openings(self, openings):
        """Exact (value, stderr) per sensor with `openings` open (as Contributions.evaluate_openings)."""
        openings = api.openings_argument(openings)
        parts = self._map(_evaluate_openings_shard, self._spec, openings)
        return np.concatenate([p[0] for p in parts]), np.concatenate([p[1] for p in parts])

    def as_contributions(self):
        """A fenestra.Contributions with these arrays and no path records (save(), solve's inputs)."""
        return _core.contributions_from_arrays(
            self.scene, self.paths_per_sensor, self.E, self.E_stderr, self.A, self.T, self.closed, self.closed_stderr,
            self.all_open, self.all_open_stderr, self.seconds, self.events)

    def save(self, path):
        """Writes PATH.npz and PATH.json as fenestra.Contributions.save does."""
        return self.as_contributions().save(self.scene, os.fspath(path))

    def close(self):
        """Frees the shards' records on the workers."""
        keys, self._keys = self._keys, []
        if keys:
            try:
                self._cluster.client.run(_release_shards, keys)
            except Exception:  # the cluster is gone: nothing is held any more
                pass

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def __repr__(self):
        return "DistributedContributions(%d sensors x %d elements, %d paths per sensor, %d shards)" % (
            self.E.shape[0], self.E.shape[1], self.paths_per_sensor, len(self._shards))


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
