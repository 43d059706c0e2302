"""Studies past one machine: contributions and evaluation sharded by sensors over a Dask cluster.

Each sensor's paths are independent and seeded by the sensor's index in the scene, so a study
splits into blocks of consecutive sensors (shards). Every shard runs the native core on a Dask
worker and keeps its path records in that worker's memory; the client gathers the rows of E, A,
the closed and all-open values, and T's entries, and assembles them bit for bit as one process
would. Exact evaluations of any set of open elements map over the shards and concatenate.

    from fenestra import distributed
    if __name__ == "__main__":  # a local cluster's workers are new processes that import the script
        with distributed.Cluster(workers=2) as cluster:         # or scheduler="tcp://host:8786"
            c = distributed.contributions("scene.json", cluster)
            values, stderr = c.evaluate(open_mask)             # bools, or 0 and 1
            batch, batch_stderr = c.evaluate_batch(masks)      # one genetic generation
            c.save("contributions.npz")

docs/distributed.md explains running a cluster on several machines.
"""

import hashlib
import ipaddress
import itertools
import json
import logging
import os
import re
import sys
import threading
import time
import warnings

import numpy as np

from . import _core, api
from .json_values import json_text

# What client and workers must agree on: the package version and the shard protocol.
PROTOCOL = 3
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
    address "tcp://HOST:PORT") or a local one of `workers` processes (each with
    `threads_per_worker` threads; `memory_limit` per worker: "auto", None for no limit, bytes, or
    Dask's format, e.g. "4GB"). Raises ClusterError within `timeout` seconds (a finite number
    above 0, at most a day) when the scheduler cannot be reached, has no worker, or a worker
    cannot import Fenestra or runs another version of it; while a study waits on the cluster, when
    it has had no worker, or a worker has not been heard from, for `timeout` seconds (check())."""

    def __init__(self, scheduler=None, workers=None, threads_per_worker=None, memory_limit="auto", timeout=10.0):
        timeout = _check_timeout(timeout)
        if scheduler is not None and workers is not None:
            raise ValueError("give either scheduler (an existing cluster) or workers (a local one), not both")
        if scheduler is not None:
            _check_address(scheduler)
            if threads_per_worker is not None or not (isinstance(memory_limit, str) and memory_limit == "auto"):
                raise ValueError("threads_per_worker and memory_limit set a local cluster's workers; a running "
                                 "cluster's are set where its workers start ('dask worker --nthreads N --memory-limit "
                                 "SIZE')")
        else:
            workers = (os.cpu_count() or 1) if workers is None else workers
            if not _is_integer(workers) or not 1 <= workers <= 1024:
                raise ValueError("workers must be an integer from 1 to 1024, got %s" % _shown(workers))
            if threads_per_worker is not None and (not _is_integer(threads_per_worker)
                                                   or not 1 <= threads_per_worker <= 4096):
                raise ValueError("threads_per_worker must be None (the cores shared out) or an integer from 1 to "
                                 "4096, got %s" % _shown(threads_per_worker))
            memory_limit = _check_memory_limit(memory_limit)
        try:
            import distributed
        except ImportError as exc:
            raise ClusterError("Dask distributed is not installed (Debian: python3-distributed): %s" % exc) from None
        self.timeout = timeout
        self._local, self._closed = None, False
        self._checked, self._no_worker_since, self._heard = 0.0, None, {}
        if scheduler is not None:
            try:
                self._client = distributed.Client(scheduler, timeout=timeout, set_as_default=False)
            except (OSError, TimeoutError) as exc:
                raise ClusterError("cannot reach the Dask scheduler at %s within %g s: %s" % (scheduler, timeout, exc)) from None
        else:
            threads = threads_per_worker or max(1, (os.cpu_count() or 1) // workers)
            path = os.pathsep.join(p for p in (_ADDON_DIR, os.environ.get("PYTHONPATH")) if p)
            self._local = distributed.LocalCluster(
                n_workers=workers, threads_per_worker=threads, processes=True, protocol="tcp://",
                host="127.0.0.1", dashboard_address=":0", memory_limit=memory_limit,
                silence_logs=logging.ERROR, env={"PYTHONPATH": path})
            self._client = distributed.Client(self._local, set_as_default=False)
        try:
            self._check_workers(timeout)
        except BaseException:
            self.close()
            raise

    @property
    def client(self):
        """The Dask client; ClusterError once the cluster is closed."""
        if self._closed:
            raise ClusterError("this study's cluster was closed (Cluster.close(), or the end of its with block): "
                               "start a new Cluster and compute the contributions again on it")
        return self._client

    @property
    def closed(self):
        return self._closed

    def _check_workers(self, timeout):
        try:
            self._client.wait_for_workers(1, timeout=timeout)
        except (TimeoutError, OSError):
            raise ClusterError("the Dask scheduler at %s has no worker after %g s: start some with "
                               "'dask worker %s' (docs/distributed.md)" % (self.address, timeout, self.address)) from None
        mine = _identity()
        for address in self.workers():
            try:
                theirs = self._run_within(timeout, _worker_identity, workers=[address])[address]
            except TimeoutError:
                raise ClusterError("worker %s did not answer within %g s: it is stopped, overloaded or unreachable "
                                   "from here (restart it, or leave it out of the cluster)" % (address, timeout)) from None
            except Exception as exc:  # the worker could not unpickle or run it: no Fenestra there
                raise ClusterError(
                    "worker %s cannot run Fenestra (%s: %s): install Fenestra's dependencies there and put its "
                    "addon directory on the worker's PYTHONPATH (docs/distributed.md)"
                    % (address, type(exc).__name__, exc)) from None
            if theirs != mine:
                raise ClusterError("worker %s runs %s, this client %s: use the same Fenestra build on every machine"
                                   % (address, _describe(theirs), _describe(mine)))

    def _run_within(self, timeout, function, *args, **kwargs):
        """client.run(function, *args, **kwargs), or TimeoutError after `timeout` seconds (Dask's run
        has no timeout: a stopped worker would hang it; the call is left to finish on its own thread)."""
        client = self.client
        done, outcome = threading.Event(), {}

        def target():
            try:
                outcome["value"] = client.run(function, *args, **kwargs)
            except BaseException as exc:  # re-raised in the caller's thread
                outcome["error"] = exc
            finally:
                done.set()

        threading.Thread(target=target, name="fenestra-cluster-check", daemon=True).start()
        if not done.wait(timeout):
            raise TimeoutError
        if "error" in outcome:
            raise outcome["error"]
        return outcome["value"]

    def _run_on_heard(self, function, *args):
        """function(*args) on the workers the scheduler has heard from lately, by address; {} for
        those that do not answer within the timeout (check() names a stopped worker)."""
        self._observe()
        workers = [w for w, (_, since) in self._heard.items() if time.monotonic() - since < self.timeout / 2]
        if not workers:
            return {}
        try:
            return self._run_within(self.timeout, function, *args, workers=workers)
        except (TimeoutError, OSError):
            return {}

    @property
    def address(self):
        return self.client.scheduler.address

    def _scheduler_workers(self):
        """The scheduler's record of each worker, by address."""
        client = self.client
        info = client.scheduler_info()
        if "workers" not in info or client.status not in ("running", "connecting"):
            raise ClusterError("lost the connection to the Dask scheduler at %s: restart it and its workers, then "
                               "run the study again" % client.scheduler.address)
        return info["workers"]

    def workers(self):
        """Addresses of the workers now connected."""
        return sorted(self._scheduler_workers())

    def _observe(self):
        """Asks the scheduler for its workers and notes, per worker, when (on this client's clock)
        its last heartbeat was seen to change, and since when there has been no worker."""
        now = self._checked = time.monotonic()
        workers = self._scheduler_workers()
        if not workers:
            self._no_worker_since = self._no_worker_since or now
            return  # the workers last heard of are kept for the message
        self._no_worker_since = None
        heard = {}
        for address, info in workers.items():
            seen, before = info.get("last_seen"), self._heard.get(address)
            heard[address] = (seen, now) if before is None or before[0] != seen else before
        self._heard = heard

    def check(self):
        """Raises ClusterError when the cluster has had no worker for `timeout` seconds (the last one
        killed, crashed or out of memory), or when a worker has not been heard from by the scheduler
        for that long (workers report twice a second: stopped, e.g. by SIGSTOP, hung, or cut off).
        Studies call it while they wait on the cluster; it asks the scheduler at most twice a second."""
        self.client  # noqa: B018 -- a closed cluster is refused at once
        if time.monotonic() - self._checked < 0.5:
            return
        self._observe()
        now = time.monotonic()
        if self._no_worker_since is not None:
            if now - self._no_worker_since > self.timeout:
                raise ClusterError(
                    "the Dask cluster at %s has had no worker for %g s (%s): its work cannot go on; start workers "
                    "with 'dask worker %s' and run the study again (docs/distributed.md)"
                    % (self.address, self.timeout, "%s left: killed, crashed or out of memory"
                       % ", ".join(sorted(self._heard)) if self._heard else "none joined", self.address))
            return
        for address, (_, since) in sorted(self._heard.items()):
            if now - since > self.timeout:
                raise ClusterError(
                    "worker %s has not been heard from for %g s: it is stopped (e.g. by SIGSTOP), hung, or cut off "
                    "from the scheduler at %s; resume or restart it (a worker that ends has its work moved to the "
                    "others), then run the study again" % (address, self.timeout, self.address))

    def close(self):
        """Closes the client (and a local cluster's workers); the cluster cannot be used after."""
        if self._closed:
            return
        self._closed = True
        try:
            self._client.close()
        finally:
            if self._local is not None:
                self._local.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()


def _shown(value):
    """A value as repr shows it, at most about 80 characters."""
    text = repr(value)
    return text if len(text) <= 80 else text[:77] + "..."


def _is_integer(value):
    return isinstance(value, (int, np.integer)) and not isinstance(value, (bool, np.bool_))


def _check_timeout(timeout):
    """Seconds: a finite number above 0, at most a day (Dask reads others as its own strings or fails)."""
    if isinstance(timeout, (bool, np.bool_)) or not isinstance(timeout, (int, float, np.integer, np.floating)) \
            or not 0 < timeout <= 86400:
        raise ValueError("timeout must be a finite number of seconds above 0 and at most 86400 (a day), got %s"
                         % _shown(timeout))
    return float(timeout)


def _check_memory_limit(limit):
    """A local worker's memory limit as Dask takes it: "auto", None (no limit), bytes, or a size
    string such as "4GB" (Dask's format)."""
    if limit is None or (isinstance(limit, str) and limit == "auto"):
        return limit
    if _is_integer(limit) and limit >= 0:
        return int(limit)
    if isinstance(limit, str):
        from dask.utils import parse_bytes

        try:
            if parse_bytes(limit) > 0:
                return limit
        except (ValueError, OverflowError, TypeError):
            pass
    raise ValueError("memory_limit must be \"auto\" (the machine's memory shared out), None (no limit), a whole "
                     "number of bytes or a size such as \"4GB\", got %s" % _shown(limit))


# The address of a scheduler: tcp://HOST:PORT, HOST a host name, an IPv4 address or [an IPv6 one].
_ADDRESS = re.compile(r"tcp://(\[[0-9A-Fa-f:.]+\]|[^:/\s\[\]]+):([0-9]{1,5})")
_LABEL = re.compile(r"[A-Za-z0-9_]([A-Za-z0-9_-]{0,61}[A-Za-z0-9_])?")


def _check_address(scheduler):
    """A scheduler address, tcp://HOST:PORT (checked here, without connecting: Dask's own errors for
    other schemes and bad host names come late, in its words, and leave a client behind that hangs
    the interpreter's exit)."""
    if not isinstance(scheduler, str):
        raise ValueError("scheduler address %s: expected a string 'tcp://HOST:PORT', e.g. 'tcp://host:8786'"
                         % _shown(scheduler))
    scheme, sep, _ = scheduler.partition("://")
    if sep and scheme != "tcp" and "/" not in scheme:
        raise ValueError("scheduler address %s: scheme %s:// is not supported: Fenestra's clusters connect over "
                         "tcp:// only (tls, ucx, ws and inproc are not), e.g. 'tcp://host:8786'"
                         % (_shown(scheduler), scheme[:20]))
    match = _ADDRESS.fullmatch(scheduler)
    if not match or not 1 <= int(match.group(2)) <= 65535:
        raise ValueError("scheduler address %s: expected tcp://HOST:PORT with PORT 1 to 65535, e.g. 'tcp://host:8786'"
                         % _shown(scheduler))
    host = match.group(1)
    if host.startswith("["):
        try:
            ipaddress.IPv6Address(host[1:-1])
        except ValueError:
            raise ValueError("scheduler address %s: %s is not an IPv6 address" % (_shown(scheduler), _shown(host))) from None
    elif len(host) > 253 or not all(_LABEL.fullmatch(label) for label in host.split(".")):
        raise ValueError("scheduler address %s: host %s (%d characters) is not a host name or IPv4 address: at most "
                         "253 characters, in parts of 1 to 63 letters, digits, '-' or '_' between dots"
                         % (_shown(scheduler), _shown(host), len(host)))


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
        if "refined" in spec:  # a solve's grid refined about its openings in thick walls
            scene = _core.refined_scene(scene, spec["refined"])
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
        "transport": _core.transport_entries(c) if spec.get("transport", True) else None,
        "seconds": c.seconds, "events": c.events,
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
    if op == "hourly_model":
        return _hourly_model(queries, sensors, *args)
    if op == "annual_parts":
        return queries.annual_parts(args[0])
    if op == "flip_effects":
        return _sparse(queries.flip_effects(args[0]))
    if op == "record_bytes":
        return queries.record_bytes
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


def _hourly_model(queries, sensors, about, rows, columns, flips):
    """The shard's rows of the climate goals' hourly model: (their positions in `rows`, its part)."""
    begin, end = sensors
    positions = np.flatnonzero((rows >= begin) & (rows < end)).astype(np.int32)
    return positions, queries.hourly_model(about, (rows[positions] - begin).astype(np.int32), columns, flips)


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


# ---- the client side ---------------------------------------------------------------------------


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
    return _contributions(spec, local, cluster, shards, callback)


def _contributions(spec, local, cluster, shards, callback):
    api._warn_if_dark(local)
    blocks = _blocks(local.sensor_count, shards if shards is not None else len(cluster.workers()))
    workers = cluster._scheduler_workers()
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
        self.T = (_core.transport_matrix_from_entries([p["transport"] for p in parts], scene.element_count,
                                                      self.paths_per_sensor)
                  if parts[0]["transport"] is not None else np.zeros((0, 0)))  # a solve's refined grid: no T
        self.seconds = max(p["seconds"] for p in parts)
        self.events = sum(p["events"] for p in parts)
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
        bit as one process gives). Its exact evaluations, flip effects, edge searches (on thick
        walls' refined grid too, traced there) and, with climate goals, the hourly models' rows and
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
            self.all_open, self.all_open_stderr, self.seconds, self.events)

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
        self.summary = None   # refined records: their contributions without records (refined())
        self._owns_study = False  # refined records free their study's shards when closed
        self.calls = 0

    def _ask(self, op, *args):
        self.calls += 1
        changes = op not in ("evaluate", "flip_effects", "record_bytes", "try", "hourly_model", "annual_parts")
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

    def evaluate(self, rectangles):
        return self._pairs(self._ask("evaluate", np.asarray(rectangles, dtype=np.float64)))

    def flip_effects(self, about):
        return _dense(self._ask("flip_effects", np.asarray(about, dtype=np.uint8)))

    def region_search(self, rectangles):
        search = next(self._searches)
        values = np.concatenate(self._ask("search", search, np.asarray(rectangles, dtype=np.float64)))
        return _ShardedSearch(self, search, values)

    def cut(self, openings, paths):
        s = self._study
        return self._pairs(s._map(_evaluate_cut_session, s._spec, openings, paths,
                                  cancelled=lambda: self._progress.cancelled))

    def record_bytes(self):
        return float(sum(self._ask("record_bytes")))

    def hourly_model(self, about, rows, columns, flips):
        """Per shard, its rows' positions in `rows` and its part of the hourly model (the native
        side stacks them)."""
        return self._ask("hourly_model", np.asarray(about, dtype=np.uint8), np.asarray(rows, dtype=np.int32),
                         columns, bool(flips))

    def annual_parts(self, rectangles):
        parts = self._ask("annual_parts", np.asarray(rectangles, dtype=np.float64))
        return tuple(np.concatenate([p[j] for p in parts]) for j in range(4))

    def annual_cut(self, openings, paths):
        s = self._study
        parts = s._map(_annual_cut_session, s._spec, openings, paths, cancelled=lambda: self._progress.cancelled)
        return tuple(np.concatenate([p[j] for p in parts]) for j in range(4)) + (parts[0][4],)

    def refined(self, regions, paths):
        """The records traced again on the grid refined about `regions` (edges in thick walls), shard
        by shard on the workers, as records of their own (`summary`: their contributions without
        records); closing them frees the shards."""
        s = self._study
        spec = dict(s._spec, refined=[list(r[:5]) + [list(r[5]), list(r[6])] for r in regions], transport=False)
        local = _core.refined_scene(s.scene, spec["refined"])  # with the study's render settings
        _set_render(spec, local, paths_per_sensor=int(paths))
        keys = _shard_keys("refined", spec, len(s._shards))
        client = s._cluster.client
        alive = set(s._cluster.workers())
        futures = [client.submit(_compute_shard, spec, key, sh["begin"], sh["end"], pure=False, key=key,
                                 workers=[sh["worker"]] if sh["worker"] in alive else None, allow_other_workers=True)
                   for key, sh in zip(keys, s._shards)]
        parts = _gather(s._cluster, futures, keys, lambda fraction, what: not self._progress.cancelled,
                        "tracing a finer grid in thick walls")
        del futures
        study = DistributedContributions(s._cluster, spec, local, keys, parts)
        records = _ShardedRecords(study, self._progress)
        records.summary, records._owns_study = study.as_contributions(), True
        return records

    def close(self):
        self._actors.clear()  # their futures released: the workers drop them
        try:
            self._study._cluster._run_on_heard(_end_session, self._session)
        except Exception:  # the cluster is gone: so is the state
            pass
        if self._owns_study:
            self._study.close()


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


def _evaluate_cut_session(key, sensors, spec, openings, paths):
    """The shard's sensors path-traced with the openings cut (the solver's checks with real cutters)."""
    return _core.evaluate(_scene_of(spec), openings, None, sensors, paths)


def _annual_cut_session(key, sensors, spec, openings, paths):
    """The shard's sensors' year path-traced with the openings cut (the climate goals' check)."""
    return _core.annual_cut_coefficients(_scene_of(spec), openings, None, sensors, paths)


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
    with _contributions(spec, local, cluster, shards, callback) as study:
        return study.solve(callback=callback)


# What the client of a solve on a cluster holds, by the cost model's names (docs/cost.md): the
# contributions' arrays and the solver's own state. The records, their indexes and the tracing stay
# on the workers.
_CLIENT_PARTS = ("E", "E_stderr", "A", "T", "solver_copies", "population", "genetic_history", "result_history")


def check_client_fits(scene, max_memory=None):
    """Raises ValueError, naming the figures, when what the client of a solve on a cluster holds
    would not fit in max_memory (default: what this machine has available): E, E_stderr, A and T,
    the solver's copies and population, and the flip-effect matrices the shards' answers are
    assembled into (sensors x elements, 8 bytes each). Climate goals' hourly model is checked when
    it is stacked, as one process checks it."""
    estimate = api.estimate_cost(scene, "solve", max_memory)
    held = {name: estimate["memory"].get(name, 0.0) for name in _CLIENT_PARTS}
    held["flip_effects"] = 8.0 * scene.sensor_count * scene.element_count
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
