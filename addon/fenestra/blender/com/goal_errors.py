"""How far each sensor is from its goal, as a person reads it (no bpy here): relative to the goal
where the goal is meaningful, in lux where it is not. A goal far below the others (a dark zone
painted at 1 lx among goals of 300 lx) makes any light a huge relative error, which says nothing:
below a tenth of the sensors' median goal a sensor is judged by its difference in lux, scaled by
that tenth for ranking."""

import numpy as np

MEANINGFUL_SHARE = 0.1  # of the median positive goal


def goal_floor(goal):
    """The goal below which relative errors mean nothing: a tenth of the median positive goal (0
    without positive goals)."""
    positive = np.asarray(goal, dtype=np.float64)
    positive = positive[positive > 0]
    return MEANINGFUL_SHARE * float(np.median(positive)) if len(positive) else 0.0


def scaled_errors(goal, achieved):
    """Per sensor |achieved - goal| / max(goal, floor); -1 for sensors without a goal (goal < 0)."""
    goal, achieved = np.asarray(goal, dtype=np.float64), np.asarray(achieved, dtype=np.float64)
    scale = np.maximum(goal, goal_floor(goal))
    with np.errstate(divide="ignore", invalid="ignore"):
        error = np.where(scale > 0, np.abs(achieved - goal) / scale, 0.0)
    return np.where(goal < 0, -1.0, error)


def describe(goal, achieved, floor):
    """One sensor's distance from its goal, in two lines for a narrow panel: ("12.3 %", "goal 300 lx,
    got 337 lx") where the goal is meaningful, else ("2366 lx off", "goal 1 lx, got 2367 lx")."""
    detail = "goal %.0f lx, got %.0f lx" % (goal, achieved)
    if goal >= floor and goal > 0:
        return "%.1f %%" % (100 * abs(achieved - goal) / goal), detail
    return "%.0f lx off" % abs(achieved - goal), detail
