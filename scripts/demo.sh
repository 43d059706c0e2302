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
if ! command -v blender >/dev/null; then
  echo "Blender not found: the apartment study in Blender is skipped."
  exit 0
fi
echo "The Blender add-on is installed and enabled: 3D View > Sidebar (N) > Fenestra (docs/blender.md)."
echo
echo "== the apartment, built, solved (Preview quality) and rendered in Blender (examples/build_blend_examples.py)"
start=$(date +%s)
log="$out/blender.log"
if ! blender -b --factory-startup --python-exit-code 1 --python examples/build_blend_examples.py \
     -- "$out" apartment --solve --render >"$log" 2>&1; then
  tail -n 30 "$log"; echo "the Blender study failed (log: $log)"; exit 1
fi
grep '^apartment ' "$log"
cp "$out/apartment_solved_study/result.json" "$out/result.json"
if /usr/bin/python3 -c "import matplotlib" 2>/dev/null; then
  /usr/bin/python3 - "$out/apartment_solved_study" "$out/apartment_goals.png" <<'PY'
import json, os, sys
import numpy as np
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
from matplotlib.colors import LogNorm

study, image = sys.argv[1], sys.argv[2]
scene = json.load(open(os.path.join(study, "scene.json")))
result = json.load(open(os.path.join(study, "result.json")))
points = np.array(scene["sensors"]["points"])
goal = np.array([s["goal"] for s in result["sensors"]], float)
achieved = np.array([s["predicted"] for s in result["sensors"]], float)

# Walls in plan: the footprint of every vertical triangle of the study's geometry.
verts, walls = [], []
for line in open(os.path.join(study, "scene.obj")):
    if line.startswith("v "):
        verts.append([float(c) for c in line.split()[1:4]])
    elif line.startswith("f "):
        tri = np.array([verts[int(t.split("/")[0]) - 1] for t in line.split()[1:4]])
        n = np.cross(tri[1] - tri[0], tri[2] - tri[0])
        if np.linalg.norm(n) > 0 and abs(n[2]) < 1e-3 * np.linalg.norm(n) and tri[:, 2].max() > 0.5:
            xy = tri[:, :2]
            i, j = max(((a, b) for a in range(3) for b in range(a + 1, 3)),
                       key=lambda ab: np.linalg.norm(xy[ab[0]] - xy[ab[1]]))
            walls.append((xy[i], xy[j]))
lo, hi = points[:, :2].min(axis=0) - 1.0, points[:, :2].max(axis=0) + 1.0

fig, axes = plt.subplots(1, 3, figsize=(13, 3.3), dpi=90, constrained_layout=True)
norm = LogNorm(vmin=max(1.0, min(goal.min(), achieved.min())), vmax=max(goal.max(), achieved.max()))
ratio = achieved / goal
panels = [("goal (lux)", goal, "inferno", norm), ("achieved (lux)", achieved, "inferno", norm),
          ("achieved / goal", ratio, "RdBu_r", LogNorm(vmin=0.25, vmax=4.0))]
for ax, (title, values, cmap, n) in zip(axes, panels):
    for a, b in walls:
        ax.plot([a[0], b[0]], [a[1], b[1]], color="0.55", lw=1.2, zorder=1)  # walls
    for o in result["openings"]:
        c = np.array(o["corners"])
        xy = c[:, :2]
        i, j = max(((a, b) for a in range(4) for b in range(a + 1, 4)),
                   key=lambda ab: np.linalg.norm(xy[ab[0]] - xy[ab[1]]))
        if np.ptp(c[:, 2]) < 1e-6:  # a skylight: its outline
            ax.fill(xy[:, 0], xy[:, 1], facecolor="none", edgecolor="deepskyblue", lw=2, zorder=3)
        else:
            ax.plot([xy[i, 0], xy[j, 0]], [xy[i, 1], xy[j, 1]], color="deepskyblue", lw=4, zorder=3,
                    solid_capstyle="butt")
    sc = ax.scatter(points[:, 0], points[:, 1], c=values, cmap=cmap, norm=n, s=60, marker="s", zorder=2)
    ax.set_title(title, fontsize=10)
    ax.set_aspect("equal")
    ax.set_xlim(lo[0], hi[0]); ax.set_ylim(lo[1], hi[1])
    ax.tick_params(labelsize=7)
    if title != "goal (lux)":
        bar = fig.colorbar(sc, ax=ax if title.startswith("achieved /") else axes[:2], shrink=0.8, pad=0.01)
        if title.startswith("achieved /"):
            bar.set_ticks([0.25, 0.5, 1, 2, 4], labels=["0.25", "0.5", "1", "2", "4"])
err = result["error"]
fig.suptitle("%d openings (blue), relative RMS error %.1f %% (predicted), %.1f %% (checked with real cutters)"
             % (len(result["openings"]), 100 * err["relative_rms"],
                100 * err.get("verified", {}).get("relative_rms", float("nan"))), fontsize=10)
fig.savefig(image)
PY
else
  echo "(matplotlib is missing: apt-get install python3-matplotlib for the goal / achieved image)"
fi
/usr/bin/python3 - "$out/result.json" "$(( $(date +%s) - start ))" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
e, t = r["error"], r["timings_s"]
print("apartment: %d openings, relative RMS error %.1f %% (checked with real cutters: %.1f %%), worst sensor %.0f %%;"
      % (len(r["openings"]), 100 * e["relative_rms"], 100 * e["verified"]["relative_rms"], 100 * e["max_relative"]))
print("solve %.1f s (contributions %.1f s), Blender build + solve + render %s s"
      % (t["total"], t["contributions"], sys.argv[2]))
for o in r["openings"]:
    print("  %.2f x %.2f m at (%.2f, %.2f, %.2f), facing (%g, %g, %g)" % ((o["width"], o["height"]) + tuple(o["centre"]) + tuple(round(c, 2) for c in o["normal"])))
PY
echo
echo "== the same study with the residential window catalogue and aligned sills and heads, beside the answer above"
/usr/bin/python3 scripts/demo_composition.py "$out/apartment_solved_study" "$out/apartment_facades.png" 2>/dev/null
echo
echo "Blender outputs in $out/: apartment.blend (the study set up), apartment_solved.blend (solved, cutters"
echo "and Boolean modifiers, sky previewed in the World), apartment_render.png (Cycles, openings cut, ceiling"
echo "hidden from the camera), apartment_goals.png (goal and achieved lux per sensor), apartment_facades.png"
echo "(the facades in elevation: the answer, and the catalogue with aligned sills and heads), result.json,"
echo "apartment_solved_study/ (scene.json, scene.obj, result.json, sky.exr: \`fenestra solve\` re-runs it)."
