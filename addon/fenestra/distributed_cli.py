"""`fenestra solve|contributions|evaluate|annual|sky ... --workers N | --scheduler ADDRESS`: the command line's
studies sharded over a Dask cluster (fenestra.distributed). The `fenestra` program hands such runs
to this module (python3 -m fenestra.distributed_cli, the same arguments); outputs are the same
files, written whole or not at all, after every shard has finished."""

import json
import os
import signal
import sys
import time
import warnings

from .wording import counted

USAGE = """usage:
  fenestra solve SCENE.json -o RESULT.json (--workers N | --scheduler ADDRESS) [options]
  fenestra contributions SCENE.json -o OUT[.npz] (--workers N | --scheduler ADDRESS) [options]
  fenestra evaluate SCENE.json --openings OPENINGS.json -o OUT.json (--workers N | --scheduler ADDRESS) [options]
  fenestra annual SCENE.json --openings OPENINGS.json -o OUT[.npz] [--cutters] (--workers N | --scheduler ADDRESS)
      [options]
  fenestra sky SCENE.json -o SKY.exr [--json SUMMARY.json] (--workers N | --scheduler ADDRESS)

cluster options (docs/distributed.md):
  --workers N          start a local Dask cluster of N worker processes (1 to 1024)
  --scheduler ADDRESS  use a running Dask scheduler, e.g. tcp://host:8786
  --shards N           blocks of sensors (default: one per worker; not for sky, which one worker builds)
  --threads N          threads per local worker (default: the cores shared out)
other options as for a single process: --paths N, --seed N, --quiet, --strict, --max-memory SIZE
(a local worker's memory limit), --cutters (annual), --json PATH (sky)
"""


COMMANDS = ("solve", "contributions", "evaluate", "annual", "sky")


class UsageError(Exception):
    pass


def warn_if_dropped(dropped):
    """The warning `fenestra` prints when the tracer dropped light (docs/outputs.md, "dropped")."""
    from fenestra import _core
    message = _core.dropped_warning(dropped) if dropped else ""
    if message:
        print("fenestra: warning: %s" % message, file=sys.stderr)


def parse(argv):
    a = {"positional": [], "quiet": False, "strict": False, "cutters": False}
    flags = {"-o": "output", "--output": "output", "--openings": "openings", "--workers": "workers",
             "--scheduler": "scheduler", "--shards": "shards", "--threads": "threads", "--paths": "paths",
             "--seed": "seed", "--max-memory": "max_memory", "--json": "summary"}
    integers = {"workers": (1, 1024), "shards": (1, 1 << 20), "threads": (0, 4096), "paths": (1, 1 << 30),
                "seed": (0, 1 << 53)}
    i = 0
    while i < len(argv):
        arg = argv[i]
        if arg in ("-h", "--help"):
            print(USAGE)
            sys.exit(0)
        if arg == "--quiet":
            a["quiet"] = True
        elif arg == "--strict":
            a["strict"] = True
        elif arg == "--cutters":
            a["cutters"] = True
        elif arg in flags:
            if i + 1 >= len(argv):
                raise UsageError("%s needs a value" % arg)
            i += 1
            name, text = flags[arg], argv[i]
            if name in integers:
                lo, hi = integers[name]
                if not (text.isascii() and text.isdigit()) or not lo <= int(text) <= hi:
                    raise UsageError("%s expects an integer from %d to %d, got '%s'" % (arg, lo, hi, text))
                a[name] = int(text)
            else:
                a[name] = text
        elif arg.startswith("-"):
            raise UsageError("unknown option '%s'" % arg)
        else:
            a["positional"].append(arg)
        i += 1
    if len(a["positional"]) != 2 or a["positional"][0] not in COMMANDS:
        raise UsageError("expected 'solve', 'contributions', 'evaluate', 'annual' or 'sky' and one scene file")
    a["command"], a["scene"] = a["positional"]
    if "output" not in a:
        raise UsageError("%s needs -o OUT" % a["command"])
    if a["command"] in ("evaluate", "annual") and "openings" not in a:
        raise UsageError("%s needs --openings OPENINGS.json" % a["command"])
    if a["cutters"] and a["command"] != "annual":
        raise UsageError("--cutters belongs to the annual command")
    if "summary" in a and a["command"] != "sky":
        raise UsageError("--json belongs to the sky command")
    if a["command"] == "sky":
        for flag, name in (("--shards", "shards"), ("--paths", "paths"), ("--seed", "seed"), ("--strict", "strict")):
            if a.get(name):
                raise UsageError("%s does not apply to sky: one worker builds the sky" % flag)
    if ("workers" in a) == ("scheduler" in a):
        raise UsageError("give --workers N (a local cluster) or --scheduler ADDRESS (a running one)")
    for flag, name in (("--threads", "threads"), ("--max-memory", "max_memory")):
        if "scheduler" in a and name in a:
            raise UsageError("%s sets a local cluster's workers; a running cluster's are set where they start" % flag)
    return a


def output_paths(a):
    if a["command"] in ("contributions", "annual"):
        from fenestra import _core
        return list(_core.npz_json_pair(a["output"]))
    return [a["output"]] + ([a["summary"]] if "summary" in a else [])


def run(a):
    import fenestra
    from fenestra import _core, distributed

    inputs = [a["scene"]] + ([a["openings"]] if "openings" in a else [])
    _core.check_output_paths(output_paths(a), inputs)
    scene = fenestra.load_scene(a["scene"])
    _core.check_output_paths(output_paths(a), inputs)
    # The setup checks, as one process runs them (docs/outputs.md, "Setup warnings"): printed before
    # any work, or with --strict an error.
    if a["command"] == "sky":
        return run_sky(a, scene)
    stage = "evaluate" if a["command"] == "annual" else a["command"]  # as one process checks an annual study
    setup = fenestra.api.setup_messages(scene, stage, a["strict"])
    for message in setup:
        print("fenestra: warning: %s" % message, file=sys.stderr)
    if a["command"] == "solve":
        return run_solve(a, scene, setup)
    if "paths" in a:
        scene.render.paths_per_sensor = a["paths"]
    if "seed" in a:
        scene.render.seed = a["seed"]
    say, progress = reporters(a)
    start = time.monotonic()
    with cluster_of(a) as cluster:
        say("cluster: %d workers at %s" % (len(cluster.workers()), cluster.address))
        if a["command"] == "contributions":
            with distributed.contributions(scene, cluster, shards=a.get("shards"), callback=progress) as c:
                written = c.save(a["output"])
                seconds = time.monotonic() - start
                print("contributions: %d sensors x %d elements, %d paths per sensor, %d shards, %.2f s"
                      % (c.E.shape[0], c.E.shape[1], c.paths_per_sensor, len(c.shards), seconds))
                print("wrote %s\nwrote %s" % tuple(written))
                warn_if_dropped(c.dropped)
        elif a["command"] == "annual":
            return run_annual(a, scene, cluster, setup, start)
        else:
            openings = fenestra.read_openings(a["openings"])
            value, stderr = distributed.evaluate(scene, openings, cluster, shards=a.get("shards"), callback=progress)
            _core.write_evaluation(scene, value, stderr, len(openings), a["output"])  # a list or an (n, 4, 3) array
            print("evaluate: %d sensors, %d shards, %.2f s\nwrote %s"
                  % (len(value), len(distributed.client._blocks(len(value), a.get("shards") or len(cluster.workers()))),
                     time.monotonic() - start, a["output"]))
    return 0


def run_annual(a, scene, cluster, setup, start):
    """The annual study on the cluster: its files as `fenestra annual` writes them, and a summary."""
    import fenestra
    from fenestra import distributed

    if not scene.has_climate:
        raise ValueError("scene '%s': annual needs a sky of type \"climate\" (a weather file; docs/scene-format.md)"
                         % a["scene"])
    say, progress = reporters(a)
    openings = fenestra.read_openings(a["openings"])
    r = distributed.annual(scene, openings, cluster, shards=a.get("shards"), output=a["output"], callback=progress,
                           cutters=a["cutters"], warnings=setup)
    m = r["summary"]
    space = m["space"]
    print("annual%s: %d sensors x %d hours (%d occupied), %d paths per sensor, %d workers; %.2f s"
          % (" (openings cut)" if a["cutters"] else "", m["sensors"], m["hours"], m["occupied_hours"],
             m["paths_per_sensor"], len(cluster.workers()), time.monotonic() - start))
    print("sDA %.1f %%, ASE %.1f %%, mean DA %.1f %%, mean illuminance %.0f lx"
          % (100 * space["spatial_daylight_autonomy"], 100 * space["annual_sunlight_exposure"],
             100 * space["daylight_autonomy"], space["mean_illuminance_lux"]))
    from fenestra import _core
    print("wrote %s\nwrote %s" % tuple(_core.npz_json_pair(a["output"])))
    if not a["cutters"]:
        warn_if_dropped(m.get("dropped"))
    return 0


def run_sky(a, scene):
    """The sky built on a worker, its map (and summary) written as `fenestra sky` writes them."""
    from fenestra import distributed

    say, _ = reporters(a)
    with cluster_of(a) as cluster:
        say("cluster: %d workers at %s" % (len(cluster.workers()), cluster.address))
        report = distributed.write_sky(a["scene"], a["output"], cluster, json_path=a.get("summary"))
    print("%swrote %s" % (report, a["output"]))
    if "summary" in a:
        print("wrote %s" % a["summary"])
    return 0


def reporters(a):
    """say(text) on stderr unless --quiet, and a progress callback that says the stage and share done
    when either changes (the callback comes about once a second, a long stage's share seldom moves)."""
    say = (lambda text: None) if a["quiet"] else (lambda text: print(text, file=sys.stderr, flush=True))
    last = [None]

    def progress(fraction, status):
        line = "  %s: %3.0f%%" % (status, 100 * fraction)
        if line != last[0]:
            last[0] = line
            say(line)

    return say, progress


def cluster_of(a):
    from fenestra import _core, distributed

    memory = _core.parse_memory_size(a["max_memory"]) if "max_memory" in a else "auto"
    return distributed.Cluster(scheduler=a.get("scheduler"), workers=a.get("workers"),
                               threads_per_worker=a.get("threads") or None, memory_limit=memory)


def solve_scene(a, scene):
    """The scene to solve: its file, or with --paths and --seed its JSON with them applied as
    `fenestra solve` applies them (render.paths_per_sensor and solver.paths; render.seed and
    solver.seed), and the directory its relative paths start from."""
    if "paths" not in a and "seed" not in a:
        return a["scene"], "."
    with open(a["scene"], encoding="utf-8") as f:
        data = json.load(f)
    render, solver = data.setdefault("render", {}), data.setdefault("solver", {})
    if "paths" in a:
        render["paths_per_sensor"] = solver["paths"] = a["paths"]
    if "seed" in a:
        render["seed"] = solver["seed"] = a["seed"]
    return data, os.path.dirname(os.path.abspath(a["scene"]))


def print_climate_summary(climate):
    """Each climate goal: reached (path records) and checked (real cutters), and the glazing; as the
    one-process `fenestra solve` prints them."""
    if not climate:
        return

    def text(goal, x):
        return "%.0f lx" % x if goal["unit"] == "lux" else "%.1f %%" % (100 * x)

    for goal in climate["goals"]:
        line = "climate goal %s:" % goal["description"]
        if goal.get("achieved") is not None:
            line += " %s %s" % (text(goal, goal["achieved"]), "met" if goal["met"] else "NOT met")
        if goal.get("verified") is not None:
            line += "; real cutters %s %s" % (text(goal, goal["verified"]), "met" if goal["verified_met"] else "NOT met")
        print(line)
    print("glazing %.2f m2 of %.2f m2 of opening domain" % (climate["glazing_area_m2"], climate["domain_area_m2"]))
    for room in climate.get("rooms", []):  # as one process prints them
        m = room["space"]
        print("room %s (%d sensors): sDA %.1f %%, ASE %.1f %%, mean illuminance %.0f lx"
              % (room["name"], len(room["sensors"]), 100 * m["spatial_daylight_autonomy"],
                 100 * m["annual_sunlight_exposure"], m["mean_illuminance_lux"]))


def memory_line(scene, a, workers):
    """The solve's memory on the cluster by the cost model, as one process prints its estimate."""
    from fenestra import distributed

    if "paths" in a:  # the paths the solve traces its contributions with (the scene is not used after)
        scene.render.paths_per_sensor = a["paths"]
    elif scene.solver_paths > 0:
        scene.render.paths_per_sensor = scene.solver_paths
    m = distributed.solve_memory(scene, workers, a.get("shards"))
    mib = distributed.client._mib
    return ("estimated memory: about %s per worker, %s in this process (one process would hold %s)"
            % (mib(m["worker"]), mib(m["client"]), mib(m["one_process"])))


def run_solve(a, scene, setup=()):
    from fenestra import _core, distributed

    say, progress = reporters(a)
    source, base_dir = solve_scene(a, scene)
    with cluster_of(a) as cluster:
        say("cluster: %d workers at %s" % (len(cluster.workers()), cluster.address))
        say(memory_line(scene, a, len(cluster.workers())))
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)  # the result's warnings: printed below
            r = distributed.solve(source, cluster, shards=a.get("shards"), base_dir=base_dir, callback=progress)
    own = r.get("warnings", [])  # the solver's (the setup's are printed above)
    r["warnings"] = list(setup) + own
    _core.write_json_text(a["output"], json.dumps(r))
    e = r["error"]
    opened = len(r["open_elements"])
    if "climate" in r:
        print("solve: %s, %s; %.2f s\nwrote %s"
              % (counted(len(r["openings"]), "opening"), counted(opened, "open element"), r["timings_s"]["total"],
                 a["output"]))
    else:
        print("solve: %s, %s; relative RMS error %.2f%% (linear model %.2f%%, compensated "
              "%.2f%%), worst sensor %.1f%%; %.2f s\nwrote %s"
              % (counted(len(r["openings"]), "opening"), counted(opened, "open element"), 100 * e["relative_rms"], 100 * e["linear"]["relative_rms"],
                 100 * e["compensated"]["relative_rms"], 100 * e["max_relative"], r["timings_s"]["total"],
                 a["output"]))
        if e.get("verified"):
            print("checked with real cutters: relative RMS error %.2f%%, worst sensor %.1f%%"
                  % (100 * e["verified"]["relative_rms"], 100 * e["verified"]["max_relative"]))
    print_climate_summary(r.get("climate"))
    for message in own:
        print("fenestra: warning: %s" % message, file=sys.stderr)
    warn_if_dropped(r.get("dropped"))
    return 0


def main(argv):
    try:
        a = parse(argv)
    except UsageError as exc:
        print("fenestra: %s\n\n%s" % (exc, USAGE), file=sys.stderr)
        return 2
    received = {}

    def on_signal(sig, frame):
        received["signal"] = sig
        raise KeyboardInterrupt

    signal.signal(signal.SIGTERM, on_signal)
    try:
        return run(a)
    except KeyboardInterrupt:
        sig = received.get("signal", signal.SIGINT)
        print("fenestra: interrupted by %s; no output written" % signal.Signals(sig).name, file=sys.stderr)
        return 128 + sig
    except Exception as exc:  # a clear message, not a traceback
        print("fenestra: error: %s" % exc, file=sys.stderr)
        return 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
