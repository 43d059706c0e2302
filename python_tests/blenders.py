"""The Blenders the headless add-on suite runs in, and how a script is run in each
(the `blender` fixture in conftest.py gives one per test; docs/blender.md, "Blender versions").

- Debian's Blender 3.4 binary (`blender` on PATH): `blender -b --factory-startup --python SCRIPT`,
  the checkout's addon/fenestra linked into a fresh BLENDER_USER_SCRIPTS/addons.
- Blender 4.5 LTS as the bpy module, in the venv `make bpy-venv` makes (build/bpy-venv, or
  FENESTRA_BPY_PYTHON): `python blender/run_in_bpy.py SCRIPT`. The add-on is the extension zip that
  `make extension` writes (or FENESTRA_EXTENSION_ZIP), installed by Blender's installer as
  bl_ext.user_default.fenestra into user resources (BLENDER_USER_RESOURCES) that the session's runs
  share; without a zip, the checkout's addon/fenestra linked into fresh user resources' add-on
  folder as module `fenestra`.

A script finds the add-on through python_tests/blender/installed.py."""

import atexit
import functools
import glob
import os
import shutil
import subprocess
import tempfile
from dataclasses import dataclass

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
ADDON = os.path.join(ROOT, "addon", "fenestra")
BPY_RUNNER = os.path.join(HERE, "blender", "run_in_bpy.py")
EXTENSION_MODULE = "bl_ext.user_default.fenestra"


def extension_zip():
    """The extension zip the suite installs in bpy: FENESTRA_EXTENSION_ZIP, else the newest
    build/dist/fenestra-*-linux_x64.zip (`make extension`), else None."""
    given = os.environ.get("FENESTRA_EXTENSION_ZIP")
    if given:
        return given
    found = sorted(glob.glob(os.path.join(ROOT, "build", "dist", "fenestra-*-linux_x64.zip")), key=os.path.getmtime)
    return found[-1] if found else None


@functools.cache
def extension_resources(zip_path):
    """User resources shared by the session's bpy runs: the first run installs the zip (its wheel
    unpacks to 150 MB, some seconds), the later ones find it installed and enable it."""
    folder = tempfile.mkdtemp(prefix="fenestra-bpy-user-")
    atexit.register(shutil.rmtree, folder, True)
    return folder


def bpy_python():
    given = os.environ.get("FENESTRA_BPY_PYTHON")
    if given:
        return given
    venv = os.path.join(ROOT, "build", "bpy-venv", "bin", "python")
    return venv if os.path.exists(venv) else None


@dataclass
class Blender:
    name: str                 # the test id: "blender-3.4", "bpy-4.5"
    program: str | None       # the binary, or the venv's python; None: not available
    missing: str              # why not, when program is None

    @property
    def is_bpy(self):
        return self.name.startswith("bpy")

    def command(self, script, args):
        if self.is_bpy:
            return [self.program, BPY_RUNNER, script, "--", *args]
        return [self.program, "-b", "--factory-startup", "--python-exit-code", "1", "--python", script, "--", *args]

    def environment(self, tmp_path):
        """A fresh user folder with the add-on installed (or to be installed) in it."""
        if self.is_bpy:
            zip_path = extension_zip()
            if zip_path:
                return dict(os.environ, BLENDER_USER_RESOURCES=extension_resources(zip_path),
                            FENESTRA_EXTENSION_ZIP=zip_path, FENESTRA_ADDON_MODULE=EXTENSION_MODULE)
            resources = tmp_path / "bpy-user"
            addons = resources / "scripts" / "addons"
            env = dict(os.environ, BLENDER_USER_RESOURCES=str(resources))
        else:
            addons = tmp_path / "scripts" / "addons"
            env = dict(os.environ, BLENDER_USER_SCRIPTS=str(tmp_path / "scripts"))
        addons.mkdir(parents=True, exist_ok=True)
        if not (addons / "fenestra").exists():
            os.symlink(ADDON, addons / "fenestra")
        env.update(FENESTRA_ADDON_MODULE="fenestra")
        env.pop("FENESTRA_EXTENSION_ZIP", None)
        return env

    def run(self, tmp_path, script, *args, timeout=600):
        return subprocess.run(self.command(script, [str(a) for a in args]), capture_output=True, text=True,
                              timeout=timeout, env=self.environment(tmp_path))


def blenders():
    binary = shutil.which("blender")
    python = bpy_python()
    return [Blender("blender-3.4", binary, "Blender is not installed"),
            Blender("bpy-4.5", python, "no bpy venv: run `make bpy-venv` (or set FENESTRA_BPY_PYTHON)")]
