"""The forward check against Radiance on its reference room (make bench).

    /usr/bin/python3 scripts/forward_check_bench.py BUILD/fenestra

Runs `fenestra evaluate` on examples/reference_room (the window of window.json really cut) for
three seeds, each a whole process (start-up and scene load included, as a user runs it), and
compares every sensor with the reference table of ../shared/reference/radiance-scene-b.md (all
bounces, Radiance 6.1a and radiosity agreeing within 0.3 %). The target: RMS <= 1 % and worst
sensor <= 3 % for every seed, in no more wall time than Radiance's
`rtrace -ab 8 -ad 8192 -as 0 -aa 0` on two processes (0.88 s on one process, so about 0.45 s).
The sky is the reference's in closed form (scene_uniform.json: a uniform sky over a uniform
ground); the same room with the sky as an image (scene.json) is timed too, since reading an
image loads OpenImageIO.
"""
import json
import math
import os
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOM = os.path.join(HERE, "..", "examples", "reference_room")
TABLE = [66.90, 258.96, 258.96, 66.90, 50.68, 81.13, 81.13, 50.68,
         30.73, 36.73, 36.73, 30.73, 22.83, 25.33, 25.33, 22.83]
RTRACE_ONE_PROCESS_S = 0.88
TARGET_S = RTRACE_ONE_PROCESS_S / 2
PATHS = 2048
SEEDS = (1, 2, 3)


def run(cli, scene, paths, seed):
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "values.json")
        start = time.perf_counter()
        subprocess.run([cli, "evaluate", os.path.join(ROOM, scene), "--openings", os.path.join(ROOM, "window.json"),
                        "-o", out, "--paths", str(paths), "--seed", str(seed), "--quiet"], check=True,
                       capture_output=True)
        seconds = time.perf_counter() - start
        with open(out) as f:
            values = [s["value"] for s in json.load(f)["sensors"]]
    deviations = [(v - t) / t for v, t in zip(values, TABLE)]
    rms = math.sqrt(sum(d * d for d in deviations) / len(deviations))
    return seconds, 100 * rms, 100 * max(abs(d) for d in deviations)


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    cli = sys.argv[1]
    print("Forward check: fenestra evaluate on the reference room, %d paths per sensor, whole process timed" % PATHS)
    print("  target: RMS <= 1 %%, worst <= 3 %% for every seed, wall time <= %.2f s (rtrace on two processes)" % TARGET_S)
    met = True
    for scene, label in (("scene_uniform.json", "sky in closed form"), ("scene.json", "sky as an image")):
        for seed in SEEDS:
            seconds, rms, worst = run(cli, scene, PATHS, seed)
            ok = rms <= 1.0 and worst <= 3.0 and seconds <= TARGET_S
            if scene == "scene_uniform.json":
                met = met and ok
            print("  %-19s seed %d: %.2f s, RMS %.2f %%, worst %.2f %%%s" % (label, seed, seconds, rms, worst,
                                                                          "" if ok else "  (outside the target)"))
    print("  forward check target %s (sky in closed form); rtrace: 0.88 s on one process, mean 0.5 %%, worst 2.9 %%"
          % ("MET" if met else "NOT met"))


if __name__ == "__main__":
    main()
