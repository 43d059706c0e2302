"""An annual design, headless: solves a scene with climate goals (by default
examples/annual_room/design.json: sDA300/50% at least 55 %, ASE1000,250 at most 10 %, the least
glazing, Chicago weather) and draws the answer: the floor plan coloured by each sensor's DA300 (percent
of the occupied hours) with the openings on the south wall, the wall's elevation with the openings,
and the goals, what the openings reach and the glazing area in the title. `make demo-annual` runs it.

    /usr/bin/python3 scripts/annual_design_demo.py [SCENE.json [OUT.png [RESULT.json]]]

Every figure is the native core's (fenestra.solve's "climate" object); this script only draws.
"""
import json
import os
import sys
import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "addon"))
import fenestra  # noqa: E402

DEFAULT_SCENE = os.path.join(ROOT, "examples", "annual_room", "design.json")
DEFAULT_PNG = os.path.join(ROOT, "docs", "annual-design.png")
DEFAULT_RESULT = os.path.join(ROOT, "out", "annual_design", "result.json")


def cell_size(points):
    """The sensor grid's spacing (meters): the smallest distance between distinct x or y values."""
    steps = [np.diff(np.unique(np.round(points[:, k], 6))) for k in (0, 1)]
    steps = [s[s > 1e-6].min() for s in steps if (s > 1e-6).any()]
    return min(steps) if steps else 0.5


def figure_text(goal, value):
    """A goal's figure in its unit: fractions as percent, lux as lux."""
    if value is None:
        return "-"
    return "%.0f lx" % value if goal["unit"] == "lux" else "%.0f %%" % (100 * value)


def draw(scene_path, scene, result, out_png, seconds):
    climate = result["climate"]
    points = np.asarray(scene.sensor_points)
    da = 100.0 * np.asarray(climate["per_sensor"]["daylight_autonomy"])
    size = cell_size(points)
    corners = [np.asarray(o["corners"], np.float64) for o in result["openings"]]
    fig, (plan, wall) = plt.subplots(1, 2, figsize=(11, 5.6), constrained_layout=True,
                                     gridspec_kw={"width_ratios": [1.0, 1.1]})
    cmap = plt.get_cmap("viridis")
    for (x, y, _), v in zip(points, da):
        plan.add_patch(plt.Rectangle((x - size / 2, y - size / 2), size, size, color=cmap(v / 100.0)))
    for c in corners:  # in plan, an opening in the south wall is a segment along y = its wall's
        plan.plot(c[:, 0], c[:, 1], color="deepskyblue", linewidth=5, solid_capstyle="butt")
    lo, hi = points.min(axis=0) - size, points.max(axis=0) + size
    plan.set_xlim(lo[0], hi[0])
    plan.set_ylim(lo[1] - 0.3, hi[1])
    plan.set_aspect("equal")
    plan.set_xlabel("x (m, east)")
    plan.set_ylabel("y (m, north)")
    plan.set_title("floor plan: DA300 (% of occupied hours), openings in blue")
    fig.colorbar(plt.cm.ScalarMappable(norm=plt.Normalize(0, 100), cmap=cmap), ax=plan, shrink=0.8,
                 label="DA300 (%)")

    # The south wall's elevation seen from outside (x east to the right): the wall and the openings.
    xs = [c[:, 0] for c in corners]
    zs = [c[:, 2] for c in corners]
    x0, x1, z0, z1 = domain_extent(scene_path)
    wall.add_patch(plt.Rectangle((x0, z0), x1 - x0, z1 - z0, facecolor="0.85", edgecolor="0.3"))
    for x, z in zip(xs, zs):
        wall.add_patch(plt.Rectangle((x.min(), z.min()), np.ptp(x), np.ptp(z), facecolor="lightskyblue",
                                     edgecolor="steelblue", linewidth=1.5))
        wall.annotate("%.2f x %.2f m" % (np.ptp(x), np.ptp(z)), ((x.min() + x.max()) / 2, z.max() + 0.05),
                      ha="center", va="bottom", fontsize=8)
    wall.set_xlim(x0 - 0.2, x1 + 0.2)
    wall.set_ylim(z0 - 0.2, z1 + 0.3)
    wall.set_aspect("equal")
    wall.set_xlabel("x (m, east)")
    wall.set_ylabel("z (m, up)")
    wall.set_title("south wall (opening domain), seen from outside")

    lines = []
    for g in climate["goals"]:
        state = "met" if g["met"] else "NOT met"
        lines.append("%s: %s (%s)" % (g["description"].replace(">=", "≥").replace("<=", "≤"),
                                      figure_text(g, g["achieved"]), state))
    share = climate["glazing_area_m2"] / climate["domain_area_m2"] if climate["domain_area_m2"] else 0.0
    space = climate.get("space") or {}
    en = (space.get("en17037") or {}).get("level_reached")
    en = en if en and en != "none" else "below minimum"
    fig.suptitle("Annual design of %s, %s weather, occupied %s\n%s\nglazing %.2f m² of %.1f m² (%.0f %%)%s, "
                 "%d opening%s; annual mean %.0f lx, EN 17037 %s; solved in %.0f s"
                 % (os.path.basename(os.path.dirname(os.path.abspath(scene_path))), weather_name(scene_path),
                    "-".join(_scene_file(scene_path)["sky"].get("occupied", ["08:00", "18:00"])), "; ".join(lines),
                    climate["glazing_area_m2"], climate["domain_area_m2"], 100 * share,
                    ", least glazing" if climate["least_glazing"] else "", len(corners),
                    "" if len(corners) == 1 else "s", space.get("mean_illuminance_lux", float("nan")), en, seconds),
                 fontsize=9)
    os.makedirs(os.path.dirname(os.path.abspath(out_png)), exist_ok=True)
    fig.savefig(out_png, dpi=110)
    print("wrote %s" % out_png)


def _scene_file(scene_path):
    with open(scene_path) as f:
        return json.load(f)


def weather_name(scene_path):
    weather = _scene_file(scene_path)["sky"].get("weather", "")
    return os.path.splitext(os.path.basename(weather))[0].split(".")[0].replace("_", " ")


def domain_extent(scene_path):
    """(x0, x1, z0, z1) of the opening domain's faces (the OBJ faces of its material or groups), meters."""
    data = _scene_file(scene_path)
    domain = data["opening_domain"]
    chosen = set(domain.get("materials", [])) | set(domain.get("groups", []))
    obj = os.path.join(os.path.dirname(os.path.abspath(scene_path)), data["geometry"])
    group = material = None
    verts, faces = [], []
    with open(obj) as f:
        for line in f:
            parts = line.split()
            if not parts:
                continue
            if parts[0] == "v":
                verts.append([float(t) for t in parts[1:4]])
            elif parts[0] == "g":
                group = parts[1] if len(parts) > 1 else None
            elif parts[0] == "usemtl":
                material = parts[1] if len(parts) > 1 else None
            elif parts[0] == "f" and (group in chosen or material in chosen):
                faces += [int(t.split("/")[0]) - 1 for t in parts[1:]]
    v = np.asarray(verts)[faces]
    return v[:, 0].min(), v[:, 0].max(), v[:, 2].min(), v[:, 2].max()


def main(scene_path=DEFAULT_SCENE, out_png=DEFAULT_PNG, result_path=DEFAULT_RESULT):
    start = time.time()
    scene = fenestra.load_scene(scene_path)
    print("solving %s for its climate goals (%d sensors)..." % (scene_path, len(scene.sensor_points)))
    result = fenestra.solve(scene)
    seconds = time.time() - start
    if "climate" not in result:
        sys.exit("%s has no climate goals (goals.climate): nothing to draw" % scene_path)
    os.makedirs(os.path.dirname(os.path.abspath(result_path)), exist_ok=True)
    with open(result_path, "w") as f:
        json.dump(result, f, indent=1)
    for g in result["climate"]["goals"]:
        print("  %s: %s, %s" % (g["description"], figure_text(g, g["achieved"]), "met" if g["met"] else "not met"))
    print("  glazing %.2f m² of %.2f m²; %.0f s; result in %s" % (result["climate"]["glazing_area_m2"],
                                                               result["climate"]["domain_area_m2"], seconds, result_path))
    draw(scene_path, scene, result, out_png, seconds)


if __name__ == "__main__":
    if len(sys.argv) > 4 or any(a in ("-h", "--help") for a in sys.argv[1:]):
        sys.exit(__doc__)
    main(*sys.argv[1:])
