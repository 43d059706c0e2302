"""make demo, last part: the apartment's study solved again with a window catalogue and aligned
sills, next to the solution with the automatic constraints alone: the facades in elevation, each
with its openings and the errors.

    /usr/bin/python3 scripts/demo_composition.py STUDY_DIR OUT.png

STUDY_DIR is a study folder (scene.json, scene.obj, result.json: the add-on's solve). Writes
result_catalogue.json beside its result.json."""

import json
import os
import sys

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "addon"))
import fenestra  # noqa: E402

COMPOSED = {"catalogue": "residential", "align_sills": True, "align_heads": True}


def solve_composed(study):
    with open(os.path.join(study, "scene.json")) as f:
        scene = json.load(f)
    constraints = dict(scene.get("solver", {}).get("constraints", {}), **COMPOSED)
    scene["solver"] = dict(scene.get("solver", {}), constraints=constraints)
    result = fenestra.solve(fenestra.scene_from_dict(scene, study))
    with open(os.path.join(study, "result_catalogue.json"), "w") as f:
        json.dump(result, f, indent=1)
    return result


def facades(results):
    """Wall openings grouped by outward normal (rounded), over all results: {normal: label}."""
    out = {}
    for result in results:
        for o in result["openings"]:
            n = tuple(int(round(c)) for c in o["normal"])
            if n[2] == 0:
                out.setdefault(n, {(1, 0, 0): "east", (-1, 0, 0): "west", (0, 1, 0): "north",
                                   (0, -1, 0): "south"}.get(n, str(n)))
    return out


def draw(results, titles, image):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.patches import Rectangle
    walls = sorted(facades(results).items(), key=lambda kv: kv[1])
    fig, axes = plt.subplots(len(results), len(walls), figsize=(6 * len(walls), 2.4 * len(results) + 0.6), dpi=90,
                             squeeze=False, constrained_layout=True)
    for col, (normal, name) in enumerate(walls):
        along = np.cross([0, 0, 1], normal)  # horizontal, as seen from outside
        xs = [np.asarray(o["corners"]) @ along for r in results for o in r["openings"]
              if tuple(int(round(c)) for c in o["normal"]) == normal]
        lo, hi = min(x.min() for x in xs) - 1.0, max(x.max() for x in xs) + 1.0
        for row, (result, title) in enumerate(zip(results, titles)):
            ax = axes[row][col]
            for o in result["openings"]:
                if tuple(int(round(c)) for c in o["normal"]) != normal:
                    continue
                c = np.asarray(o["corners"])
                x, z = c @ along, c[:, 2]
                ax.add_patch(Rectangle((x.min(), z.min()), np.ptp(x), np.ptp(z), facecolor="lightskyblue",
                                       edgecolor="steelblue", lw=1.5))
                ax.text(x.mean(), z.max() + 0.05, "%.2f x %.2f" % (o["width"], o["height"]), ha="center",
                        va="bottom", fontsize=7)
            ax.axhline(0.0, color="0.4", lw=1)
            ax.set_xlim(lo, hi)
            ax.set_ylim(-0.2, 3.2)
            ax.set_aspect("equal")
            ax.set_title("%s facade, %s" % (name, title), fontsize=9)
            ax.tick_params(labelsize=7)
    fig.savefig(image)


def summary(result):
    e = result["error"]
    checked = e.get("verified") or {}
    return "%d openings, %.1f %% predicted, %.1f %% checked" % (
        len(result["openings"]), 100 * e["relative_rms"], 100 * checked.get("relative_rms", float("nan")))


def main():
    study, image = sys.argv[1], sys.argv[2]
    with open(os.path.join(study, "result.json")) as f:
        free = json.load(f)
    composed = solve_composed(study)
    print("automatic constraints:                 " + summary(free))
    print("residential catalogue, aligned sills and heads: " + summary(composed))
    for step in composed["composition"]:
        print("  %s: %.1f %% -> %.1f %%%s" % (step["rule"], 100 * step["error_before"], 100 * step["error_after"],
                                            "" if step["met"] else " (not met)"))
    print("  constraints met: %s" % composed["constraints_met"])
    try:
        draw([free, composed], ["automatic constraints: %s" % summary(free),
                                "catalogue, aligned sills and heads: %s" % summary(composed)], image)
    except ImportError:
        print("(matplotlib is missing: apt-get install python3-matplotlib for the facade image)")


if __name__ == "__main__":
    main()
