"""Annual daylight of a climate scene on its floor plan: runs the annual study of the given
openings and draws each sensor's DA300 (and its ASE hours) as coloured cells, with the space's sDA,
ASE and EN 17037 level in the title. Used for the README's annual example.

    /usr/bin/python3 scripts/annual_floor_plan.py SCENE.json OPENINGS.json OUT.png
"""
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "addon"))
import fenestra  # noqa: E402


def cell_size(points):
    """The sensor grid's spacing (meters): the smallest distance between distinct x or y values."""
    steps = [np.diff(np.unique(np.round(points[:, k], 6))) for k in (0, 1)]
    steps = [s[s > 1e-6].min() for s in steps if (s > 1e-6).any()]
    return min(steps) if steps else 0.5


def draw(scene_path, openings_path, out_png):
    scene = fenestra.load_scene(scene_path)
    with open(openings_path) as f:
        openings = json.load(f)
    year = fenestra.annual(scene, openings)
    space, per_sensor = year["summary"]["space"], year["summary"]["per_sensor"]
    points = np.asarray(scene.sensor_points)
    size = cell_size(points)
    fig, axes = plt.subplots(1, 2, figsize=(10, 5.2), constrained_layout=True)
    panels = [("DA300 (% of occupied hours)", 100 * np.asarray(per_sensor["daylight_autonomy"]), "viridis", 0, 100),
              ("hours of direct sun above 1000 lux", np.asarray(per_sensor["ase_hours"]), "magma", 0, None)]
    for ax, (title, values, cmap, lo, hi) in zip(axes, panels):
        hi = hi if hi is not None else max(250.0, float(values.max()))
        for (x, y, _), v in zip(points, values):
            colour = plt.get_cmap(cmap)((v - lo) / (hi - lo) if hi > lo else 0.0)
            ax.add_patch(plt.Rectangle((x - size / 2, y - size / 2), size, size, color=colour))
        for o in openings["openings"]:
            c = np.asarray(o["corners"])
            ax.plot(c[:, 0], c[:, 1], color="deepskyblue", linewidth=4, solid_capstyle="butt")
        ax.set_xlim(points[:, 0].min() - size, points[:, 0].max() + size)
        ax.set_ylim(points[:, 1].min() - size, points[:, 1].max() + size)
        ax.set_aspect("equal")
        ax.set_xlabel("x (m, east)")
        ax.set_ylabel("y (m, north)")
        ax.set_title(title)
        fig.colorbar(plt.cm.ScalarMappable(norm=plt.Normalize(lo, hi), cmap=cmap), ax=ax, shrink=0.8)
    fig.suptitle("%s: sDA300/50%% %.0f %%, ASE1000,250 %.0f %% (%s), EN 17037 %s, mean %.0f lx\n%s"
                 % (os.path.basename(os.path.dirname(os.path.abspath(scene_path))), 100 * space["spatial_daylight_autonomy"],
                    100 * space["annual_sunlight_exposure"], "passes" if space["ase_passes"] else "fails",
                    space["en17037"]["level_reached"], space["mean_illuminance_lux"],
                    "%s, occupied %02g:00-%02g:00, %d hours" % (os.path.basename(year["summary"]["weather"]),
                                                              year["summary"]["occupied"]["start_hour"],
                                                              year["summary"]["occupied"]["end_hour"],
                                                              year["summary"]["occupied_hours"])),
                 fontsize=9)
    fig.savefig(out_png, dpi=110)
    print("wrote %s" % out_png)


if __name__ == "__main__":
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    draw(*sys.argv[1:])
