"""Annual studies on a cluster: `fenestra annual` sharded by sensors. From the path records, each
shard traces its sensors' contributions and sends their daylight coefficients for the openings;
with real cutters (cutters=True), each shard traces its sensors' year with the openings cut. The
client stacks the coefficients in sensor order and turns them into hours and metrics as one
process does, so the study equals one process's bit for bit (but its timings)."""

import time

import numpy as np

from .. import _core, api
from .client import _blocks, _contributions, _gather, _shard_keys, _spec
from .worker import _annual_cut_shard, _annual_parts_shard


def _stacked(parts):
    """The shards' (sources, direct, mean, stderr) stacked in sensor order."""
    return tuple(np.concatenate([p[j] for p in parts]) for j in range(4))


def annual(scene, openings, cluster, shards=None, base_dir=".", output=None, callback=None, cutters=False, paths=0,
           warnings=()):
    """fenestra.annual on `cluster` (a Cluster), in `shards` blocks of sensors (default one per
    worker): the same dict, and with `output` the same OUTPUT.npz and OUTPUT.json, written whole
    after every shard has finished. `scene`: a scene file's path, a dict in the scene-file format
    (relative paths against base_dir) or a fenestra.Scene read from a file. `openings` as for
    fenestra.evaluate. cutters=True traces the paths with the openings cut and keeps no records,
    `paths` per sensor (0: the scene's render.paths_per_sensor). `warnings`: lines for the output's
    "warnings" (the command line's setup checks). callback(fraction, status) about once a second;
    returning False cancels (fenestra.Cancelled)."""
    spec, local = _spec(scene, base_dir)
    out, rects = api._annual_arguments(local, openings, output, cutters, paths)
    warnings = [str(w) for w in warnings]
    if out is not None:
        _core.check_output_paths(list(_core.npz_json_pair(out)), [local.source])
    if cutters:
        blocks = _blocks(local.sensor_count, shards if shards is not None else len(cluster.workers()))
        keys = _shard_keys("annual-cut", spec, len(blocks))
        futures = [cluster.client.submit(_annual_cut_shard, spec, key, rects, b, e, int(paths), pure=False, key=key)
                   for key, (b, e) in zip(keys, blocks)]
        start = time.monotonic()
        parts = _gather(cluster, futures, keys, callback, "tracing the year with the openings cut")
        return _core.annual_from_shards(local, _stacked(parts), parts[0][4], True, warnings=warnings,
                                        output=out or "", seconds=time.monotonic() - start)
    _core.check_openings(local, rects)  # before the long pass, as the records' study reads them
    with _contributions(spec, local, cluster, shards, callback) as study:
        start = time.monotonic()
        parts = study._map(_annual_parts_shard, spec, rects)
        dropped = study.dropped
        return _core.annual_from_shards(local, _stacked(parts), study.paths_per_sensor, False,
                                        dropped["non_finite"], dropped["truncated_conditions"], warnings, out or "",
                                        time.monotonic() - start)
