"""False colour: a sensor value as a colour, and the scale the legend shows (no bpy, no drawing).

Achieved lux and daylight factors use a sequential map from 0 to the top of the scale; achieved /
goal a diverging one on a log scale from 1/4 to 4, white at 1, so that too dark and too bright are
told apart at a glance."""

import math

import numpy as np

# Viridis at nine evenly spaced points (sRGB): dark to bright, readable by colour-blind viewers.
SEQUENTIAL = ((0.267, 0.005, 0.329), (0.282, 0.157, 0.471), (0.243, 0.290, 0.537),
              (0.192, 0.408, 0.557), (0.149, 0.510, 0.557), (0.122, 0.620, 0.537),
              (0.208, 0.718, 0.475), (0.427, 0.804, 0.349), (0.992, 0.906, 0.145))
# Blue (below the goal) - white (on it) - red (above), at log2(ratio) = -2 ... 2.
DIVERGING = ((0.129, 0.400, 0.675), (0.404, 0.663, 0.812), (0.820, 0.898, 0.941), (0.969, 0.969, 0.969),
             (0.992, 0.859, 0.780), (0.937, 0.541, 0.384), (0.698, 0.094, 0.169))
NO_VALUE = (0.5, 0.5, 0.5)
RATIO_STOPS = 2.0  # the diverging scale spans 2**-2 ... 2**2

TITLES = {'ACHIEVED': ("Achieved illuminance", "lx"), 'RATIO': ("Achieved / goal", ""),
          'DAYLIGHT_FACTOR': ("Daylight factor", "%"),
          # An Annual Daylight run's per-sensor metrics (display_settings.ANNUAL_METRICS).
          'DA': ("Daylight autonomy DA300, occupied hours", "%"),
          'CDA': ("Continuous daylight autonomy cDA300", "%"),
          'UDI_A': ("UDI autonomous, 300-3000 lx", "%"),
          'MEAN': ("Annual mean illuminance", "lx"),
          'ASE_HOURS': ("Hours of direct sun > 1000 lx", "h"),
          # A solve with climate goals: its openings' year (climate_results.QUANTITIES).
          'CLIMATE_DA': ("Daylight autonomy DA300 of the solve", "%"),
          'CLIMATE_MEAN': ("Annual mean illuminance of the solve", "lx"),
          'CLIMATE_ASE_HOURS': ("Hours of direct sun > 1000 lx, solve", "h")}
# Percent of the occupied hours: always 0 to 100.
SHARES_OF_TIME = frozenset({'DA', 'CDA', 'UDI_A', 'CLIMATE_DA'})


class Scale:
    """Values to positions 0..1 on the colour bar, their colours, and the ticks to label."""

    def __init__(self, quantity, top):
        self.quantity, self.top = quantity, top
        title, self.units = TITLES[quantity]
        self.title = title + (" (%s)" % self.units if self.units else "")

    def title_for(self, values):
        """The legend's title over `values` (NaN: none at that sensor), saying why none has one."""
        values = np.asarray(values, np.float64)
        if not np.isfinite(values).any():
            if self.quantity == 'DAYLIGHT_FACTOR':
                return self.title + ": not known (choose it again)"
            if self.quantity.startswith("CLIMATE_"):  # a trade-off's openings: only the answer's year is kept
                return self.title + ": not known for a trade-off (Annual Daylight gives it)"
            return self.title + ": no goals"
        if self.quantity == 'RATIO' and not np.isfinite(values).all():
            return self.title + ", grey: no goal"
        return self.title

    def position(self, values):
        values = np.asarray(values, np.float64)
        with np.errstate(divide="ignore", invalid="ignore"):
            if self.quantity == 'RATIO':
                t = (np.log2(values) + RATIO_STOPS) / (2 * RATIO_STOPS)
            else:
                t = values / self.top
        return np.clip(t, 0.0, 1.0)

    def colours(self, values):
        """RGBA per value (NaN: grey)."""
        values = np.asarray(values, np.float64)
        table = np.array(DIVERGING if self.quantity == 'RATIO' else SEQUENTIAL)
        x = self.position(np.nan_to_num(values, nan=1.0)) * (len(table) - 1)
        low = np.minimum(np.floor(x).astype(int), len(table) - 2)
        w = (x - low)[:, None]
        rgb = table[low] * (1 - w) + table[low + 1] * w
        rgb[~np.isfinite(values)] = NO_VALUE
        return np.hstack([rgb, np.ones((len(rgb), 1))])

    def ticks(self):
        """[(position 0..1, label)] along the bar."""
        if self.quantity == 'RATIO':
            values = [2.0 ** k for k in range(-int(RATIO_STOPS), int(RATIO_STOPS) + 1)]
            return [(float(self.position([v])[0]), "%g" % v) for v in values]
        step = nice_step(self.top / 4)
        count = int(math.floor(self.top / step + 1e-9))
        return [(i * step / self.top, "%g" % round(i * step, 6)) for i in range(count + 1)]


def nice_step(span):
    """1, 2 or 5 times a power of ten, at least span."""
    if not span > 0:
        return 1.0
    power = 10.0 ** math.floor(math.log10(span))
    return next(m * power for m in (1, 2, 5, 10) if m * power >= span * (1 - 1e-9))


def nice_top(largest):
    """The top of a scale from 0 that holds `largest`: a multiple of a 1-2-5 step."""
    if not largest > 0:
        return 1.0
    step = nice_step(largest / 5)
    return step * math.ceil(largest / step - 1e-9)


def values(quantity, goal, achieved, horizontal_illuminance):
    """Per sensor: lux, achieved / goal (NaN without a goal) or percent (NaN when the sky's
    horizontal illuminance is not known)."""
    goal, achieved = np.asarray(goal, np.float64), np.asarray(achieved, np.float64)
    if quantity == 'ACHIEVED':
        return achieved
    if quantity == 'RATIO':
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(goal > 0, achieved / goal, np.nan)
    if horizontal_illuminance > 0:
        return 100.0 * achieved / horizontal_illuminance
    return np.full(achieved.shape, np.nan)


def scale_for(quantity, shown, top=0.0):
    """The scale of these values: `top` when set, else the largest value rounded up (shares of the
    occupied hours always span 0 to 100 %, so that two runs compare by colour)."""
    if quantity in SHARES_OF_TIME:
        top = 100.0
    elif quantity != 'RATIO' and not top > 0:
        finite = np.asarray(shown, np.float64)
        finite = finite[np.isfinite(finite)]
        top = nice_top(float(finite.max()) if len(finite) else 0.0)
    return Scale(quantity, top)
