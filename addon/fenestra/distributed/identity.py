"""What a client and its workers must agree on: the package version, the shard protocol and the
Python version. The cluster compares them when it connects (Cluster._check_workers)."""

import sys

# What client and workers must agree on: the package version and the shard protocol.
PROTOCOL = 3


def _version():
    from .. import bl_info

    return ".".join(str(v) for v in bl_info["version"])


def _identity():
    """What a process runs: compared between the client and every worker."""
    return {"fenestra": _version(), "protocol": PROTOCOL, "python": "%d.%d" % sys.version_info[:2]}


def _worker_identity():
    return _identity()


def _describe(identity):
    return "Fenestra %s (shard protocol %s) on Python %s" % (identity["fenestra"], identity["protocol"], identity["python"])
