#!/usr/bin/python3
"""Checks that a change of the code's layout leaves Fenestra's outputs bit for bit as they were.

    compare_results.py run BUILD OUTDIR    runs the reference studies with BUILD/fenestra into OUTDIR
    compare_results.py compare REF NEW     compares every result file of REF with NEW's

`compare` reads NumPy archives (.npz: every array, its dtype, shape and bytes) and JSON files (every
key and value exactly; numbers as written) and ignores what measures time. Exit status 1 on any
difference, naming the file and the key. A key or array only in NEW is an addition, listed apart
("added: ..."): outputs may grow new figures, but every figure REF has must be in NEW, equal."""

import json
import math
import pathlib
import re
import subprocess
import sys

import numpy as np

ROOT = pathlib.Path(__file__).resolve().parent.parent
EXAMPLES = ROOT / "examples"

# (output name, command after the program), with fixed seeds and paths so each run takes seconds.
RUNS = [
    ("reference_contributions", ["contributions", "reference_room/scene.json", "--paths", "512"]),
    ("room_solve", ["solve", "room_study/scene.json", "--paths", "256"]),
    ("catalogue_solve", ["solve", "{scenes}/catalogue_room.json", "--paths", "256"]),
    ("reference_sky", ["sky", "reference_room/scene.json", "--json"]),
    ("thick_contributions", ["contributions", "thick_walls_study/scene.json", "--paths", "256"]),
    ("thick_solve", ["solve", "thick_walls_study/scene.json", "--paths", "256"]),
    ("climate_contributions", ["contributions", "annual_room/climate.json", "--paths", "256"]),
    ("annual", ["annual", "annual_room/climate.json", "--openings", "annual_room/window.json",
                "--paths", "256"]),
    ("annual_cutters", ["annual", "annual_room/climate.json", "--openings", "annual_room/window.json",
                        "--paths", "128", "--cutters"]),
    ("annual_design", ["solve", "annual_room/design.json", "--paths", "256"]),
]

# Where `run` notes the checkout it ran from, so two clones' outputs compare equal.
CHECKOUT_FILE = "checkout.txt"

# Keys whose values are measured times or depend on the machine, not on the computation.
IGNORED = ("seconds", "timings", "time_s", "elapsed", "build_seconds", "threads", "memory")


def catalogue_room(scenes):
    """room_study with a window catalogue and facade rules: the constraint and composition stages."""
    scene = json.loads((EXAMPLES / "room_study/scene.json").read_text())
    scene["geometry"] = str(EXAMPLES / "room_study" / scene["geometry"])
    scene["solver"]["constraints"].update(catalogue="residential", align_sills=True, equal_widths=True)
    scene["solver"]["generations"] = 40
    (scenes / "catalogue_room.json").write_text(json.dumps(scene, indent=1))


def run(build, outdir):
    scenes = outdir / "scenes"
    scenes.mkdir(parents=True, exist_ok=True)
    catalogue_room(scenes)
    program = pathlib.Path(build).resolve() / "fenestra"
    (outdir / CHECKOUT_FILE).write_text(str(ROOT))  # outputs name the examples' paths: see same_text
    for name, args in RUNS:
        command, scene, rest = args[0], args[1], args[2:]
        if command == "sky":
            output = ["-o", str(outdir / f"{name}.hdr"), "--json", str(outdir / f"{name}.json")]
            rest = []
        elif command == "solve":
            output = ["-o", str(outdir / f"{name}.json")]
        else:
            output = ["-o", str(outdir / f"{name}.npz")]
        rest = [str(EXAMPLES / a) if a.endswith(".json") else a for a in rest]
        scene = scene.format(scenes=scenes)
        line = [str(program), command, str(EXAMPLES / scene), *output, *rest,
                "--seed", "7", "--threads", "2", "--quiet"]
        print(" ".join(line), flush=True)
        with open(outdir / f"{name}.stdout", "w") as stdout:
            subprocess.run(line, check=True, stdout=stdout, cwd=outdir)


def ignored(key):
    return any(part in key.lower() for part in IGNORED)


def same_json(a, b, where, differences, dirs, added):
    if isinstance(a, dict) and isinstance(b, dict):
        for key in sorted(set(a) | set(b)):
            if ignored(key):
                continue
            if key not in b:
                differences.append(f"{where}.{key}: only in reference")
            elif key not in a:
                added.append(f"{where}.{key}")
            else:
                same_json(a[key], b[key], f"{where}.{key}", differences, dirs, added)
    elif isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            differences.append(f"{where}: {len(a)} items against {len(b)}")
        for i, (x, y) in enumerate(zip(a, b)):
            same_json(x, y, f"{where}[{i}]", differences, dirs, added)
    elif isinstance(a, float) and isinstance(b, float) and math.isnan(a) and math.isnan(b):
        pass
    elif isinstance(a, str) and isinstance(b, str):
        if same_text(a, dirs[0]) != same_text(b, dirs[1]):
            differences.append(f"{where}: {a[:80]!r} against {b[:80]!r}")
    elif type(a) is not type(b) or a != b:
        differences.append(f"{where}: {str(a)[:80]} against {str(b)[:80]}")


def same_npz(a, b, where, differences, added):
    with np.load(a) as x, np.load(b) as y:
        for key in sorted(set(x.files) | set(y.files)):
            if key not in y.files:
                differences.append(f"{where}:{key}: only in reference")
                continue
            if key not in x.files:
                added.append(f"{where}:{key}")
                continue
            u, v = x[key], y[key]
            if u.dtype != v.dtype or u.shape != v.shape or u.tobytes() != v.tobytes():
                differences.append(f"{where}:{key}: arrays differ")


def same_text(text, folder):
    """A string with its output folder and its checkout's path put as OUT and CHECKOUT."""
    text = text.replace(str(folder), "OUT")
    checkout = folder / CHECKOUT_FILE
    return text.replace(checkout.read_text().strip(), "CHECKOUT") if checkout.exists() else text


def printed(path, folder):
    text = same_text(path.read_text(), folder)
    return re.sub(r"[0-9.]+ s\b", "T s", text)


def compare(reference, new):
    differences, added = [], []
    files = sorted(p for p in reference.iterdir() if p.suffix in (".json", ".npz", ".hdr", ".stdout"))
    if not files:
        differences.append(f"{reference}: no result files")
    for ref in files:
        other = new / ref.name
        if not other.exists():
            differences.append(f"{other}: missing")
        elif ref.suffix == ".npz":
            same_npz(ref, other, ref.name, differences, added)
        elif ref.suffix == ".json":
            same_json(json.loads(ref.read_text()), json.loads(other.read_text()), ref.name, differences,
                      (reference, new), added)
        elif ref.suffix == ".hdr":
            if ref.read_bytes() != other.read_bytes():
                differences.append(f"{ref.name}: bytes differ")
        else:  # printed summaries: equal but for the folder and the seconds
            if printed(ref, reference) != printed(other, new):
                differences.append(f"{ref.name}: printed lines differ")
    for line in differences:
        print(line)
    for where in added:
        print(f"added: {where}")
    print(f"{len(files)} files compared, {len(differences)} differences, {len(added)} added keys")
    return 1 if differences else 0


if __name__ == "__main__":
    if len(sys.argv) == 4 and sys.argv[1] == "run":
        run(sys.argv[2], pathlib.Path(sys.argv[3]).resolve())
    elif len(sys.argv) == 4 and sys.argv[1] == "compare":
        sys.exit(compare(pathlib.Path(sys.argv[2]), pathlib.Path(sys.argv[3])))
    else:
        sys.exit(__doc__)
