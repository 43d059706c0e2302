"""Seeded mutations of valid scenes, OBJ files, openings and arguments: every run of the
command-line program must end by itself, within its time budget and a memory cap, with exit
status 0, 1 or 2 (never a signal), an error naming the problem, and no output left on failure."""

import concurrent.futures
import copy
import json
import os
import random
import resource
import shutil
import subprocess
import warnings

import numpy as np
import pytest

from conftest import CLI, EXAMPLES, box_obj, write_small_room

import fenestra

CASES = int(os.environ.get("FENESTRA_FUZZ_CASES", "200"))
TIME_BUDGET_S = 60.0            # per run; valid runs take well under a second
MEMORY_CAP = 6 * 1024 ** 3      # bytes of address space per run (ulimit -v)

# Values that have broken parsers before: overflow in float or int, wrap-around, wrong types.
NASTY = [0, -1, 1, 2, 0.5, -0.5, 1e-300, 1e-45, 1e39, -1e39, 1e300, -1e300, 2 ** 31, 2 ** 32, 2 ** 32 + 1,
         2 ** 53 + 1, 2 ** 63, 2 ** 64 + 5, 4294967424, 1.5, 1e7, 1e8, "x", "", "\u00e9\u00e8", None, True, False,
         [], {}, [1e39, 1, 1], [0, 0, 0], [1, 2], [[1, 2, 3]], {"type": 3}]
OBJ_NASTY = ["1e39", "-1e39", "nan", "inf", "1e300", "0", "1e19", "3e18", "-0"]
INDEX_NASTY = ["0", "-1", "-99999", "99999", "18446744073709551617", "4294967297", "2147483648", "x", ""]


def base_scene(kind):
    scene = {
        "fenestra": 1,
        "geometry": "room.obj",
        "materials": {"grey": {"type": "diffuse", "reflectance": 0.6},
                      "facade": {"type": "diffuse", "reflectance": 0.5},
                      "pane": {"type": "glass", "transmittance": 0.8, "ior": 1.52},
                      "steel": {"type": "glossy", "reflectance": 0.6, "roughness": 0.3, "metallic": 0.5}},
        "opening_domain": {"materials": ["facade"], "element_size": 0.5, "thickness": 0.0},
        "sensors": {"points": [[1.5, 1.0, 0.8], [0.5, 2.5, 0.8], [2.5, 0.5, 1.2]], "normals": [0, 0, 1],
                    "goals": [0.5, 0.3, 0.6], "goal_units": "normalized"},
        "sky": {"type": "uniform", "radiance": 318.3, "ground_radiance": 63.7},
        "render": {"paths_per_sensor": 32, "max_bounces": 4, "seed": 1, "threads": 2, "sampler": "sobol"},
        "solver": {"population": 8, "generations": 4, "improve_iterations": 20, "verify": True, "verify_paths": 16,
                   "constraints": {"min_width": 0.5, "max_openings": 3, "head_clearance": 0.1,
                                   "max_openings_per_panel": 2, "full_height": False,
                                   "catalogue": {"walls": [[0.5, 1.0], [1.0, 1.0]], "roofs": [[1.0, 1.0]]}}},
    }
    if kind == "preetham":
        scene["sky"] = {"type": "preetham", "latitude": 48.85, "longitude": 2.35, "timezone": "Europe/Paris",
                        "date": "2026-03-21", "start": "09:00", "end": "17:00", "step_minutes": 120,
                        "turbidity": 3, "resolution": [64, 32]}
    elif kind == "overcast":
        scene["sky"] = {"type": "cie_overcast", "horizontal_illuminance": 10000, "resolution": [64, 32]}
    elif kind == "envmap":
        scene["sky"] = {"type": "envmap", "file": "sky.exr", "scale": 1.0, "rotation_deg": 30}
    return scene


def leaf_paths(node, prefix=()):
    """Every key path in the JSON tree, containers included."""
    yield prefix
    if isinstance(node, dict):
        for k, v in node.items():
            yield from leaf_paths(v, prefix + (k,))
    elif isinstance(node, list):
        for i, v in enumerate(node):
            yield from leaf_paths(v, prefix + (i,))


def set_at(root, path, value):
    node = root
    for p in path[:-1]:
        node = node[p]
    node[path[-1]] = value


def delete_at(root, path):
    node = root
    for p in path[:-1]:
        node = node[p]
    if isinstance(node, dict):
        del node[path[-1]]
    else:
        node.pop(path[-1])


def mutate_json(rng, scene):
    for _ in range(rng.randint(1, 3)):
        paths = [p for p in leaf_paths(scene) if p]
        path = rng.choice(paths)
        op = rng.random()
        if op < 0.6:
            set_at(scene, path, copy.deepcopy(rng.choice(NASTY)))
        elif op < 0.8:
            delete_at(scene, path)
        elif op < 0.9:
            set_at(scene, path[:-1] + ("unknown_key",) if isinstance(path[-1], str) else path, "surprise")
        else:  # many copies of a list (sensors, materials)
            parent = scene
            for p in path[:-1]:
                parent = parent[p]
            if isinstance(parent, list):
                parent.extend([copy.deepcopy(parent[0])] * rng.choice([10, 1000]))
    return scene


def mutate_text(rng, text):
    """Byte-level damage: truncation, a stray byte (invalid UTF-8 included), a key given twice, a NUL
    in a file name, a huge number. Returns the bytes and whether they must be refused."""
    data = text.encode()
    op = rng.random()
    at = rng.randrange(len(data))
    if op < 0.25:
        return data[:at], False
    if op < 0.5:
        return data[:at] + bytes([rng.choice([0x00, 0xff, 0xc3, ord("{"), ord('"'), ord(",")])]) + data[at:], False
    lines = text.splitlines(keepends=True)
    keyed = [i for i, l in enumerate(lines) if '":' in l and l.rstrip().endswith(",")]
    if op < 0.6 and keyed:  # a key given twice: the last one won
        i = rng.choice(keyed)
        return "".join(lines[:i + 1] + [lines[i]] + lines[i + 1:]).encode(), True
    if op < 0.65:  # a NUL inside a file name: room.obj was read
        return text.replace('"room.obj"', '"room.obj\\u0000' + rng.choice(["x", ".bak", "/../x"]) + '"').encode(), True
    digits = [i for i, c in enumerate(text) if c.isdigit()]
    i = rng.choice(digits)
    return (text[:i] + rng.choice(["1e400", "-1e400", "99999999999999999999999", "0x10"]) + text[i + 1:]).encode(), False


def mutate_obj(rng, text):
    lines = text.splitlines()
    op = rng.random()
    if op < 0.3:  # a bad coordinate
        i = rng.choice([k for k, l in enumerate(lines) if l.startswith("v ")])
        parts = lines[i].split()
        parts[rng.randrange(1, 4)] = rng.choice(OBJ_NASTY)
        lines[i] = " ".join(parts)
    elif op < 0.55:  # a bad face index
        i = rng.choice([k for k, l in enumerate(lines) if l.startswith("f ")])
        parts = lines[i].split()
        parts[rng.randrange(1, len(parts))] = rng.choice(INDEX_NASTY)
        lines[i] = " ".join(parts)
    elif op < 0.7:  # exported in millimetres
        lines = ["v " + " ".join("%g" % (1000 * float(c)) for c in l.split()[1:]) if l.startswith("v ") else l
                 for l in lines]
    elif op < 0.85:
        lines.insert(rng.randrange(len(lines) + 1), rng.choice(["f 1", "v 1 2", "usemtl", "usemtl nowhere",
                                                               "o", "f 1 1 1", "\x00\x01", "vt 0 0", "f 1/ 2/ 3/"]))
    else:
        lines = lines[:rng.randrange(len(lines))]
    return "\n".join(lines) + "\n"


def mutate_args(rng, args):
    flag = rng.choice(["--paths", "--threads", "--seed"])
    value = rng.choice(["0", "-1", "4294967296", "4294967297", "2147483648", "1e9", "abc", "", "99999999999999999999",
                        "1073741825", "3"])
    return args + [flag, value]


def make_case(seed, workdir):
    """Writes one mutated study into workdir; returns (command line, output paths, what was done)."""
    rng = random.Random(seed)
    kind = rng.choice(["uniform", "uniform", "preetham", "overcast", "envmap"])
    scene = base_scene(kind)
    obj = box_obj((0, 0, 0), (3, 3, 2.5), lambda f: "facade" if f == "south" else "grey")
    openings = {"openings": [{"corners": [[1, 0, 1], [2, 0, 1], [2, 0, 2], [1, 0, 2]]}]}
    command = rng.choices(["contributions", "evaluate", "sky", "solve"], weights=[5, 2, 1, 2])[0]
    target = rng.choices(["json", "text", "obj", "openings", "args", "output", "memory"],
                         weights=[6, 2, 3, 1, 1, 1, 1])[0]
    if target == "openings" and command != "evaluate":
        target = "json"
    if target == "output":  # a sky map in a format that keeps cd/m^2 or not
        command = "sky"
    scene_bytes, refused = None, False
    if target == "json":
        scene = mutate_json(rng, scene)
    elif target == "text":
        scene_bytes, refused = mutate_text(rng, json.dumps(scene, indent=1))
    elif target == "obj":
        obj = mutate_obj(rng, obj)
    elif target == "openings":
        openings = mutate_json(rng, openings)
    if scene_bytes is None:
        scene_bytes = json.dumps(scene).encode()
    # A typo'd key and a face of fewer than 3 corners were read past.
    keys = {p[-1] for p in leaf_paths(scene if target == "json" else openings if target == "openings" else {}) if p}
    refused = refused or "unknown_key" in keys or any(l in ("f 1", "v 1 2") for l in obj.splitlines())
    (workdir / "scene.json").write_bytes(scene_bytes)
    (workdir / "room.obj").write_text(obj)
    (workdir / "openings.json").write_text(json.dumps(openings))
    if kind == "envmap":
        shutil.copy(os.path.join(EXAMPLES, "reference_room", "sky.exr"), workdir / "sky.exr")
    sky_name = "out." + (rng.choice(["png", "jpg", "tif", "hdr", "HDR", "exr", "bmp", "pfm"]) if target == "output"
                         else "exr")
    out = workdir / (sky_name if command == "sky" else "out.npz" if command == "contributions" else "out.json")
    args = [CLI, command, str(workdir / "scene.json"), "-o", str(out), "--quiet"]
    if command == "evaluate":
        args += ["--openings", str(workdir / "openings.json")]
    if target == "args":
        args = mutate_args(rng, args)
    cap = MEMORY_CAP
    if target == "memory":  # an address-space limit anywhere from too small to start to enough
        cap = rng.randrange(96, 1536) * 1024 ** 2  # below about 64 MiB the program's libraries cannot be mapped
        args += ["--max-memory", "100G"]  # past the cost checks: the allocations themselves fail
    outputs = [out] + ([workdir / "out.json"] if command == "contributions" else [])
    return args, outputs, cap, "%s sky, %s, %s mutated%s" % (kind, command, target,
                                                          " (must be refused)" if refused else "")


def cap_memory(cap):
    return lambda: resource.setrlimit(resource.RLIMIT_AS, (cap, cap))


def check_case(seed, root):
    workdir = root / ("case%04d" % seed)
    workdir.mkdir()
    args, outputs, cap, what = make_case(seed, workdir)
    inputs = set(os.listdir(workdir))
    try:
        r = subprocess.run(args, capture_output=True, timeout=TIME_BUDGET_S, preexec_fn=cap_memory(cap))
    except subprocess.TimeoutExpired:
        return "seed %d (%s): still running after %.0f s" % (seed, what, TIME_BUDGET_S)
    stderr = r.stderr.decode("utf-8", "replace")
    problem = None
    if "must be refused" in what and r.returncode != 1:
        problem = "accepted (exit %d)" % r.returncode
    if r.returncode < 0:
        problem = "killed by signal %d" % -r.returncode
    elif r.returncode not in (0, 1, 2):
        problem = "exit status %d" % r.returncode
    elif any(s in stderr for s in ("terminate called", "json.exception", "std::bad_alloc", "Assertion", "what():",
                                   "syntax error while", "last read:", "Failed parse", "literal;")):
        problem = "raw internal message"
    elif r.returncode != 0:
        if "fenestra: " not in stderr or len(stderr.strip()) < 20:
            problem = "no message naming the problem"
        elif set(os.listdir(workdir)) != inputs:
            problem = "left %s behind" % sorted(set(os.listdir(workdir)) - inputs)
    elif outputs[0].suffix.lower() not in (".exr", ".hdr", ".npz", ".json"):
        problem = "exit 0 writing %s, which cannot keep cd/m^2" % outputs[0].name
    else:
        missing = [str(p) for p in outputs if not p.exists()]
        leftovers = [f for f in os.listdir(workdir) if ".tmp" in f]
        if missing or leftovers:
            problem = "exit 0 but missing %s, temporaries %s" % (missing, leftovers)
        elif outputs[0].suffix == ".npz":
            with np.load(outputs[0]) as data:
                bad = [k for k in data.files if not np.isfinite(data[k]).all() and k != "E_stderr"
                       and not k.endswith("_stderr")]
                if bad:
                    problem = "exit 0 with non-finite %s" % bad
    if problem:
        return "seed %d (%s): %s; rc %d; %s" % (seed, what, problem, r.returncode, stderr.strip()[-300:])
    shutil.rmtree(workdir)
    return None


@pytest.mark.skipif(not os.path.exists(CLI), reason="CLI not built")
def test_mutated_inputs_end_cleanly(tmp_path):
    with concurrent.futures.ThreadPoolExecutor(max_workers=2) as pool:
        results = list(pool.map(lambda s: check_case(s, tmp_path), range(CASES)))
    failures = [r for r in results if r]
    assert not failures, "%d of %d mutated runs failed:\n%s" % (len(failures), CASES, "\n".join(failures[:25]))


# ---- site coordinates: the same room moved anywhere --------------------------------------------

def offset_value(rng):
    """One axis's offset, meters: small, fractional, UTM-sized, at the limit, just beyond it."""
    kind = rng.randrange(6)
    sign = rng.choice([-1.0, 1.0])
    if kind == 0:
        return sign * rng.uniform(0.0, 200.0)
    if kind == 1:
        return sign * rng.uniform(1e5, 1e7 - 10.0)
    if kind == 2:
        return sign * round(rng.uniform(1e5, 9.9e6)) + rng.choice([0.25, 0.5, 0.37])
    if kind == 3:
        return sign * (1e7 - 3.0)
    if kind == 4:
        return sign * (1e7 + rng.choice([1.0, 1e3, 1e6]))
    return sign * 10.0 ** rng.uniform(-300, 2)


@pytest.mark.skipif(not os.path.exists(CLI), reason="CLI not built")
def test_a_room_moved_anywhere_gives_the_origins_numbers_or_is_refused(tmp_path):
    from scipy import stats

    bound = stats.t.isf(stats.norm.sf(4.0), 15)
    home = write_small_room(tmp_path / "home", paths=512, seed=5)
    subprocess.run([CLI, "contributions", str(home), "-o", str(tmp_path / "home.npz"), "--quiet"], check=True)
    reference = np.load(tmp_path / "home.npz")
    rng = random.Random(35)
    for case in range(24):
        offset = np.array([offset_value(rng) for _ in range(3)])
        scene = write_small_room(tmp_path / str(case), offset, paths=512, seed=5)
        out = tmp_path / ("%d.npz" % case)
        r = subprocess.run([CLI, "contributions", str(scene), "-o", str(out), "--quiet"], capture_output=True,
                           text=True, timeout=120)
        largest = np.abs(np.array([offset + p for p in ([0, 0, 0], [3, 3, 2.5])])).max()
        if largest > 1e7:
            assert r.returncode == 1 and "1e+07 m" in r.stderr, (offset, r.returncode, r.stderr)
            assert not out.exists()
            continue
        assert r.returncode == 0, (offset, r.stderr)
        moved = np.load(out)
        assert np.all(moved["closed"] == 0.0), (offset, moved["closed"])
        assert np.all(np.abs(moved["all_open"] - reference["all_open"])
                      <= bound * np.hypot(moved["all_open_stderr"], reference["all_open_stderr"])), offset
        np.testing.assert_allclose(moved["element_corners"] - offset, reference["element_corners"],
                                   atol=1e-5)

def make_setup_case(seed, workdir):
    """A small room with seeded misleading setups (sensors outdoors or facing down, a face left out,
    goals 0 or none): (command line, output, strict)."""
    rng = random.Random(1000 + seed)
    faces = ["floor", "ceiling", "south", "north", "west", "east"]
    missing = rng.choice([None, None, "ceiling", "north", "floor"])
    text, skip = [], False
    for line in box_obj((0, 0, 0), (3, 3, 2.5), lambda f: "facade" if f == "south" else "grey").splitlines():
        if line.startswith("o "):
            skip = line == "o %s" % missing
        if not (skip and not line.startswith("v ")):
            text.append(line)
    assert missing is None or missing in faces
    (workdir / "room.obj").write_text("\n".join(text) + "\n")
    points = [[rng.uniform(-2, 5), rng.uniform(-2, 5), rng.uniform(0.1, 2.4)] for _ in range(rng.randint(1, 6))]
    normals = [rng.choice([[0, 0, 1], [0, 0, -1], [1, 0, 0], [0, 0.6, -0.8]]) for _ in points]
    scene = {"fenestra": 1, "geometry": "room.obj",
             "materials": {"grey": {"reflectance": 0.5}, "facade": {"reflectance": 0.5}},
             "opening_domain": {"materials": ["facade"], "element_size": 0.75},
             "sensors": {"points": points, "normals": normals},
             "sky": {"type": "uniform", "radiance": 100}, "render": {"paths_per_sensor": 16},
             "solver": {"generations": 2, "population": 4, "improve_iterations": 10, "verify": False}}
    goal = rng.choice([None, 0.0, 0.4])
    if goal is not None:
        scene["goals"] = {"uniform": [{"level": goal}]}
    (workdir / "scene.json").write_text(json.dumps(scene))
    command = rng.choice(["contributions", "solve"])
    strict = rng.random() < 0.4
    out = workdir / ("out.npz" if command == "contributions" else "out.json")
    return [CLI, command, str(workdir / "scene.json"), "-o", str(out), "--quiet"] + (["--strict"] if strict else []), \
        workdir / "out.json", strict


@pytest.mark.skipif(not os.path.exists(CLI), reason="CLI not built")
def test_misleading_setups_warn_or_refuse_cleanly(tmp_path):
    """Seeded setups: a run warns on stderr and records the same warnings in its output, or (with
    --strict, or a solve without goals) refuses with status 1 and writes nothing."""
    for seed in range(12):
        workdir = tmp_path / ("setup%02d" % seed)
        workdir.mkdir()
        args, summary, strict = make_setup_case(seed, workdir)
        r = subprocess.run(args, capture_output=True, text=True, timeout=TIME_BUDGET_S)
        warned = [line[len("fenestra: warning: "):] for line in r.stderr.splitlines()
                  if line.startswith("fenestra: warning: ")]
        if r.returncode == 0:
            recorded = json.loads(summary.read_text())["warnings"]
            assert set(recorded) <= set(warned), (seed, recorded, warned)
        else:
            assert r.returncode == 1, (seed, r.returncode, r.stderr)
            assert r.stderr.startswith("fenestra: error: ") and "what():" not in r.stderr, (seed, r.stderr)
            assert sorted(os.listdir(workdir)) == ["room.obj", "scene.json"], (seed, os.listdir(workdir))


# ---- Python inputs: open masks and cluster options -------------------------------------------------

MASK_VALUES = [0, 1, True, False, 0.0, 1.0, -0.0, 0.5, -1, 2, 255, 256, np.nan, np.inf, -np.inf, 1e-300, 1 + 0j, 1j,
               None, "1", "", [], np.float32(1.0), np.int64(1), np.uint8(0), np.float16(0.5), 2 ** 64]


def test_fuzzed_open_masks_are_read_as_given_or_refused(small_room):
    """Seeded masks of every dtype: accepted only when every entry is a bool or a number exactly 0 or
    1, and then equal to the bool mask; otherwise ValueError naming an entry that is neither."""
    scene = fenestra.load_scene(small_room)
    scene.render.paths_per_sensor = 16
    c = fenestra.contributions(scene)
    n = scene.element_count
    rng = random.Random(35)
    outcomes = {"read": 0, "refused": 0}
    for _ in range(200):
        base = [rng.random() < 0.5 for _ in range(n)]
        mask = list(base)
        for _ in range(rng.choice([0, 0, 1, 2])):
            mask[rng.randrange(n)] = rng.choice(MASK_VALUES)
        form = rng.choice(["list", "array", "float", "int8", "object"])
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")  # NumPy's own about casts (256 to int8, complex to float)
                given = {"list": lambda: mask, "array": lambda: np.array(mask), "float": lambda: np.array(mask, float),
                         "int8": lambda: np.array(mask, np.int8), "object": lambda: np.array(mask, dtype=object)}[form]()
        except (ValueError, TypeError, OverflowError):
            continue  # NumPy itself cannot make that array
        flat = list(np.array(given, dtype=object).ravel()) if not isinstance(given, list) else given
        clean = all(isinstance(v, (bool, np.bool_)) or (isinstance(v, (int, float, np.integer, np.floating))
                                                        and not isinstance(v, complex) and v in (0, 1)) for v in flat)
        try:
            values, _ = c.evaluate(given)
        except ValueError as exc:
            assert not clean, (form, mask, exc)
            assert "open mask" in str(exc) and len(str(exc)) < 400, str(exc)
            outcomes["refused"] += 1
            continue
        assert clean, (form, mask)
        assert np.array_equal(values, c.evaluate(np.array([bool(v) for v in flat]))[0])
        outcomes["read"] += 1
    assert min(outcomes.values()) >= 30, outcomes  # both kinds well exercised


def test_fuzzed_cluster_options_are_refused_before_connecting_or_accepted(monkeypatch):
    """Seeded options of distributed.Cluster: each is refused at once (ValueError naming it) or
    reaches Dask with well-formed values; Dask is replaced here, so nothing connects."""
    dask_distributed = pytest.importorskip("distributed")
    from fenestra import distributed

    reached = []

    def connect(*args, **kwargs):
        reached.append((args, kwargs))
        raise OSError("not connecting in this test")

    monkeypatch.setattr(dask_distributed, "Client", connect)
    monkeypatch.setattr(dask_distributed, "LocalCluster", connect)
    addresses = ["tcp://127.0.0.1:8786", "tls://h:1", "ucx://h:1", "ws://h:1", "inproc://x", "tcp://h:0",
                 "tcp://h:65536", "tcp://" + "a" * 300 + ":1", "tcp://[::1]:8786", "tcp://[zz]:1", "h:8786",
                 "tcp://a..b:1", "tcp://é:1", "tcp://a b:1", ""]
    rng = random.Random(36)
    outcomes = {"reached": 0, "refused": 0}
    pick = lambda good, bad: rng.choice(good if rng.random() < 0.6 else bad)  # noqa: E731
    for _ in range(300):
        options = {}
        if rng.random() < 0.5:
            options["scheduler"] = pick(addresses[:1] + ["tcp://[::1]:8786", "tcp://h.example.org:1"],
                                        addresses + NASTY)
        else:
            options["workers"] = pick([1, 2, 1024], NASTY)
            if rng.random() < 0.5:
                options["threads_per_worker"] = pick([None, 1, 8], NASTY)
            if rng.random() < 0.5:
                options["memory_limit"] = pick(["auto", None, "4GB", 10 ** 9], ["x", "-1GB"] + NASTY)
        if rng.random() < 0.7:
            options["timeout"] = pick([10, 0.5, 86400], NASTY + [float("nan"), float("inf"), -1e-9])
        del reached[:]
        try:
            distributed.Cluster(**options)
        except ValueError as exc:
            assert not reached and len(str(exc)) < 400, (options, exc)
            outcomes["refused"] += 1
            continue
        except distributed.ClusterError as exc:  # reached Dask, which "failed to connect"
            assert "cannot reach" in str(exc) or "not connecting" in str(exc), (options, exc)
        except OSError:
            pass
        assert len(reached) == 1, options
        timeout = options.get("timeout", 10.0)
        assert not isinstance(timeout, bool) and 0 < timeout <= 86400, options
        if options.get("scheduler") is not None:
            assert options["scheduler"].startswith("tcp://"), options
        outcomes["reached"] += 1
    assert min(outcomes.values()) >= 20, outcomes


# Keys whose names are the user's (materials, sensor groups): not typos.
FREE_NAMES = {("materials",), ("sensors", "groups")}


def typo(rng, word):
    """One seeded edit of `word`: a letter dropped, doubled, swapped with the next, or replaced."""
    i = rng.randrange(len(word))
    op = rng.choice(["drop", "double", "swap", "replace"])
    if op == "drop" and len(word) > 1:
        return word[:i] + word[i + 1:]
    if op == "swap" and i + 1 < len(word) and word[i] != word[i + 1]:
        return word[:i] + word[i + 1] + word[i] + word[i + 2:]
    if op == "replace":
        return word[:i] + rng.choice([c for c in "abcdefghijklmnopqrstuvwxyz_" if c != word[i]]) + word[i + 1:]
    return word[:i] + word[i] + word[i:]


def key_paths(node, prefix=()):
    """(path of the object, key) for every key of every object, user-named keys left out."""
    if isinstance(node, dict):
        for k, v in node.items():
            if prefix not in FREE_NAMES:
                yield prefix, k
            yield from key_paths(v, prefix + (k,))
    elif isinstance(node, list):
        for i, v in enumerate(node):
            yield from key_paths(v, prefix + (i,))


def shown_path(path, key):
    out = ""
    for p in path + (key,):
        out += "[%d]" % p if isinstance(p, int) else ("." if out else "") + p
    return out


def full_scene(kind):
    scene = base_scene(kind)
    scene["opening_domain"]["groups"] = []
    scene["sensors"]["weights"] = [1, 1, 1]
    scene["goals"] = {"uniform": [{"sensors": "all", "level": 0.3, "min": 0.1, "max": 0.9}]}
    scene["solver"].update(paths=16, seed=2, shape_weights={"isolated": 1, "boundary": 1, "regions": 1},
                           panel_constraints=[{"materials": ["facade"], "constraints": {"max_openings": 2}}])
    scene["solver"]["constraints"]["catalogue"]["walls"].append({"width": 1.5, "height": 1.2})
    return scene


@pytest.mark.parametrize("kind", ["uniform", "preetham", "overcast"])
def test_a_typo_of_any_key_is_refused_naming_it(tmp_path, kind):
    """A seeded typo of every key at every level of a valid scene: each is refused, naming the
    misspelt key's path, with a suggestion (they ran with the defaults before)."""
    import fenestra

    (tmp_path / "room.obj").write_text(box_obj((0, 0, 0), (3, 3, 2.5), lambda f: "facade" if f == "south" else "grey"))
    fenestra.scene_from_dict(full_scene(kind), tmp_path)  # the valid scene loads
    every = list(key_paths(full_scene(kind)))
    known = {k for _, k in every} | {"time", "date_end", "timezone", "utc_offset", "roofs", "groups", "weather"}
    rng = random.Random(35)
    for path, key in every:
        wrong = typo(rng, key)
        while wrong in known:  # another key's name is no typo
            wrong = typo(rng, key)
        scene = full_scene(kind)
        parent = scene
        for p in path:
            parent = parent[p]
        parent[wrong] = parent.pop(key)
        with pytest.raises(ValueError) as error:
            fenestra.scene_from_dict(scene, tmp_path)
        message = str(error.value)
        where = shown_path(path, wrong)
        assert "scene '<dict>': %s: unknown key; did you mean `" % where in message, (key, wrong, message)
