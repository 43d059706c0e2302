#!/usr/bin/env bash
# Makes VENV (default build/bpy-venv): Blender 4.5 LTS as the bpy module, at requirements/bpy.txt's pins,
# from a Python 3.11 that is not Debian's /usr/bin/python3 (BPY_PYTHON, default: the `python3` first
# on PATH). Does nothing when VENV was made from the same requirements file.
# The bpy wheel is 373 MB: PIP_FIND_LINKS=DIR takes it from a folder that holds it instead of PyPI.
set -euo pipefail
cd "$(dirname "$0")/.."
venv=${1:-build/bpy-venv}
requirements=requirements/bpy.txt
python=${BPY_PYTHON:-python3}
stamp="$venv/.requirements"

if [ -f "$stamp" ] && cmp -s "$stamp" "$requirements" && "$venv/bin/python" -c "import bpy" 2>/dev/null; then
  exit 0
fi
if ! command -v "$python" >/dev/null; then
  echo "bpy-venv: no $python on PATH (a Python 3.11 is needed for bpy 4.5; set BPY_PYTHON)" >&2
  exit 1
fi
if [ "$(readlink -f "$(command -v "$python")")" = "$(readlink -f /usr/bin/python3)" ]; then
  echo "bpy-venv: $python is Debian's Python; set BPY_PYTHON to another Python 3.11 (bpy is never installed into Debian's)" >&2
  exit 1
fi
version=$("$python" -c 'import sys; print("%d.%d" % sys.version_info[:2])')
if [ "$version" != "3.11" ]; then
  echo "bpy-venv: $python is Python $version; bpy 4.5 needs Python 3.11 (set BPY_PYTHON)" >&2
  exit 1
fi
echo "bpy-venv: making $venv (bpy 4.5, $requirements)"
rm -rf "$venv"
"$python" -m venv "$venv"
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check --no-deps -r "$requirements"
"$venv/bin/python" -c "import bpy; assert bpy.app.version[:2] == (4, 5), bpy.app.version_string"
cp "$requirements" "$stamp"
