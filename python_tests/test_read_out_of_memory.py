"""A failed allocation is never the end of a file. Under an address-space limit (prlimit --as,
RLIMIT_AS) too small for a large OBJ, reading it used to stop where memory ran out and the rest
was taken for the end of the file: a box plus a 2-million-triangle occluder loaded as 12 triangles,
exit status 0, both outputs written. Now the run ends with "out of memory while reading geometry
file '...'", status 1 (MemoryError in Python) and nothing written."""

import json
import os
import shutil
import subprocess
import sys

import pytest

from conftest import CLI, ROOT, write_small_room

PRLIMIT = shutil.which("prlimit")
BIG_OBJ_BYTES = 64 << 20
MiB = 1 << 20


def write_study(directory, occluder_bytes, sky=None):
    """scene.json and room.obj: the small room, then (after it in the file) an occluder outside it made
    of the same triangle repeated until the OBJ is about occluder_bytes larger."""
    path = write_small_room(directory, paths=16)
    block = b"v 1 -5 0\nv 2 -5 0\nv 1 -5 1\nf -3 -2 -1\n"
    with open(directory / "room.obj", "ab") as f:
        f.write(b"o occluder\nusemtl grey\n")
        f.write(block * (occluder_bytes // len(block)))
    scene = json.loads(path.read_text())
    scene["sensors"]["points"] = scene["sensors"]["points"][:1]
    scene["sky"] = sky or {"type": "uniform", "radiance": 318.0}
    scene["render"]["threads"] = 1
    path.write_text(json.dumps(scene))
    return path


def run_capped(cap, *args):
    return subprocess.run([PRLIMIT, "--as=%d" % cap, "--", CLI, *map(str, args)], capture_output=True, text=True)


def cap_to_load(directory):
    """The smallest address-space limit (to 4 MiB) under which the program gets through reading a
    small room's OBJ, building its domain and sensors, to the sky: there the sky's missing file
    ends the run. Found by bisection (a dozen runs of a few milliseconds)."""
    scene = write_study(directory, 0, sky={"type": "envmap", "file": "missing.exr"})
    lo, hi = 16 * MiB, 4096 * MiB
    def loads(cap):
        r = run_capped(cap, "contributions", scene, "-o", directory / "out", "--max-memory", "100G", "--quiet")
        return r.returncode == 1 and "missing.exr" in r.stderr
    assert loads(hi), "the small room does not load even under a 4 GiB limit"
    while hi - lo > 4 * MiB:
        mid = (lo + hi) // 2
        lo, hi = (lo, mid) if loads(mid) else (mid, hi)
    return hi


@pytest.mark.skipif(PRLIMIT is None or not os.path.exists(CLI), reason="needs prlimit and the built CLI")
def test_a_mesh_too_large_for_memory_is_refused_not_cut_short(tmp_path):
    small, big = tmp_path / "small", tmp_path / "big"
    small.mkdir(), big.mkdir()
    cap = cap_to_load(small) + BIG_OBJ_BYTES // 2  # room for half the file's bytes
    scene = write_study(big, BIG_OBJ_BYTES)
    before = sorted(os.listdir(big))
    r = run_capped(cap, "contributions", scene, "-o", big / "o.npz", "--max-memory", "100G", "--quiet")
    assert r.returncode == 1, (r.returncode, r.stdout, r.stderr)
    assert "fenestra: error: out of memory while reading geometry file '%s'" % (big / "room.obj") in r.stderr, r.stderr
    assert sorted(os.listdir(big)) == before  # nothing written


PYTHON_UNDER_LIMIT = r"""
import resource, sys
sys.path.insert(0, sys.argv[1])
import fenestra
def in_use():
    for line in open("/proc/self/status"):
        if line.startswith("VmSize:"):
            return int(line.split()[1]) * 1024
limit = in_use() + int(sys.argv[3])
resource.setrlimit(resource.RLIMIT_AS, (limit, limit))
try:
    fenestra.load_scene(sys.argv[2], max_memory="100G")
except MemoryError as exc:
    print("MemoryError:", exc)
    sys.exit(3)
print("loaded")
"""


@pytest.mark.skipif(sys.platform != "linux", reason="reads /proc/self/status")
def test_python_raises_memory_error_naming_the_file(tmp_path):
    scene = write_study(tmp_path, BIG_OBJ_BYTES)
    r = subprocess.run([sys.executable, "-c", PYTHON_UNDER_LIMIT, os.path.join(ROOT, "addon"), str(scene),
                        str(BIG_OBJ_BYTES // 2)], capture_output=True, text=True)
    assert r.returncode == 3, (r.returncode, r.stdout, r.stderr)
    assert "MemoryError: out of memory while reading geometry file '%s'" % (tmp_path / "room.obj") in r.stdout
