"""The cluster: a Dask client with workers able to run Fenestra (Cluster), checked when it connects
(the workers' Fenestra, version and protocol: identity.py) and watched while a study waits on it
(Cluster.check); the checks of its arguments before anything connects."""

import ipaddress
import logging
import os
import re
import threading
import time

import numpy as np

from .identity import _describe, _identity, _worker_identity

_ADDON_DIR = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))  # on the workers' path


class ClusterError(RuntimeError):
    """The cluster cannot run the study: the scheduler is unreachable, a worker cannot import
    Fenestra or runs another version, or work was lost and could not be recomputed."""


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
