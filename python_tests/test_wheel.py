"""The wheel (`make wheel`, docs/install.md) installed with pip in a fresh venv of a Python 3.11
that is not Debian's: `fenestra solve` on an example copied out of the checkout, `import fenestra`,
and no system Embree, TBB or OpenImageIO in the processes (their /proc maps), only the wheel's own
renamed copies; auditwheel's view of the wheel agrees."""

import os
import re
import shutil
import signal
import subprocess
import time
import zipfile

import pytest

from conftest import EXAMPLES, ROOT, write_small_room
from packaging_paths import built_wheel, packaging_python

# The libraries Blender also ships (libtbb.so.12, libembree4.so.4) and the heaviest system one.
GUARDED = re.compile(r"lib(embree\d*|tbb\w*|OpenImageIO\w*)[-.]")
# auditwheel's renamed copy: libNAME-<8 hex>.so..., the hash before the first dot
VENDORED = re.compile(r"^lib[^/]*-[0-9a-f]{8}\.")


def guarded_libraries(paths):
    return sorted({p for p in paths if GUARDED.search(os.path.basename(p))})


def mapped_files(maps_text):
    return {line.split(None, 5)[5] for line in maps_text.splitlines() if len(line.split(None, 5)) == 6}


def check_only_vendored(paths, venv):
    libs = guarded_libraries(paths)
    assert libs, "no Embree, TBB or OpenImageIO mapped at all: the check saw nothing"
    outside = [p for p in libs if not (p.startswith(str(venv)) and VENDORED.match(os.path.basename(p)))]
    assert not outside, "libraries loaded from outside the wheel or under their system names: %s" % outside


@pytest.fixture(scope="module")
def venv(tmp_path_factory):
    """A fresh venv of pyenv's Python 3.11 (which never saw Debian's paths), the wheel installed."""
    base = packaging_python()
    path = tmp_path_factory.mktemp("wheel_venv") / "venv"
    subprocess.run([base, "-m", "venv", str(path)], check=True)
    pip = [str(path / "bin" / "python"), "-m", "pip", "install", "-q", "--disable-pip-version-check"]
    subprocess.run(pip + ["-r", os.path.join(ROOT, "requirements", "wheel-test.txt")], check=True)
    subprocess.run(pip + ["--no-deps", built_wheel()], check=True)
    return path


@pytest.fixture
def outside(tmp_path):
    """Examples copied to a folder outside the checkout."""
    assert not str(tmp_path).startswith(ROOT)
    for name in ("room_study", "reference_room"):
        shutil.copytree(os.path.join(EXAMPLES, name), tmp_path / name)
    return tmp_path


def clean_env(venv):
    """The venv's bin first, nothing of the checkout or of Debian's Python on the paths."""
    env = {k: v for k, v in os.environ.items() if not k.startswith(("PYTHON", "FENESTRA", "LD_"))}
    env["PATH"] = "%s:%s" % (venv / "bin", env.get("PATH", ""))
    return env


def test_the_venv_python_never_saw_debians_paths(venv):
    out = subprocess.run([str(venv / "bin" / "python"), "-c", "import sys; print('\\n'.join(sys.path))"],
                         capture_output=True, text=True, check=True, env=clean_env(venv)).stdout
    assert "/usr/lib/python3" not in out and "dist-packages" not in out, out


def test_fenestra_solve_runs_from_the_wheel_with_its_own_libraries(venv, outside):
    """The console command (the program exec'd by fenestra.command) solves, and every Embree, TBB
    and OpenImageIO mapped while it ran is the wheel's (the envmap scene loads OpenImageIO)."""
    command = str(venv / "bin" / "fenestra")
    env = clean_env(venv)
    seen = set()
    runs = [([command, "solve", "scene.json", "-o", "result.json", "--paths", "256", "--quiet"], "room_study"),
            ([command, "contributions", "scene.json", "-o", "contrib", "--paths", "512", "--quiet"],
             "reference_room")]
    for args, folder in runs:
        proc = subprocess.Popen(args, cwd=outside / folder, env=env, stdout=subprocess.PIPE,
                                stderr=subprocess.PIPE, text=True)
        while proc.poll() is None:  # the program is this pid after the exec: read its maps as it runs
            try:
                with open("/proc/%d/maps" % proc.pid) as f:
                    seen |= mapped_files(f.read())
            except (FileNotFoundError, ProcessLookupError):
                break
            time.sleep(0.02)
        out, err = proc.communicate()
        assert proc.returncode == 0, err
    result = (outside / "room_study" / "result.json").read_text()
    assert '"openings"' in result
    assert (outside / "reference_room" / "contrib.npz").is_file()
    assert any(p.endswith("/fenestra/fenestra") for p in seen), "the wheel's program did not run"
    assert any(os.path.basename(p).startswith("libOpenImageIO-") for p in seen), "the image module was not seen"
    check_only_vendored(seen, venv)


def test_fenestra_command_keeps_exit_status_and_usage(venv, outside):
    env = clean_env(venv)
    bad = subprocess.run([str(venv / "bin" / "fenestra"), "solve", "missing.json", "-o", "r.json"],
                         cwd=outside, env=env, capture_output=True, text=True)
    assert bad.returncode == 1, bad.stderr
    assert "missing.json" in bad.stderr
    usage = subprocess.run([str(venv / "bin" / "fenestra"), "frobnicate"], cwd=outside, env=env,
                           capture_output=True, text=True)
    assert usage.returncode == 2 and "unknown command 'frobnicate'" in usage.stderr


def test_fenestra_command_is_interrupted_like_the_program(venv, tmp_path):
    """SIGINT reaches the program itself (no Python in between): status 130, no output left."""
    scene = write_small_room(tmp_path / "room", paths=1 << 22)
    proc = subprocess.Popen([str(venv / "bin" / "fenestra"), "contributions", str(scene), "-o",
                             str(tmp_path / "out")], env=clean_env(venv), stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True)
    deadline = time.time() + 60
    while time.time() < deadline:  # wait for the exec: the pid's program is then the wheel's
        try:
            if os.readlink("/proc/%d/exe" % proc.pid).endswith("/fenestra/fenestra"):
                break
        except OSError:
            pass
        time.sleep(0.05)
    time.sleep(1.0)
    proc.send_signal(signal.SIGINT)
    _, err = proc.communicate(timeout=60)
    assert proc.returncode == 130, err
    assert not list(tmp_path.glob("out*"))


def test_import_fenestra_from_the_wheel_maps_only_its_own_libraries(venv, outside):
    """`import fenestra` in the venv takes the installed package, and a scene with an environment
    map (OpenImageIO) evaluated there maps no system Embree, TBB or OpenImageIO (/proc/self/maps)."""
    code = r"""
import sys, fenestra
scene = fenestra.load_scene("reference_room/scene.json")
scene.render.paths_per_sensor = 256
c = fenestra.contributions(scene)
print("MODULE", fenestra.__file__, fenestra._core.__file__)
print(open("/proc/self/maps").read())
"""
    out = subprocess.run([str(venv / "bin" / "python"), "-c", code], cwd=outside, env=clean_env(venv),
                         capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    module_line, maps = out.stdout.split("\n", 1)
    assert module_line.split()[1].startswith(str(venv)), module_line
    check_only_vendored(mapped_files(maps), venv)


def manylinux_base(tag):
    """The system libraries a manylinux wheel of this tag may use (auditwheel's policy)."""
    import glob
    import json
    venv = os.path.dirname(os.path.dirname(packaging_python(venv=True)))
    policy = glob.glob(os.path.join(venv, "lib", "python3.*", "site-packages", "auditwheel", "policy",
                                    "manylinux-policy.json"))[0]
    with open(policy) as f:
        return set(next(p["lib_whitelist"] for p in json.load(f) if p["name"] == tag))


def test_the_wheel_needs_nothing_outside_it_but_the_manylinux_base(venv):
    """The wheel is tagged manylinux (auditwheel repair found every library it needs vendorable); the
    program, the modules and every vendored library need only renamed libraries of the wheel or the
    manylinux base of its tag (libc, libstdc++, libX11, ...), and ldd resolves every Embree, TBB and
    OpenImageIO inside the wheel. (`auditwheel show` says the same, in minutes over 250 libraries.)"""
    tag = re.search(r"manylinux_(\d+)_(\d+)_x86_64", os.path.basename(built_wheel()))
    assert tag, "auditwheel repair did not make a manylinux wheel: %s" % built_wheel()
    assert int(tag.group(1)) == 2 and int(tag.group(2)) <= 36, "needs a newer glibc than Debian 12's 2.36"
    base = manylinux_base("manylinux_%s_%s" % (tag.group(1), tag.group(2))) | {"linux-vdso.so.1"}
    package = next((venv / "lib").glob("python3.*/site-packages/fenestra"))
    libs = package.parent / "fenestra.libs"
    vendored = {p.name for p in libs.iterdir()}
    binaries = [package / "fenestra", package / "fenestra_images.so"] + list(package.glob("_core*.so"))
    for binary in binaries + sorted(libs.iterdir()):
        dynamic = subprocess.run(["readelf", "-d", str(binary)], capture_output=True, text=True, check=True).stdout
        for name in re.findall(r"\(NEEDED\)\s+Shared library: \[(.+?)\]", dynamic):
            assert name in base or name.startswith("ld-linux") or (name in vendored and VENDORED.match(name)), \
                "%s needs %s, neither vendored nor in the manylinux base" % (binary.name, name)
        ldd = subprocess.run(["ldd", str(binary)], capture_output=True, text=True, check=True).stdout
        assert "not found" not in ldd, ldd
        resolved = [line.split("=>")[1].split("(")[0].strip() for line in ldd.splitlines() if "=>" in line]
        outside = [p for p in guarded_libraries(resolved) if not os.path.normpath(p).startswith(str(libs))]
        assert not outside, "%s resolves %s outside the wheel" % (binary.name, outside)


def test_the_wheel_holds_the_package_once(venv):
    names = zipfile.ZipFile(built_wheel()).namelist()
    package = [n for n in names if n.startswith("fenestra/")]
    assert "fenestra/blender/__init__.py" in package and "fenestra/command.py" in package
    assert not [n for n in names if "__pycache__" in n or n.endswith(".pyc")]
    assert "fenestra/fenestra" in package and "fenestra/fenestra_images.so" in package
    sources = sorted(os.path.relpath(os.path.join(d, f), os.path.join(ROOT, "addon"))
                     for d, _, files in os.walk(os.path.join(ROOT, "addon", "fenestra"))
                     for f in files if f.endswith(".py"))
    assert sorted(n for n in package if n.endswith(".py")) == sources


def core_bindings(venv, cwd, preload, code="import fenestra"):
    """Which file each of _core's Embree calls binds to (LD_DEBUG=bindings), with `preload` loaded
    RTLD_GLOBAL first, as a host's own libraries are (Blender's executable links libembree4.so.4)."""
    script = "import ctypes, os\nctypes.CDLL(%r, mode=os.RTLD_GLOBAL)\n%s\n" % (preload, code)
    env = dict(clean_env(venv), LD_DEBUG="bindings", LD_DEBUG_OUTPUT=str(cwd / "ld"))
    out = subprocess.run([str(venv / "bin" / "python"), "-c", script], cwd=cwd, env=env,
                         capture_output=True, text=True)
    assert out.returncode == 0, out.stderr[-2000:]
    bound = {}
    for log in cwd.glob("ld.*"):
        for m in re.finditer(r"binding file (\S+) \[\d+\] to (\S+) \[\d+\]: normal symbol `(\w*rtc\w+)'", log.read_text()):
            if "/_core." in m.group(1):
                bound[m.group(3).replace("fenestra_", "")] = m.group(2)
    return bound, out.stdout


def test_core_binds_to_its_own_embree_when_the_host_has_one_global(venv, tmp_path):
    """With the system's Embree loaded RTLD_GLOBAL first (standing in for a host's, under the same
    symbol names), _core's Embree calls still bind to the wheel's copy (its symbols renamed,
    scripts/rename_embree_symbols.py)."""
    system = "/usr/lib/x86_64-linux-gnu/libembree3.so.3"
    if not os.path.exists(system):
        pytest.skip("no system Embree 3 to stand in for a host's (%s)" % system)
    bound, _ = core_bindings(venv, tmp_path, system)
    assert {"rtcNewDevice", "rtcIntersect1"} <= set(bound), bound
    assert all("/fenestra.libs/libembree3-" in path for path in bound.values()), bound


def test_blenders_embree4_global_does_not_change_the_numbers(venv, tmp_path):
    """Blender 4.5's own libembree4.so.4 (from the bpy venv) loaded RTLD_GLOBAL first: the
    contributions are the same numbers, bit for bit, as without it (bound to Embree 4 they were not:
    every sensor came out 'outdoors')."""
    from packaging_paths import bpy_python
    embree4 = glob_one(os.path.dirname(os.path.dirname(bpy_python())), "lib/python3.11/site-packages/bpy/lib/libembree4.so.4")
    shutil.copytree(os.path.join(EXAMPLES, "room_study"), tmp_path / "room_study")
    code = ("import fenestra, numpy\ns = fenestra.load_scene('room_study/scene.json')\n"
            "s.render.paths_per_sensor = 256\nprint(repr(fenestra.contributions(s).all_open.tolist()))")
    with_host, out_host = core_bindings(venv, tmp_path, embree4, code)
    alone = subprocess.run([str(venv / "bin" / "python"), "-c", code], cwd=tmp_path, env=clean_env(venv),
                           capture_output=True, text=True, check=True).stdout
    assert out_host == alone


def glob_one(root, pattern):
    import glob
    found = glob.glob(os.path.join(root, pattern))
    assert found, "no %s under %s" % (pattern, root)
    return found[0]
