"""Benchmark of a study sharded over a Dask cluster (docs/distributed.md), part of `make bench`.

A generated building floor: 12 rooms of 6 x 5 x 3 m in a row, 0.2 m apart, each with its south
wall the opening domain (0.2 m elements: 5 400 in all) and a grid of 9 x 10 sensors at desk height
(1 080 in all), under a Preetham sky. The contributions are computed by one process and by a local
cluster of 2 worker processes over TCP, then a generation of 64 random sets is evaluated exactly
from the records both ways. Last the floor is solved (goals of 5 % of the unobstructed light,
opening limits, a genetic run of --generations) by one process and on a fresh local cluster, and
so is a floor of 2 such rooms (0.5 m elements, 180 sensors) under the Chicago O'Hare TMY3 year
for climate goals (sDA300/50% >= 50 %, ASE1000,250 <= 10 %, least glazing). Printed: wall times, the ratios, each worker's peak memory (resident set) and the records it
holds, and whether the results agree bit for bit.

    /usr/bin/python3 scripts/distributed_bench.py [--paths N] [--workers N] [--generations N]
                                                  [--no-solve] [--no-climate] [--json OUT.json]
"""

import argparse
import json
import os
import sys
import tempfile
import time

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "addon"))

import fenestra  # noqa: E402
from fenestra import distributed  # noqa: E402

ROOMS, WIDTH, DEPTH, HEIGHT, GAP = 12, 6.0, 5.0, 3.0, 0.2
CLIMATE_ROOMS = 2
WEATHER = os.path.join(ROOT, "examples", "weather", "USA_IL_Chicago-OHare.Intl.AP.725300_TMY3.epw")


def box_faces(x0, x1):
    """The six inward-facing quads of a room spanning x0..x1, and which is the facade (south)."""
    y0, y1, z0, z1 = 0.0, DEPTH, 0.0, HEIGHT
    return {
        "floor": [(x0, y0, z0), (x0, y1, z0), (x1, y1, z0), (x1, y0, z0)],
        "ceiling": [(x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)],
        "south": [(x0, y0, z0), (x1, y0, z0), (x1, y0, z1), (x0, y0, z1)],
        "north": [(x0, y1, z0), (x0, y1, z1), (x1, y1, z1), (x1, y1, z0)],
        "west": [(x0, y0, z0), (x0, y0, z1), (x0, y1, z1), (x0, y1, z0)],
        "east": [(x1, y0, z0), (x1, y1, z0), (x1, y1, z1), (x1, y0, z1)],
    }


def write_floor(directory, paths, rooms=ROOMS):
    lines, n, sensors = [], 0, []
    for r in range(rooms):
        x0 = r * (WIDTH + GAP)
        for name, quad in box_faces(x0, x0 + WIDTH).items():
            lines += ["o room%d_%s" % (r, name), "usemtl %s" % ("facade" if name == "south" else "interior")]
            lines += ["v %g %g %g" % p for p in quad]
            lines.append("f %d %d %d %d" % (n + 1, n + 2, n + 3, n + 4))
            n += 4
        sensors += [[x0 + 0.5 + i * (WIDTH - 1.0) / 8, 0.5 + j * (DEPTH - 1.0) / 9, 0.8] for i in range(9) for j in range(10)]
    with open(os.path.join(directory, "floor.obj"), "w") as f:
        f.write("\n".join(lines) + "\n")
    scene = {
        "fenestra": 1, "geometry": "floor.obj",
        "materials": {"interior": {"reflectance": 0.5}, "facade": {"reflectance": 0.5}},
        "opening_domain": {"materials": ["facade"], "element_size": 0.2},
        "sensors": {"points": sensors},
        "sky": {"type": "preetham", "turbidity": 3, "latitude": 48.85, "longitude": 2.35, "date": "2026-03-21",
                "time": "11:00", "timezone": "Europe/Paris"},
        "render": {"paths_per_sensor": paths, "seed": 1},
    }
    path = os.path.join(directory, "scene.json")
    with open(path, "w") as f:
        json.dump(scene, f)
    return path


def write_solve_scene(path, generations):
    """The floor with goals and solver settings, beside it."""
    with open(path) as f:
        scene = json.load(f)
    scene["goals"] = {"units": "normalized", "uniform": [{"sensors": "all", "level": 0.05}]}
    scene["solver"] = {"generations": generations, "population": 32, "seed": 1,
                       "constraints": {"min_width": 0.6, "min_height": 1.0, "sill_min": 0.8}}
    solve_path = os.path.join(os.path.dirname(path), "solve.json")
    with open(solve_path, "w") as f:
        json.dump(scene, f)
    return solve_path


def write_climate_scene(directory, paths, generations):
    """A floor of CLIMATE_ROOMS rooms under the weather file's year, with climate goals."""
    climate_dir = os.path.join(directory, "climate")
    os.makedirs(climate_dir)
    path = write_floor(climate_dir, paths, rooms=CLIMATE_ROOMS)
    with open(path) as f:
        scene = json.load(f)
    scene["opening_domain"]["element_size"] = 0.5
    scene["sky"] = {"type": "climate", "weather": WEATHER}
    scene["goals"] = {"climate": [{"metric": "sda", "min_area_fraction": 0.5},
                                  {"metric": "ase", "max_area_fraction": 0.1}], "least_glazing": True}
    scene["solver"] = {"generations": generations, "population": 16, "seed": 1,
                       "constraints": {"min_width": 0.6, "min_height": 1.0, "sill_min": 0.8}}
    with open(path, "w") as f:
        json.dump(scene, f)
    return path


def without_timings(result):
    """A solve result without what measures the run, not the answer: its timings, the stages'
    seconds (and the tracing's stage, listed when the solve traced its own contributions), and the
    climate model's bytes (summed over the shards that hold it)."""
    result = json.loads(json.dumps(result))
    result.pop("timings_s")
    for generation in result["genetic"]["history"]:
        generation.pop("seconds")
    result["stages"] = [s for s in result["stages"] if s["name"] != "contributions"]
    for stage in result["stages"]:
        stage.pop("seconds")
    if "climate" in result:
        result["climate"].pop("model_bytes")
    return result


def one_process_solve(path):
    """Runs in a child process, so that its peak memory is the solve's own."""
    import warnings

    warnings.simplefilter("ignore", RuntimeWarning)
    start = time.monotonic()
    result = fenestra.solve(fenestra.load_scene(path))
    model_bytes = result["climate"]["model_bytes"] if "climate" in result else 0.0
    return time.monotonic() - start, without_timings(result), result["timings_s"], peak_rss_bytes(), model_bytes


def solve_bench(path, args):
    return compare_solves(write_solve_scene(path, args.generations), args, "solve")


def compare_solves(solve_path, args, name):
    """The scene solved by one process (a child) and on a fresh local cluster: times, peaks, equality."""
    import concurrent.futures
    import multiprocessing
    import warnings

    with concurrent.futures.ProcessPoolExecutor(1, mp_context=multiprocessing.get_context("spawn")) as pool:
        one_seconds, one, one_timings, one_peak, one_model_bytes = pool.submit(one_process_solve, solve_path).result()
    with distributed.Cluster(workers=args.workers, threads_per_worker=max(1, os.cpu_count() // args.workers),
                             timeout=60) as cluster:
        start = time.monotonic()
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            many = distributed.solve(solve_path, cluster)
        many_seconds = time.monotonic() - start
        peaks = cluster.client.run(peak_rss_bytes)
    same = without_timings(many) == one
    mib = 1 << 20
    if "climate" in one:
        quality = "; ".join("%s: %.2f" % (g["description"], g["achieved"]) for g in one["climate"]["goals"])
        quality += "; hourly model %.0f MiB in one process, %.0f MiB over the shards" % (
            one_model_bytes / mib, many["climate"]["model_bytes"] / mib)
    else:
        quality = "relative RMS error %.1f %%" % (100 * one["error"]["relative_rms"])
    print("  %s, one process: %.1f s (contributions %.1f s), peak resident %.0f MiB; %d openings, %s"
          % (name, one_seconds, one_timings["contributions"], one_peak / mib, len(one["openings"]), quality))
    print("  %s, %d workers: %.1f s; the solver's stages in this process %.1f s"
          % (name, args.workers, many_seconds, many["timings_s"]["total"]))
    for worker in sorted(peaks):
        print("    worker %s: peak resident %.0f MiB" % (worker, peaks[worker] / mib))
    print("  ratio (one process / cluster): %s %.2f x; results equal bit for bit (but timings): %s"
          % (name, one_seconds / many_seconds, same))
    key = name.replace(" ", "_")
    return {"one_process_%s_seconds" % key: one_seconds, "cluster_%s_seconds" % key: many_seconds,
            "one_process_%s_peak_resident_bytes" % key: one_peak, "%s_worker_peak_resident_bytes" % key: peaks,
            "%s_bit_identical" % key: same}


def peak_rss_bytes():
    """This process's peak resident memory: VmHWM, which a new program starts afresh (getrusage's
    ru_maxrss is kept across exec, so a worker started late would report its parent's peak)."""
    with open("/proc/self/status") as f:
        for line in f:
            if line.startswith("VmHWM:"):
                return int(line.split()[1]) * 1024
    raise RuntimeError("no VmHWM in /proc/self/status")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--paths", type=int, default=1024)
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--generations", type=int, default=100)
    parser.add_argument("--no-solve", action="store_true")
    parser.add_argument("--no-climate", action="store_true")
    parser.add_argument("--json")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        path = write_floor(tmp, args.paths)
        scene = fenestra.load_scene(path)
        print("Distributed benchmark: a generated floor of %d rooms, %d sensors x %d elements, %d paths per sensor; "
              "%d cores" % (ROOMS, scene.sensor_count, scene.element_count, args.paths, os.cpu_count()))
        masks = np.random.default_rng(2).random((64, scene.element_count)) < 0.3

        # The cluster starts first: its worker processes must not inherit the one-process run's
        # high-water mark of memory.
        with distributed.Cluster(workers=args.workers, threads_per_worker=max(1, os.cpu_count() // args.workers),
                                 timeout=60) as cluster:
            start = time.monotonic()
            one = fenestra.contributions(scene)
            one_seconds = time.monotonic() - start
            start = time.monotonic()
            one_values = np.array([one.evaluate(m)[0] for m in masks])
            one_eval_seconds = time.monotonic() - start
            one_records = one.memory_bytes - 8 * (3 * one.E.size + one.T.size)
            one_peak = peak_rss_bytes()
            del one

            start = time.monotonic()
            with distributed.contributions(path, cluster) as many:
                many_seconds = time.monotonic() - start
                traced = many.seconds  # the slowest shard's own time on its worker
                start = time.monotonic()
                many_values, _ = many.evaluate_batch(masks)
                many_eval_seconds = time.monotonic() - start
                held = distributed.worker_memory(cluster)
                peaks = cluster.client.run(peak_rss_bytes)
                same = bool(np.array_equal(many_values, one_values))
                shards = many.shards
        mib = 1 << 20
        print("  one process:  contributions %.2f s, 64 exact evaluations %.2f s, records %.1f MiB, peak resident %.0f MiB"
              % (one_seconds, one_eval_seconds, one_records / mib, one_peak / mib))
        print("  %d workers:    contributions %.2f s (the slowest shard %.2f s on its worker; the rest is loading the "
              "scene there, moving the rows and assembling T), 64 exact evaluations %.2f s (one batch)"
              % (args.workers, many_seconds, traced, many_eval_seconds))
        for worker in sorted(held):
            print("    worker %s: records %.1f MiB (its shard of sensors %s), peak resident %.0f MiB"
                  % (worker, held[worker] / mib, [(b, e) for b, e, w in shards if w == worker], peaks[worker] / mib))
        print("  ratio (one process / cluster): contributions %.2f x, evaluations %.2f x; results equal bit for bit: %s"
              % (one_seconds / many_seconds, one_eval_seconds / many_eval_seconds, same))
        solved = {} if args.no_solve else solve_bench(path, args)
        if not args.no_climate:
            climate_path = write_climate_scene(tmp, 256, max(1, args.generations // 5))
            climate = fenestra.load_scene(climate_path)
            print("  climate goals: %d rooms, %d sensors x %d elements, 256 paths per sensor, the Chicago year"
                  % (CLIMATE_ROOMS, climate.sensor_count, climate.element_count))
            solved.update(compare_solves(climate_path, args, "climate solve"))
        same = same and all(v for k, v in solved.items() if k.endswith("bit_identical"))
        if args.json:
            with open(args.json, "w") as f:
                json.dump(dict(solved, **{"sensors": scene.sensor_count, "elements": scene.element_count, "paths": args.paths,
                           "one_process_seconds": one_seconds, "cluster_seconds": many_seconds,
                           "one_process_evaluation_seconds": one_eval_seconds, "slowest_shard_seconds": traced,
                           "cluster_evaluation_seconds": many_eval_seconds, "worker_records_bytes": held,
                           "worker_peak_resident_bytes": peaks, "one_process_records_bytes": one_records,
                           "bit_identical": same}), f, indent=2)
        return 0 if same else 1


if __name__ == "__main__":
    sys.exit(main())
