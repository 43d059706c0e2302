"""Benchmark of a whole floor designed for the year on a Dask cluster (docs/distributed.md), part of
`make bench`.

The floor (scripts/office_floor.py): 12 perimeter rooms on four facades around a ring corridor and
a core, 36 x 24 m, each room a closed box with a door to the corridor; the facades are the opening
domain (0.26 m elements: 4 884), 1 024 sensors at desk height in one group per room, the Chicago
O'Hare TMY3 year. Goals per room: sDA300/50% >= 55 % and ASE1000,250 <= 10 %, with the least
glazing. The floor is solved on a local cluster of --workers worker processes (one shard each);
with --scaling, on 1, 2 and 4 (the cores shared out). Printed per run: wall time, each worker's
peak resident memory and the client's against their estimated shares, each room's figures and
whether its goals are met; and what one process would hold (the cost model's estimate, and the
hourly model the shards counted from their records).

    /usr/bin/python3 scripts/floor_bench.py [--workers N] [--scaling] [--paths N] [--generations N]
                                            [--population N] [--json OUT.json]
"""

import argparse
import concurrent.futures
import json
import multiprocessing
import os
import sys
import tempfile
import time
import warnings

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(os.path.dirname(HERE), "addon"))
sys.path.insert(0, HERE)

import fenestra  # noqa: E402
from fenestra import distributed  # noqa: E402
from office_floor import write_office_floor  # noqa: E402

MIB = 1 << 20


def peak_rss_bytes():
    """This process's peak resident memory (VmHWM, which a new program starts afresh)."""
    with open("/proc/self/status") as f:
        for line in f:
            if line.startswith("VmHWM:"):
                return int(line.split()[1]) * 1024
    raise RuntimeError("no VmHWM in /proc/self/status")


def cluster_solve(path, workers):
    """In a child process, so that its peak is the client's own: the floor solved on a fresh local
    cluster of `workers` workers. Returns the seconds, the result, the workers' and client's peaks."""
    warnings.simplefilter("ignore", RuntimeWarning)
    threads = max(1, (os.cpu_count() or 1) // workers)
    with distributed.Cluster(workers=workers, threads_per_worker=threads, timeout=60) as cluster:
        start = time.monotonic()
        result = distributed.solve(path, cluster)
        seconds = time.monotonic() - start
        peaks = cluster.client.run(peak_rss_bytes)
    return seconds, result, peaks, peak_rss_bytes()


def room_lines(result):
    """Each room's figures, and its goals: met or not by the headline figures (the path records'),
    with the real cutters' check beside them."""
    lines, met = [], 0
    for room in result["climate"]["rooms"]:
        mine = [g for g in result["climate"]["goals"] if g["sensors"] == room["sensors"]]
        ok = all(g["met"] for g in mine)
        met += ok
        space = room["space"]
        checked = ", ".join("%s %.1f %%" % (g["metric"], 100 * g["verified"]) for g in mine if "verified" in g)
        lines.append("    %-8s %3d sensors: sDA %5.1f %%, ASE %4.1f %%, mean %5.0f lx (real cutters: %s)  %s" % (
            room["name"], len(room["sensors"]), 100 * space["spatial_daylight_autonomy"],
            100 * space["annual_sunlight_exposure"], space["mean_illuminance_lux"], checked,
            "goals met" if ok else "NOT met: " + "; ".join(
                "%s reaches %.1f %%" % (g["description"], 100 * g["achieved"]) for g in mine if not g["met"])))
    return lines, met


def run(path, scene, workers):
    share = distributed.solve_memory(scene, workers)
    with concurrent.futures.ProcessPoolExecutor(1, mp_context=multiprocessing.get_context("spawn")) as pool:
        seconds, result, peaks, client_peak = pool.submit(cluster_solve, path, workers).result()
    lines, met = room_lines(result)
    climate = result["climate"]
    print("  %d worker%s: %.0f s (the model %.0f s, the search %.0f s); %d openings, glazing %.1f m2; "
          "%d of %d rooms meet their goals" % (
              workers, "s" if workers > 1 else "", seconds, result["timings_s"].get("climate model", 0.0),
              result["timings_s"].get("climate search", 0.0), len(result["openings"]), climate["glazing_area_m2"],
              met, len(climate["rooms"])))
    for worker in sorted(peaks):
        print("    worker %s: peak resident %.0f MiB (estimated share %.0f MiB)"
              % (worker, peaks[worker] / MIB, share["worker"] / MIB))
    print("    client: peak resident %.0f MiB (estimated %.0f MiB, with the local cluster's scheduler)"
          % (client_peak / MIB, share["client"] / MIB))
    print("    hourly model over the shards: %.0f MiB" % (climate["model_bytes"] / MIB))
    print("\n".join(lines))
    return {"workers": workers, "seconds": seconds, "worker_peak_bytes": sorted(peaks.values()),
            "client_peak_bytes": client_peak, "estimated_worker_bytes": share["worker"],
            "estimated_client_bytes": share["client"], "model_bytes": climate["model_bytes"],
            "rooms_met": met, "rooms": len(climate["rooms"]), "glazing_m2": climate["glazing_area_m2"],
            "openings": len(result["openings"]), "timings_s": result["timings_s"]}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--scaling", action="store_true", help="solve on 1, 2 and 4 workers")
    parser.add_argument("--paths", type=int, default=2048)
    parser.add_argument("--generations", type=int, default=150)
    parser.add_argument("--population", type=int, default=48)
    parser.add_argument("--json")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        path = write_office_floor(tmp, paths=args.paths, solver={
            "population": args.population, "generations": args.generations, "seed": 1})
        scene = fenestra.load_scene(path)
        estimate = fenestra.estimate_cost(scene, "solve")
        memory = estimate["memory"]
        print("Floor benchmark: %d rooms, %d sensors x %d elements (%.2f m), %d paths per sensor, the Chicago year; "
              "population %d, %d generations; %d cores" % (
                  len(json.load(open(path))["sensors"]["groups"]), scene.sensor_count, scene.element_count,
                  scene.element_size, args.paths, args.population, args.generations, os.cpu_count()))
        print("  one process would hold about %.1f GiB (the hourly model %.1f GiB and the search's years %.1f GiB, "
              "estimated; %.1f GiB available here); dense, the model would be %.0f GiB" % (
                  estimate["total_bytes"] / 2**30, memory["climate_model"] / 2**30,
                  memory["climate_population"] / 2**30, estimate["available_bytes"] / 2**30,
                  dense_model_bytes(scene, memory) / 2**30))
        runs = [run(path, scene, n) for n in ((1, 2, 4) if args.scaling else (args.workers,))]
    if args.json:
        with open(args.json, "w") as f:
            json.dump({"sensors": scene.sensor_count, "elements": scene.element_count, "paths": args.paths,
                       "one_process_bytes": estimate["total_bytes"], "runs": runs}, f, indent=1)


def dense_model_bytes(scene, memory):
    """The hourly model were every element kept at every goal sensor: the cost model's figure
    (hourly_flip_model_bytes: 4 bytes an hour per pair and row index, two years of the rows) with
    its hours, for rows x elements pairs."""
    reach = [r for r in fenestra.climate_reach(scene) if r > 0]
    rows, pairs = len(reach), sum(reach)
    hours = (memory["climate_model"] - 4.0 * pairs) / (4.0 * (pairs + 2.0 * rows))
    dense = rows * scene.element_count
    return 4.0 * hours * (dense + 2.0 * rows) + 4.0 * dense


if __name__ == "__main__":
    main()
