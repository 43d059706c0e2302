"""The Blender extension zip (`make extension`, docs/install.md): its manifest and layout checked
by Blender's own validator (bpy 4.5's extension command line) or, without one, against the
manifest's rules; installed with Blender's installer in bpy 4.5, it runs as
bl_ext.user_default.fenestra with _core from the bundled wheel."""

import glob
import os
import re
import subprocess
import tomllib
import zipfile

import pytest

from conftest import EXAMPLES, ROOT
from packaging_paths import BUILD, bpy_python, built_wheel


def extension_zip():
    version = os.path.basename(built_wheel()).split("-")[1]
    path = os.path.join(BUILD, "dist", "fenestra-%s-linux_x64.zip" % version)
    assert os.path.isfile(path), "no %s: run `make extension`" % path
    return path


def manifest():
    with zipfile.ZipFile(extension_zip()) as z:
        return tomllib.loads(z.read("blender_manifest.toml").decode())


def blender_ext_cli():
    """Blender's extension command line (blender_ext.py, run by `blender --command extension`),
    from the bpy 4.5 venv, or None."""
    try:
        root = os.path.dirname(os.path.dirname(bpy_python()))
    except pytest.skip.Exception:
        return None
    found = glob.glob(os.path.join(root, "lib", "python3.*", "site-packages", "bpy", "*", "scripts",
                                   "addons_core", "bl_pkg", "cli", "blender_ext.py"))
    return found[0] if found else None


def test_the_zip_holds_the_manifest_the_shim_and_the_wheel_once():
    with zipfile.ZipFile(extension_zip()) as z:
        names = sorted(z.namelist())
    wheel = os.path.basename(built_wheel())
    assert names == ["__init__.py", "blender_manifest.toml", "wheels/" + wheel]
    # Every Python file of the add-on is in the wheel only: the zip's __init__.py imports it.
    with open(os.path.join(ROOT, "addon", "extension", "__init__.py")) as f:
        assert "from fenestra import register, unregister" in f.read()


def test_the_manifest_names_this_build():
    m = manifest()
    version = os.path.basename(built_wheel()).split("-")[1]
    with open(os.path.join(ROOT, "addon", "fenestra", "__init__.py")) as f:
        bl_info_version = ".".join(re.search(r'"version": \((\d+), (\d+), (\d+)\)', f.read()).groups())
    assert m["version"] == version == bl_info_version
    assert m["id"] == "fenestra" and m["type"] == "add-on" and m["schema_version"] == "1.0.0"
    assert m["blender_version_min"] == "4.2.0"
    assert m["platforms"] == ["linux-x64"]
    assert m["wheels"] == ["./wheels/" + os.path.basename(built_wheel())]
    assert set(m["permissions"]) == {"files"}


def test_blenders_validator_accepts_the_zip():
    cli = blender_ext_cli()
    if cli is None:
        pytest.skip("no Blender 4.2+ extension command line (bpy 4.5 venv): see test_the_manifest_keeps_the_schema_rules")
    ok = subprocess.run([bpy_python(), cli, "validate", extension_zip()], capture_output=True, text=True)
    assert ok.returncode == 0 and "Success" in ok.stdout, ok.stdout + ok.stderr


def test_blenders_validator_refuses_a_broken_manifest(tmp_path):
    """The validator run above can fail: a tagline ending in a full stop is refused."""
    cli = blender_ext_cli()
    if cli is None:
        pytest.skip("no Blender 4.2+ extension command line (bpy 4.5 venv)")
    broken = tmp_path / "broken.zip"
    with zipfile.ZipFile(extension_zip()) as src, zipfile.ZipFile(broken, "w") as dst:
        for item in src.infolist():
            data = src.read(item)
            if item.filename == "blender_manifest.toml":
                data = data.replace(b'daylight goals"', b'daylight goals."')
            dst.writestr(item, data)
    bad = subprocess.run([bpy_python(), cli, "validate", str(broken)], capture_output=True, text=True)
    assert bad.returncode != 0 and "tagline" in bad.stdout + bad.stderr, bad.stdout + bad.stderr


def test_the_manifest_keeps_the_schema_rules():
    """The rules of schema 1.0.0 that Blender's validator applies, checked without Blender."""
    m = manifest()
    for key, kind in (("schema_version", str), ("id", str), ("version", str), ("name", str), ("tagline", str),
                      ("maintainer", str), ("type", str), ("license", list), ("blender_version_min", str)):
        assert isinstance(m.get(key), kind) and m[key], key
    assert m["id"].isidentifier() and not m["id"].startswith("_")
    for terse in [m["tagline"]] + list(m["permissions"].values()):
        assert len(terse) <= 64 and (terse[-1].isalnum() or terse[-1] in ")]}"), terse
    assert all(s.startswith("SPDX:") for s in m["license"])
    assert set(m["permissions"]) <= {"files", "network", "clipboard", "camera", "microphone"}
    assert m["blender_version_min"].count(".") == 2
    for wheel in m["wheels"]:
        assert wheel.startswith("./") and "\\" not in wheel and wheel.endswith(".whl")
        assert 5 <= len(os.path.basename(wheel).split("-")) <= 6


INSTALL = r"""
import importlib, os, sys
import bpy
result = bpy.ops.extensions.package_install_files(filepath=sys.argv[-2], repo="user_default", enable_on_install=True)
assert result == {"FINISHED"}, result
ext = importlib.import_module("bl_ext.user_default.fenestra")
import fenestra
assert "bl_ext.user_default.fenestra" in bpy.context.preferences.addons.keys()
assert hasattr(bpy.types.Scene, "fenestra"), "the add-on did not register its properties"
ops = [name for name in dir(bpy.ops.fenestra)]
for name in ("solve_openings", "add_sensor_grid", "annual_daylight", "check_setup"):
    assert name in ops, (name, ops)
scene = fenestra.load_scene(os.path.join(sys.argv[-1], "reference_room", "scene.json"))  # an OpenEXR sky
print("EXTENSION", ext.__file__)
print("FENESTRA", fenestra.__file__)
print("CORE", fenestra._core.__file__)
print(open("/proc/self/maps").read())
"""


def test_blenders_installer_installs_and_enables_the_extension(tmp_path):
    """bpy 4.5's installer (Get Extensions > Install from Disk) takes the zip; the add-on registers as
    bl_ext.user_default.fenestra, fenestra and _core come from the wheel it installed in the
    extensions' site-packages (not Blender's own), and Embree, TBB and OpenImageIO are the wheel's
    renamed copies or Blender's own, never the system's."""
    python = bpy_python()
    env = {k: v for k, v in os.environ.items() if not k.startswith(("PYTHON", "FENESTRA"))}
    env["BLENDER_USER_RESOURCES"] = str(tmp_path / "blender")
    out = subprocess.run([python, "-c", INSTALL, extension_zip(), EXAMPLES], env=env, capture_output=True,
                         text=True, timeout=600)
    assert out.returncode == 0, out.stdout[-3000:] + out.stderr[-3000:]
    lines = dict(line.split(" ", 1) for line in out.stdout.splitlines()
                 if line.startswith(("EXTENSION ", "FENESTRA ", "CORE ")))
    extensions = str(tmp_path / "blender" / "extensions")
    assert lines["EXTENSION"] == os.path.join(extensions, "user_default", "fenestra", "__init__.py")
    site = os.path.join(extensions, ".local", "lib", "python3.11", "site-packages", "fenestra")
    assert lines["FENESTRA"] == os.path.join(site, "__init__.py")
    assert lines["CORE"].startswith(site + os.sep + "_core.")
    bpy_root = os.path.dirname(os.path.dirname(python))
    mapped = {line.split(None, 5)[5] for line in out.stdout.splitlines() if len(line.split(None, 5)) == 6}
    native = [p for p in mapped if any(n in os.path.basename(p) for n in ("embree", "tbb", "OpenImageIO"))]
    ours = [p for p in native if p.startswith(os.path.join(extensions, ".local"))]
    assert any("libembree3-" in p for p in ours) and any("libOpenImageIO-" in p for p in ours), native
    assert all(p.startswith(bpy_root) or p in ours for p in native), native
