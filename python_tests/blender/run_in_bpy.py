"""Runs a test script in the bpy module as `blender -b --python SCRIPT -- ARGS` would:

    python run_in_bpy.py SCRIPT -- ARGS

bpy is imported first (addon_utils, bmesh and the rest are importable only after it), the script
runs as __main__ with sys.argv as Blender gives it, and an exception exits with status 1
(Blender's --python-exit-code 1)."""

import os
import runpy
import sys

import bpy  # noqa: F401

script = os.path.abspath(sys.argv[1])
sys.argv = [script] + sys.argv[2:]
sys.path.insert(0, os.path.dirname(script))
runpy.run_path(script, run_name="__main__")
