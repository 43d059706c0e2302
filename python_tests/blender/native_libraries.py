"""Prints the Embree, TBB and OpenImageIO libraries loaded once the add-on is enabled and has its
native module (run by test_blender_addon.py in each Blender): one "LIBRARY path" line each."""

import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import installed  # noqa: E402

installed.enable()
native = installed.blender("com.native")
assert native.unavailable() is None, native.unavailable()
with open("/proc/self/maps") as f:
    paths = {line.split()[-1] for line in f if "/" in line}
for path in sorted(paths):
    if any(name in os.path.basename(path) for name in ("embree", "tbb", "OpenImageIO")):
        print("LIBRARY " + path)
