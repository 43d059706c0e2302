"""Studies past one machine: contributions, evaluation, solves and annual studies sharded by sensors
over a Dask cluster, and the sky built on a worker.

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

The package's rooms: cluster (Cluster: the Dask client, its workers checked and watched), worker
(what the workers run: the shards' contributions, evaluations and solve sessions, held in the
worker's memory), client (the study's side: sharding, gathering, DistributedContributions,
contributions, evaluate, solve), annual_study (annual studies), sky_map (the sky built on a worker) and
identity (what client and workers must agree on).
"""

from .annual_study import annual
from .client import (DistributedContributions, check_client_fits, check_shards_fit, climate_share, contributions,
                     evaluate, shard_needs, solve, solve_memory, worker_memory)
from .cluster import Cluster, ClusterError
from .identity import PROTOCOL
from .sky_map import sky, write_sky

__all__ = ["Cluster", "ClusterError", "DistributedContributions", "PROTOCOL", "annual", "check_client_fits",
           "check_shards_fit", "climate_share", "contributions", "evaluate", "shard_needs", "sky", "solve",
           "solve_memory", "worker_memory", "write_sky"]
