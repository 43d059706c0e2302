"""Output safety: output paths checked before the run, never an input, only regular files, and
nothing left behind (no partial file, no temporary) on any failure. CLI and Python."""

import json
import os
import stat
import subprocess
import time

import numpy as np
import pytest

from conftest import CLI

import fenestra


def run(*args, **kw):
    return subprocess.run([CLI, *map(str, args)], capture_output=True, text=True, **kw)


def listing(directory):
    """Every entry (hidden ones too) with its type and, for regular files, content."""
    out = {}
    for name in os.listdir(directory):
        path = os.path.join(directory, name)
        st = os.lstat(path)
        content = open(path, "rb").read() if stat.S_ISREG(st.st_mode) else None
        out[name] = (stat.S_IFMT(st.st_mode), content)
    return out


def assert_refused(r, before, directory, *needles):
    assert r.returncode == 1, (r.returncode, r.stdout, r.stderr)
    assert "fenestra: error:" in r.stderr
    for n in needles:
        assert str(n) in r.stderr, r.stderr
    assert listing(directory) == before  # nothing written, replaced or left behind (no *.tmp*)


def envmap_room(small_room):
    """The small room lit by an environment map next to it: sky.hdr is an input."""
    d = small_room.parent
    fenestra.write_image(str(d / "sky.hdr"), np.full((8, 16, 3), 300.0, np.float32))
    scene = json.loads(small_room.read_text())
    scene["sky"] = {"type": "envmap", "file": "sky.hdr"}
    path = d / "env.json"
    path.write_text(json.dumps(scene))
    return path


# ---- CLI ------------------------------------------------------------------------------------


def test_sky_with_a_summary_in_a_missing_directory_leaves_no_map(small_room):
    d = small_room.parent
    before = listing(d)
    r = run("sky", small_room, "-o", d / "s.exr", "--json", d / "missing" / "s.json", "--quiet")
    assert_refused(r, before, d, "missing", "does not exist")
    assert not (d / "s.exr").exists()


def test_outputs_are_checked_before_the_run(small_room):
    d = small_room.parent
    before = listing(d)
    # A run that would take minutes: refused at once.
    start = time.monotonic()
    r = run("solve", small_room, "-o", d / "nowhere" / "result.json", "--paths", 1 << 22, "--quiet", timeout=120)
    assert_refused(r, before, d, "nowhere", "does not exist")
    assert time.monotonic() - start < 20
    r = run("contributions", small_room, "-o", d / "nowhere" / "c", "--paths", 1 << 22, "--quiet", timeout=120)
    assert_refused(r, before, d, "nowhere")
    # An image format nobody writes is refused before the sky is made too.
    r = run("sky", small_room, "-o", d / "s.unknown", "--quiet")
    assert_refused(r, before, d, "s.unknown")


def test_an_over_long_output_path_is_named_by_its_ends(small_room):
    """A 500-character path is not echoed whole: the message keeps where it starts and the file it
    names, and stays short whatever the path's length."""
    d = small_room.parent
    before = listing(d)
    deep = d / ("missing-" + "x" * 200) / ("y" * 200) / "result.json"
    for command, out in (("solve", deep), ("contributions", deep.with_suffix("")), ("sky", deep.with_suffix(".exr")),
                         ("sky", deep.with_suffix(".png"))):
        r = run(command, small_room, "-o", out, "--quiet")
        assert_refused(r, before, d, str(out)[:60] + "...", str(out)[-40:])
        assert len(r.stderr) < 600, r.stderr
        assert "x" * 100 not in r.stderr and "y" * 130 not in r.stderr, r.stderr
    with pytest.raises(ValueError) as error:
        fenestra.write_image(str(deep.with_suffix(".exr")), np.ones((2, 2, 3), np.float32))
    assert len(str(error.value)) < 600 and str(deep.with_suffix(".exr"))[-40:] in str(error.value)


def test_an_output_may_not_be_an_input(small_room, tmp_path):
    d = small_room.parent
    openings = d / "openings.json"
    openings.write_text(json.dumps({"openings": []}))
    env = envmap_room(small_room)
    before = listing(d)
    os.link(d / "room.obj", d / "hard.obj")
    before = listing(d)
    cases = [  # (arguments, the output refused, the input it would overwrite)
        (("solve", small_room, "-o", small_room), "scene.json", "scene.json"),
        (("contributions", small_room, "-o", d / "scene.npz"), "scene.json", "scene.json"),  # scene.npz + .json
        (("evaluate", small_room, "--openings", openings, "-o", d / "room.obj"), "room.obj", "room.obj"),
        (("evaluate", small_room, "--openings", openings, "-o", openings), "openings.json", "openings.json"),
        (("sky", env, "-o", d / "sky.hdr"), "sky.hdr", "sky.hdr"),
        (("sky", small_room, "-o", d / "s.exr", "--json", small_room), "scene.json", "scene.json"),
        # The same file by another name: through "..", and a hard link.
        (("solve", small_room, "-o", d / ".." / d.name / "scene.json"), "scene.json", "scene.json"),
        (("solve", small_room, "-o", d / "hard.obj"), "hard.obj", "room.obj"),
    ]
    for args, output, input_name in cases:
        r = run(*args, "--quiet")
        assert_refused(r, before, d, "refusing to overwrite an input", "cannot write '", output, input_name)
    assert json.loads(small_room.read_text())["fenestra"] == 1


def test_outputs_must_be_regular_files(small_room):
    d = small_room.parent
    (d / "target.json").write_text("keep")
    os.symlink(d / "target.json", d / "link.json")
    os.symlink(d / "nowhere.json", d / "dangling.json")
    os.mkfifo(d / "fifo.json")
    (d / "folder.json").mkdir()
    devices = []
    if os.geteuid() == 0:  # a device node of our own (the null device), never a system one
        os.mknod(d / "device.json", 0o600 | stat.S_IFCHR, os.makedev(1, 3))
        devices.append(d / "device.json")
    before = listing(d)
    targets = [("link.json", "symbolic link"), ("dangling.json", "symbolic link"),
               ("fifo.json", "not a regular file"), ("folder.json", "directory")] + \
        [(p.name, "not a regular file") for p in devices]
    for i, (name, needle) in enumerate(targets):  # each through one of the commands (a run takes a second)
        args = [("solve", small_room, "-o", d / name), ("sky", small_room, "-o", d / "s.exr", "--json", d / name),
                ("contributions", small_room, "-o", d / name[:-len(".json")])][i % 3]
        r = run(*args, "--quiet")
        assert_refused(r, before, d, name, needle)
    assert (d / "target.json").read_text() == "keep"
    assert os.path.islink(d / "link.json") and stat.S_ISFIFO(os.lstat(d / "fifo.json").st_mode)


def test_a_failed_run_keeps_the_previous_outputs(small_room):
    d = small_room.parent
    r = run("contributions", small_room, "-o", d / "c.npz", "--paths", 128, "--quiet")
    assert r.returncode == 0, r.stderr
    r = run("sky", small_room, "-o", d / "s.exr", "--json", d / "s.json", "--quiet")
    assert r.returncode == 0, r.stderr
    before = listing(d)
    assert {"c.npz", "c.json", "s.exr", "s.json"} <= set(before)
    # The second output of each pair is now refused: the first stays as it was.
    (d / "c.json").unlink()
    (d / "c.json").mkdir()
    before = listing(d)
    r = run("contributions", small_room, "-o", d / "c.npz", "--paths", 128, "--quiet")
    assert_refused(r, before, d, "c.json", "directory")
    r = run("sky", small_room, "-o", d / "s.exr", "--json", d / "c.json", "--quiet")
    assert_refused(r, before, d, "c.json")


def test_successful_writes_leave_only_their_outputs(small_room):
    d = small_room.parent
    before = set(listing(d))
    for args in [("contributions", small_room, "-o", d / "c", "--paths", 128),
                 ("sky", small_room, "-o", d / "s.hdr", "--json", d / "s.json"),
                 ("solve", small_room, "-o", d / "r.json", "--paths", 128)]:
        scene = json.loads(small_room.read_text())
        if args[0] == "solve":
            scene["sensors"]["goals"], scene["sensors"]["goal_units"] = [0.5, 0.3, 0.4], "normalized"
            scene["solver"] = {"generations": 20, "population": 16, "improve_iterations": 100, "verify": False}
            (d / "goals.json").write_text(json.dumps(scene))
            args = ("solve", d / "goals.json") + args[2:]
            before.add("goals.json")
        r = run(*args, "--quiet")
        assert r.returncode == 0, r.stderr
    assert set(listing(d)) == before | {"c.npz", "c.json", "s.hdr", "s.json", "r.json"}
    assert not [n for n in os.listdir(d) if ".tmp" in n or "fenestra-" in n]


# ---- Python ---------------------------------------------------------------------------------


def test_python_writes_are_checked_and_leave_nothing(small_room):
    d = small_room.parent
    scene = fenestra.load_scene(small_room)
    scene.render.paths_per_sensor = 64
    c = fenestra.contributions(scene)
    os.mkfifo(d / "fifo.exr")
    os.symlink(d / "room.obj", d / "link.exr")
    before = listing(d)

    def refused(call, *needles):
        with pytest.raises(ValueError) as info:
            call()
        for n in needles:
            assert n in str(info.value), str(info.value)
        assert listing(d) == before

    refused(lambda: c.save(scene, str(d / "scene")), "scene.json", "input")  # scene.npz + scene.json
    refused(lambda: c.save(scene, str(d / "missing" / "c")), "missing", "does not exist")
    refused(lambda: fenestra.write_sky(scene, d / "missing" / "s.exr"), "missing")
    refused(lambda: fenestra.write_sky(scene, d / "fifo.exr"), "fifo.exr", "not a regular file")
    refused(lambda: fenestra.write_sky(scene, d / "link.exr"), "link.exr", "symbolic link")
    refused(lambda: fenestra.write_sky(scene, d / "room.obj"), "room.obj", "input")
    refused(lambda: fenestra.write_image(str(d / "fifo.exr"), np.zeros((2, 4, 3), np.float32)), "not a regular file")
    env = fenestra.load_scene(envmap_room(small_room))
    before = listing(d)
    refused(lambda: fenestra.write_sky(env, d / "sky.hdr"), "sky.hdr", "input")
    refused(lambda: fenestra.write_sky(env, d / "env.json"), "env.json", "input")
    # And a good write leaves just its files.
    c.save(scene, str(d / "ok"))
    fenestra.write_sky(scene, d / "ok.exr")
    assert set(listing(d)) == set(before) | {"ok.npz", "ok.json", "ok.exr"}


# ---- Outputs keep their values ----------------------------------------------------------------


@pytest.mark.parametrize("name", ["sky.png", "sky.jpg", "sky.tif", "sky.PNG", "sky"])
def test_a_sky_map_in_a_format_that_cannot_keep_cd_per_m2_is_refused_before_any_work(small_room, name):
    d = small_room.parent
    before = listing(d)
    r = run("sky", small_room, "-o", d / name, "--json", d / "summary.json", "--quiet")
    assert_refused(r, before, d, name, ".exr", ".hdr", "cd/m^2")
    (d / "broken.json").write_text("{")  # refused before the scene is read: its error never shows
    before = listing(d)
    r = run("sky", d / "broken.json", "-o", d / name, "--quiet")
    assert_refused(r, before, d, name, ".exr", ".hdr")


@pytest.mark.parametrize("name", ["sky.png", "sky.jpg", "sky.tif", "sky.tiff", "sky.bmp"])
def test_python_refuses_maps_that_cannot_keep_cd_per_m2(small_room, name):
    d = small_room.parent
    scene = fenestra.load_scene(small_room)
    before = listing(d)
    with pytest.raises(ValueError, match=r"\.exr and \.hdr"):
        fenestra.write_sky(scene, d / name)
    with pytest.raises(ValueError, match=r"\.exr and \.hdr"):
        fenestra.write_image(str(d / name), np.full((4, 8, 3), 318.0, np.float32))
    assert listing(d) == before


def test_maps_written_as_exr_and_hdr_keep_their_values(small_room):
    """The formats that are accepted give back the cd/m^2 they were given (a uniform 318 sky)."""
    d = small_room.parent
    scene = json.loads(small_room.read_text())
    scene["sky"] = {"type": "uniform", "radiance": 318.0, "ground_radiance": 318.0}
    path = d / "bright.json"
    path.write_text(json.dumps(scene))
    for name in ("sky.exr", "sky.HDR"):
        r = run("sky", path, "-o", d / name, "--quiet")
        assert r.returncode == 0, r.stderr
        env = json.loads(small_room.read_text())
        env["sky"] = {"type": "envmap", "file": name}
        (d / "env.json").write_text(json.dumps(env))
        pixels = fenestra.sky(fenestra.load_scene(d / "env.json"))["map"]
        assert np.allclose(pixels, 318.0, rtol=1e-2), (name, pixels.min(), pixels.max())


# ---- A device as the stem of a pair -----------------------------------------------------------


@pytest.mark.parametrize("out", ["/dev/null", "/dev/null.npz", "/dev/zero"])
def test_a_pair_beside_a_device_is_refused(small_room, out):
    """`contributions -o /dev/null` used to create /dev/null.npz and /dev/null.json."""
    for suffix in (".npz", ".json"):
        assert not os.path.exists(out.replace(".npz", "") + suffix)
    r = run("contributions", small_room, "-o", out, "--paths", "16", "--quiet")
    assert r.returncode == 1, (r.returncode, r.stdout, r.stderr)
    assert "fenestra: error:" in r.stderr and "a device" in r.stderr and out in r.stderr, r.stderr
    for suffix in (".npz", ".json"):
        assert not os.path.exists(out.replace(".npz", "") + suffix)


def test_a_pair_beside_a_fifo_or_directory_is_refused(small_room):
    d = small_room.parent
    os.mkfifo(d / "fifo")
    (d / "folder").mkdir()
    before = listing(d)
    for out, kind in (("fifo", "a FIFO"), ("fifo.npz", "a FIFO"), ("folder", "a directory")):
        r = run("contributions", small_room, "-o", d / out, "--paths", "16", "--quiet")
        assert_refused(r, before, d, kind, out)
    scene = fenestra.load_scene(small_room)
    scene.render.paths_per_sensor = 16
    c = fenestra.contributions(scene)
    with pytest.raises(ValueError, match="a FIFO"):
        c.save(scene, str(d / "fifo"))
    assert listing(d) == before
    c.save(scene, str(d / "folder.npz"))  # beside a directory of that name, as asked
    assert (d / "folder.npz").is_file() and (d / "folder.json").is_file()
