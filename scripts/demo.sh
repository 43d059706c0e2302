#!/usr/bin/env bash
# make demo: the main job on the bundled reference room. Results land in out/demo/.
set -euo pipefail
build=${1:-build}
cd "$(dirname "$0")/.."
out=out/demo
mkdir -p "$out"
scene=examples/reference_room/scene.json

echo "== contribution matrix of the south wall's 192 elements (one pass of paths per sensor)"
"$build/fenestra" contributions "$scene" -o "$out/contributions.npz" --quiet
echo
echo "== ground truth: the reference window really cut, path-traced"
"$build/fenestra" evaluate "$scene" --openings examples/reference_room/window.json -o "$out/window.json" --paths 65536 --quiet
echo
/usr/bin/python3 - "$out" <<'PY'
import json, sys
out = sys.argv[1]
radiance = [66.90, 258.96, 258.96, 66.90, 50.68, 81.13, 81.13, 50.68,
            30.73, 36.73, 36.73, 30.73, 22.83, 25.33, 25.33, 22.83]
sensors = json.load(open(out + "/window.json"))["sensors"]
print("sensor  Fenestra lux (stderr)   Radiance lux   difference")
for i, (s, r) in enumerate(zip(sensors, radiance)):
    print("%4d   %9.2f (%5.2f)   %10.2f   %+6.2f %%" % (i, s["value"], s["stderr"], r, 100 * (s["value"] / r - 1)))
PY
echo
echo "Results are in $out/: contributions.npz (E, A, T, ... for numpy.load), contributions.json"
echo "(every element with its panel, row, column and corners), window.json (per-sensor lux)."
if command -v blender >/dev/null; then echo "The Blender add-on is installed and enabled: 3D View > Sidebar (N) > Fenestra (docs/blender.md)."; fi
