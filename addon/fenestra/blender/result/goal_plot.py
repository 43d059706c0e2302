"""The goal-versus-achieved plot of a result, `goals_vs_achieved.png` in the study folder, and
showing it in an Image Editor. Drawn with matplotlib, from the study's result.json."""

import json
import os

import bpy
from ...wording import counted

PLOT_NAME = "goals_vs_achieved.png"


class PlotUnavailable(RuntimeError):
    """matplotlib cannot be imported into Blender's Python; the message says how to get it."""


def _pyplot():
    try:
        import matplotlib
    except ImportError as exc:
        raise PlotUnavailable("The plot needs matplotlib in Blender's Python (%s): on Debian, "
                              "apt-get install python3-matplotlib; with Blender's own Python, "
                              "install it with that Python's pip" % exc) from None
    matplotlib.use("Agg")  # files only: no window toolkit inside Blender
    import matplotlib.pyplot as plt
    return plt


def write(result, path):
    """Plots achieved against goal lux for every sensor with a goal (the line: achieved = goal;
    hollow: checked with real cutters when the result has it) into the PNG at path."""
    plt = _pyplot()
    import numpy as np
    sensors = [s for s in result["sensors"] if s.get("goal") is not None]
    goal = np.array([s["goal"] for s in sensors], float)
    achieved = np.array([s["predicted"] for s in sensors], float)
    checked = np.array([s.get("verified", np.nan) for s in sensors], float)
    fig, ax = plt.subplots(figsize=(6.0, 5.0), dpi=100, constrained_layout=True)
    try:
        every = np.concatenate([goal, achieved, checked[np.isfinite(checked)]])
        positive = every[every > 0]
        lo, hi = (positive.min(), positive.max()) if len(positive) else (1.0, 10.0)
        logarithmic = hi / lo > 20.0
        if logarithmic:
            ax.set_xscale("log")
            ax.set_yscale("log")
            lo, hi = lo / 1.3, hi * 1.3
        else:
            lo, hi = 0.0, hi * 1.1
        ax.plot([lo, hi], [lo, hi], color="0.4", lw=1, label="achieved = goal")
        ax.fill_between([lo, hi], [0.9 * lo, 0.9 * hi], [1.1 * lo, 1.1 * hi], color="0.85", lw=0,
                        label="within 10 %")
        ax.scatter(goal, achieved, s=18, color="tab:blue", zorder=3, label="predicted")
        if np.isfinite(checked).any():
            ax.scatter(goal, checked, s=30, facecolors="none", edgecolors="tab:orange", zorder=2,
                       label="checked (openings cut)")
        ax.set_xlim(lo, hi)
        ax.set_ylim(lo, hi)
        ax.set_aspect("equal")
        ax.set_xlabel("goal (lx)")
        ax.set_ylabel("achieved (lx)")
        ax.grid(True, which="major", color="0.92")
        ax.legend(loc="upper left", fontsize=8)
        error = result.get("error", {})
        ax.set_title("%s, %s, relative RMS error %.1f %%"
                     % (counted(len(sensors), "sensor"), counted(len(result.get("openings", [])), "opening"), 100 * error.get("relative_rms", 0.0)),
                     fontsize=10)
        fig.savefig(path)
    finally:
        plt.close(fig)
    return path


def write_for_study(study_path):
    """The plot of the result in the study folder of scene.json at study_path; returns its path."""
    directory = os.path.dirname(study_path)
    with open(os.path.join(directory, "result.json")) as f:
        result = json.load(f)
    return write(result, os.path.join(directory, PLOT_NAME))


def load(path):
    """The plot as an image datablock, read again from the file."""
    image = bpy.data.images.load(path, check_existing=True)
    image.reload()
    return image


def show(context, image):
    """Shows the image in an Image Editor: one of this window's, else a new window."""
    for area in context.screen.areas:
        if area.type == 'IMAGE_EDITOR':
            area.spaces.active.image = image
            area.tag_redraw()
            return
    windows = set(context.window_manager.windows)
    # The button's own context, not an override: an operator under one can crash Blender while
    # another Python thread runs (docs/blender.md, "Scripts and threads").
    bpy.ops.screen.area_dupli('INVOKE_DEFAULT')  # the current area, in a window of its own
    new = [w for w in context.window_manager.windows if w not in windows]
    if not new:
        return
    area = new[0].screen.areas[0]
    area.type = 'IMAGE_EDITOR'
    area.spaces.active.image = image
