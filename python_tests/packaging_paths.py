"""Where `make wheel` put its wheel and its packaging venv (scripts/build_wheel.sh)."""

import os

import pytest

from conftest import ROOT

BUILD = os.path.join(ROOT, "build")


def built_wheel():
    path = os.environ.get("FENESTRA_WHEEL")
    if not path:
        try:
            with open(os.path.join(BUILD, "wheel-path.txt")) as f:
                path = os.path.join(ROOT, f.read().strip())
        except FileNotFoundError:
            pytest.fail("no wheel built: run `make wheel` (or set FENESTRA_WHEEL)")
    assert os.path.isfile(path), "the wheel %s is gone: run `make wheel`" % path
    return path


def packaging_python(venv=False):
    """The packaging venv's python, or (venv=False) the Python 3.11 it was made from (pyenv's)."""
    root = os.path.join(BUILD, "venv", "packaging")
    if not os.path.isfile(os.path.join(root, "pyvenv.cfg")):
        pytest.fail("no packaging venv: run `make wheel`")
    if venv:
        return os.path.join(root, "bin", "python")
    with open(os.path.join(root, "pyvenv.cfg")) as f:
        config = dict(line.split(" = ", 1) for line in f.read().splitlines() if " = " in line)
    return config["executable"]


def bpy_python():
    """Blender 4.5 as a Python module: FENESTRA_BPY_PYTHON, else the project's bpy venv (make bpy-venv)."""
    path = os.environ.get("FENESTRA_BPY_PYTHON") or os.path.join(BUILD, "bpy-venv", "bin", "python")
    if not os.path.exists(path):
        pytest.skip("no bpy 4.5 venv (%s): `make bpy-venv`, or set FENESTRA_BPY_PYTHON" % path)
    return path
