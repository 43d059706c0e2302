#pragma once
// `fenestra ... --workers N | --scheduler ADDRESS`: a study sharded over a Dask cluster runs in the
// Python package (fenestra.distributed_cli), which this program hands the command line to.

namespace fenestra {

// Whether the arguments ask for a cluster (--workers, --scheduler or --shards).
bool wants_cluster(int argc, char** argv);

// Replaces this process with `python3 -m fenestra.distributed_cli` and the same arguments, the
// package found where it was built (or under $FENESTRA_ADDON_DIR, Python at $FENESTRA_PYTHON).
// Returns only on failure, with the exit status after printing why.
int hand_to_cluster(int argc, char** argv);

}  // namespace fenestra
