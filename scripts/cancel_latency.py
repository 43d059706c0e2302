"""How soon a solve stops after a cancel, at every moment of it:

    /usr/bin/python3 scripts/cancel_latency.py SCENE.json [--element-size M] [--cancels N] [--paths P]

Runs the solve (load, contributions, solver) once uncancelled, recording its stages, then N more
times, each cancelled at a moment spread over that run, and prints the latency (from cancel() to
the end of the call) per stage: the worst, and where it was."""

import argparse
import json
import os
import sys
import tempfile
import threading
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "addon"))
import fenestra  # noqa: E402


def solve_steps(path, progress):
    scene = fenestra.load_scene(path, progress=progress)
    c = fenestra.contributions(scene, progress=progress)
    return fenestra.solve(scene, contributions=c, progress=progress)


def run(path, cancel_at=None):
    """(timeline [(seconds, status)], latency or None, status at the cancel)."""
    progress = fenestra.Progress()
    outcome = {}

    def target():
        try:
            solve_steps(path, progress)
        except fenestra.Cancelled:
            outcome["cancelled"] = True
        outcome["end"] = time.monotonic()

    start = time.monotonic()
    thread = threading.Thread(target=target, daemon=True)
    thread.start()
    timeline, cancelled_at, status_at = [], None, None
    while thread.is_alive():
        now = time.monotonic()
        status = progress.status
        if not timeline or timeline[-1][1] != status:
            timeline.append((now - start, status))
        if cancel_at is not None and cancelled_at is None and now - start >= cancel_at:
            status_at = "%s %.0f %%" % (status, 100 * progress.fraction)
            cancelled_at = time.monotonic()
            progress.cancel()
        time.sleep(0.002)
    thread.join()
    latency = outcome["end"] - cancelled_at if cancelled_at is not None and outcome.get("cancelled") else None
    return timeline, latency, status_at, outcome["end"] - start


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("scene")
    parser.add_argument("--element-size", type=float)
    parser.add_argument("--paths", type=int)
    parser.add_argument("--cancels", type=int, default=20)
    args = parser.parse_args()
    scene = json.load(open(args.scene))
    base = os.path.dirname(os.path.abspath(args.scene))
    if isinstance(scene.get("geometry"), str):
        scene["geometry"] = os.path.join(base, scene["geometry"])
    if args.element_size:
        scene["opening_domain"]["element_size"] = args.element_size
    if args.paths:
        scene.setdefault("render", {})["paths_per_sensor"] = args.paths
        scene.setdefault("solver", {})["paths"] = args.paths
    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, "scene.json")
        json.dump(scene, open(path, "w"))
        timeline, _, _, total = run(path)
        print("uncancelled: %.1f s" % total)
        for (t, status), nxt in zip(timeline, timeline[1:] + [(total, "")]):
            print("  %6.2f s  %5.2f s  %s" % (t, nxt[0] - t, status or "(reading)"))
        worst = {}
        for k in range(args.cancels):
            at = total * (k + 0.5) / args.cancels
            _, latency, status, _ = run(path, at)
            if latency is None:
                continue
            print("cancel at %6.2f s (%s): %.3f s" % (at, status, latency), flush=True)
            stage = status.rsplit(" ", 2)[0]
            if latency > worst.get(stage, (0, ""))[0]:
                worst[stage] = (latency, "%.2f s" % at)
        print("worst latency per stage:")
        for stage, (latency, where) in sorted(worst.items(), key=lambda kv: -kv[1][0]):
            print("  %.3f s  %s (at %s)" % (latency, stage or "(reading)", where))


if __name__ == "__main__":
    main()
