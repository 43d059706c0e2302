"""The scene's sky on a cluster: `fenestra sky` with the sky built on a worker (a daylight sky's
time steps, or a climate sky's year of weather), so that the client machine need not hold the
weather or build the map. The worker builds the sky from the same scene file as one process, so
the map and the summary are one process's, bit for bit (but the summary's build time)."""

import json

from .client import _result, _spec
from .worker import _sky_of


def _built(scene, cluster, base_dir):
    spec, local = _spec(scene, base_dir)
    sky_map, summary = _result(cluster, cluster.client.submit(_sky_of, spec, pure=False))
    return local, sky_map, summary


def sky(scene, cluster, base_dir="."):
    """fenestra.sky with the sky built on a worker of `cluster` (a Cluster): the same dict (the map
    as a (height, width, 3) float32 array, cd/m^2; the horizontal illuminances and the sun list)."""
    _, sky_map, summary = _built(scene, cluster, base_dir)
    out = json.loads(summary)
    out["map_size"] = out.pop("map", None)
    out["map"] = sky_map
    return out


def write_sky(scene, path, cluster, json_path=None, base_dir="."):
    """Writes the sky map to path (.exr or .hdr) and, with json_path, the summary, as `fenestra sky`
    writes them (together or not at all); the sky is built on a worker. Returns the lines the
    command prints about the sky."""
    from .. import _core

    local = _spec(scene, base_dir)[1]
    _core.check_output_paths([path] + ([json_path] if json_path else []), [local.source])  # before any work
    _core.check_image_path(path)
    local, sky_map, summary = _built(scene, cluster, base_dir)
    return _core.write_sky_outputs(local, path, sky_map, summary, json_path or "")
