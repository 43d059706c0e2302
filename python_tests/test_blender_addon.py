"""The Blender add-on, headless: registration, a solved study, save/reload, bad setups
(python_tests/blender/addon_study.py), the openings cut through zero-thickness and solid walls
(python_tests/blender/addon_holes.py), sensor grids over solid rooms (python_tests/blender/addon_sensor_grid.py)
and the openings cut through a curved wall, whose UV map is exported
(python_tests/blender/addon_curved.py), messages and setup checks (python_tests/blender/addon_checks.py)
and Evaluate on moved cutters (python_tests/blender/addon_evaluate.py), the Sun Position add-on's place and date
(python_tests/blender/addon_sun_position.py), undo and redo of a solve (python_tests/blender/addon_undo.py)
and materials (python_tests/blender/addon_materials.py), run inside each Blender of the `blender` fixture (blenders.py)
with the add-on installed there."""

import os
import shutil
import subprocess

import pytest

import blenders

BLENDER = shutil.which("blender")
HERE = os.path.dirname(os.path.abspath(__file__))
ADDON = os.path.join(os.path.dirname(HERE), "addon", "fenestra")


def test_addon_study(blender, tmp_path):
    r = blender.run(tmp_path, os.path.join(HERE, "blender", "addon_study.py"), str(tmp_path / "out"))
    assert r.returncode == 0, r.stdout[-4000:] + r.stderr[-4000:]
    assert "Ran 22 tests" in r.stderr and "OK" in r.stderr, r.stderr[-2000:]


def test_openings_cut_through_the_walls(blender, tmp_path):
    """Rays through the result's openings reach the sky, in a closed box room, an open mesh and a
    room with a 0.3 m solid south wall; rays beside them hit the wall."""
    r = blender.run(tmp_path, os.path.join(HERE, "blender", "addon_holes.py"), str(tmp_path / "out"))
    assert r.returncode == 0, r.stdout[-4000:] + r.stderr[-4000:]
    assert "Ran 8 tests" in r.stderr and "OK" in r.stderr, r.stderr[-2000:]


def test_openings_cut_through_a_curved_wall(blender, tmp_path):
    """The active UV map is exported with the geometry; a curved opening's cutter follows the
    wall, so rays through it reach the sky and rays beside it hit the wall; a flat one's is a box."""
    r = blender.run(tmp_path, os.path.join(HERE, "blender", "addon_curved.py"), str(tmp_path / "out"))
    assert r.returncode == 0, r.stdout[-4000:] + r.stderr[-4000:]
    assert "Ran 7 tests" in r.stderr and "OK" in r.stderr, r.stderr[-2000:]


def test_messages_and_setup_checks(blender, tmp_path):
    """Refusals name objects and fields, not scene-file keys or paths; hidden marked objects are
    named as hidden; goal fields stay in range; Check Setup warns, with counts, about goals all 0,
    sensors outdoors or facing down, rooms open to the sky, domain faces seen from the wrong side."""
    r = blender.run(tmp_path, os.path.join(HERE, "blender", "addon_checks.py"), str(tmp_path / "out"))
    assert r.returncode == 0, r.stdout[-4000:] + r.stderr[-4000:]
    assert "Ran 19 tests" in r.stderr and "OK" in r.stderr, r.stderr[-2000:]


def test_sensor_grids_over_the_rooms_floors(blender, tmp_path):
    """Add Sensor Grid on a solid room (walls, floor and ceiling one mesh) lays its sensors at the
    height above the floor's upper face, off the walls and the domain, so Check Setup finds nothing
    and a solve's check with real cutters agrees with its prediction; a solid holding two rooms gets
    a sensor object per room; the inset and refusals follow the settings."""
    r = blender.run(tmp_path, os.path.join(HERE, "blender", "addon_sensor_grid.py"), str(tmp_path / "out"))
    assert r.returncode == 0, r.stdout[-4000:] + r.stderr[-4000:]
    assert "Ran 6 tests" in r.stderr and "OK" in r.stderr, r.stderr[-2000:]


def test_evaluate_moved_cutters(blender, tmp_path):
    """After a solve, a cutter moved 0.5 m along the wall (or scaled) is read back as its rectangle
    and path-traced: the results change to what fenestra.evaluate gives for that rectangle, within
    standard errors; cutters off the wall, and curved ones once moved, are refused in plain words."""
    r = blender.run(tmp_path, os.path.join(HERE, "blender", "addon_evaluate.py"), str(tmp_path / "out"))
    assert r.returncode == 0, r.stdout[-4000:] + r.stderr[-4000:]
    assert "Ran 5 tests" in r.stderr and "OK" in r.stderr, r.stderr[-2000:]


def test_a_failing_blender_test_fails(blender, tmp_path):
    """The runner sees failures: a script whose test fails exits non-zero."""
    script = tmp_path / "failing.py"
    script.write_text("import sys, unittest\n"
                      "class T(unittest.TestCase):\n"
                      "    def test_fails(self):\n"
                      "        self.fail('on purpose')\n"
                      "r = unittest.main(argv=[sys.argv[0]], exit=False).result\n"
                      "sys.exit(0 if r.wasSuccessful() else 1)\n")
    r = blender.run(tmp_path, str(script))
    assert r.returncode != 0


@pytest.mark.skipif(BLENDER is None, reason="Blender is not installed")
def test_addon_registers_without_the_native_module(tmp_path):
    """A copy of the package without _core: the add-on registers, the panel says why."""
    copy = tmp_path / "pkg" / "fenestra"
    shutil.copytree(ADDON, copy, ignore=shutil.ignore_patterns("_core*.so", "__pycache__"))
    scripts = tmp_path / "scripts"
    (scripts / "addons").mkdir(parents=True)
    os.symlink(copy, scripts / "addons" / "fenestra")
    script = tmp_path / "no_core.py"
    script.write_text(
        "import os, sys\n"
        # Only the copy: not a checkout put on the path by `make install`.
        "sys.path[:] = [p for p in sys.path if p == %r\n"
        "               or not os.path.isfile(os.path.join(p, 'fenestra', '__init__.py'))]\n"
        "import addon_utils, bpy\n"
        "addon_utils.enable('fenestra', default_set=True, handle_error=None)\n"
        "assert hasattr(bpy.types.Scene, 'fenestra')\n"
        "from fenestra.blender.com import native\n"
        "assert 'make build' in native.unavailable(), native.unavailable()\n"
        "try:\n"
        "    bpy.ops.fenestra.solve_openings()\n"
        "    raise SystemExit('solved without the native module')\n"
        "except RuntimeError as exc:\n"
        "    assert 'native module' in str(exc), exc\n"
        "addon_utils.disable('fenestra', default_set=True, handle_error=None)\n"
        % str(scripts / "addons"))
    env = dict(os.environ, BLENDER_USER_SCRIPTS=str(scripts), PYTHONPATH="")
    cmd = [BLENDER, "-b", "--factory-startup", "--python-exit-code", "1", "--python", str(script)]
    r = subprocess.run(cmd, capture_output=True, text=True, timeout=300, env=env)
    assert r.returncode == 0, r.stdout[-3000:] + r.stderr[-3000:]


def test_sun_position_place_and_date(blender, tmp_path):
    """Sun Position's place, date and north reach the sky where it is installed (bundled in 3.4: the
    test must run there); where it is not (a fresh bpy 4.5: an extension from 4.2 on), the sky
    takes Fenestra's own fields."""
    r = blender.run(tmp_path, os.path.join(HERE, "blender", "addon_sun_position.py"))
    assert r.returncode == 0, r.stdout[-4000:] + r.stderr[-4000:]
    assert "Ran 2 tests" in r.stderr and "OK" in r.stderr, r.stderr[-2000:]
    if blender.name == "blender-3.4":
        assert "skipped" not in r.stderr, r.stderr[-2000:]


def test_undo_and_redo(blender, tmp_path):
    """A solve's cutters, modifiers and results go with its undo step and come back with redo."""
    r = blender.run(tmp_path, os.path.join(HERE, "blender", "addon_undo.py"), str(tmp_path / "out"))
    assert r.returncode == 0, r.stdout[-4000:] + r.stderr[-4000:]
    assert "Ran 2 tests" in r.stderr and "OK" in r.stderr, r.stderr[-2000:]


def test_materials(blender, tmp_path):
    """Principled BSDF transmission (renamed "Transmission Weight" in 4.0) is glass, rough is
    diffuse, metallic glossy; Glass and Diffuse BSDFs; no node tree is grey."""
    r = blender.run(tmp_path, os.path.join(HERE, "blender", "addon_materials.py"))
    assert r.returncode == 0, r.stdout[-4000:] + r.stderr[-4000:]
    assert "Ran 4 tests" in r.stderr and "OK" in r.stderr, r.stderr[-2000:]


def test_native_libraries_in_bpy(blender, tmp_path):
    """In bpy 4.5 with the add-on installed from the extension zip, Embree, TBB and OpenImageIO
    come from bpy's own folder or the extension's vendored wheel, none from the system. (A
    development build linked into bpy loads Debian's Embree 3 beside bpy's Embree 4, and takes bpy's
    libtbb.so.12 for Debian's, the same name: docs/blender.md, "Blender versions".)"""
    if not blender.is_bpy or blenders.extension_zip() is None:
        pytest.skip("needs bpy and the extension zip (make extension)")
    r = blender.run(tmp_path, os.path.join(HERE, "blender", "native_libraries.py"))
    assert r.returncode == 0, r.stdout[-3000:] + r.stderr[-3000:]
    libraries = [line.split(" ", 1)[1] for line in r.stdout.splitlines() if line.startswith("LIBRARY ")]
    assert any("embree" in p for p in libraries) and any("tbb" in p for p in libraries), libraries
    system = [p for p in libraries if p.startswith(("/usr/", "/lib"))]
    assert not system, system
