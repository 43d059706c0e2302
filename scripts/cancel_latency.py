"""How soon a solve stops after a cancel, in every stage of it:

    /usr/bin/python3 scripts/cancel_latency.py SCENE.json [--element-size M] [--paths P] [--at 0.1 0.5 0.9]

Runs the solve (load, contributions, solver) once uncancelled, recording its stages (the
progress status), then once more for every stage and every fraction given, cancelling that far
into the stage (its n-th occurrence: the genetic algorithm runs several times), and prints the
latency (from cancel() to the end of the call, memory freed included) per stage."""

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


def run(path, stage=None, occurrence=0, delay=0.0):
    """(timeline [(seconds, status)], total seconds, latency or None, status at the cancel);
    cancels `delay` seconds into the occurrence-th time the status is `stage`."""
    progress = fenestra.Progress()
    outcome = {}

    def target():
        try:
            solve_steps(path, progress)
        except fenestra.Cancelled:
            outcome["cancelled"] = True
        except ValueError as exc:  # refused: the machine's memory changed since the first run
            outcome["refused"] = str(exc)
        outcome["end"] = time.monotonic()

    start = time.monotonic()
    thread = threading.Thread(target=target, daemon=True)
    thread.start()
    timeline, seen, entered, cancelled_at, status_at = [], 0, None, None, None
    while thread.is_alive():
        now = time.monotonic()
        status = progress.status
        if not timeline or timeline[-1][1] != status:
            timeline.append((now - start, status))
            if status == stage:
                if seen == occurrence:
                    entered = now
                seen += 1
        if entered is not None and cancelled_at is None and now - entered >= delay:
            status_at = "%s %.0f %%" % (status, 100 * progress.fraction)
            cancelled_at = time.monotonic()
            progress.cancel()
        time.sleep(0.001)
    thread.join()
    latency = outcome["end"] - cancelled_at if cancelled_at is not None and outcome.get("cancelled") else None
    return timeline, outcome["end"] - start, latency, status_at


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("scene")
    parser.add_argument("--element-size", type=float)
    parser.add_argument("--paths", type=int)
    parser.add_argument("--at", type=float, nargs="+", default=[0.1, 0.5, 0.9])
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
        timeline, total, _, _ = run(path)
        print("uncancelled: %.1f s" % total)
        stages, count = [], {}
        for (t, status), nxt in zip(timeline, timeline[1:] + [(total, "")]):
            print("  %6.2f s  %5.2f s  %s" % (t, nxt[0] - t, status or "(reading)"))
            stages.append((status, count.get(status, 0), nxt[0] - t))
            count[status] = count.get(status, 0) + 1
        worst = {}
        for status, occurrence, duration in stages:
            if not status or duration < 0.02:
                continue
            for fraction in args.at:
                _, _, latency, at = run(path, status, occurrence, fraction * duration)
                if latency is None:
                    print("%s #%d at %.0f %%: not cancelled (the stage ended first, or the study was refused)"
                          % (status, occurrence, 100 * fraction))
                    continue
                print("%s #%d at %.0f %% (%s): %.3f s" % (status, occurrence, 100 * fraction, at, latency), flush=True)
                worst[status] = max(worst.get(status, 0.0), latency)
        print("worst latency per stage:")
        for status, latency in sorted(worst.items(), key=lambda kv: -kv[1]):
            print("  %.3f s  %s" % (latency, status))


if __name__ == "__main__":
    main()
