"""The Annual Daylight sub-panel of Results: the button (or the running job's progress and Cancel),
and the last run's space metrics in the words of daylighting practice (docs/climate-metrics.md).
Drawing only: every figure is the native core's, kept in scene.fenestra.annual."""

import bpy

from ..com import false_colour
from ..study import sky
from . import solve_progress
from .panels import FenestraPanel, draw_warning

VALUE_COLUMN = 0.72  # share of the width for a UDI band's name; its share of the hours to the right


def _percent(fraction):
    return "%.0f %%" % (100.0 * fraction)


def _passes(passed):
    return 'CHECKMARK' if passed else 'X'


def _note(layout, text):
    """A line that explains the figure above it, greyed."""
    row = layout.row()
    row.active = False
    row.label(text=text)


def _band_name(band):
    """A UDI band as "UDI-a 300-3000 lx" (Mardaljevic's four bands by their initials; others by the
    core's name), short enough for the sidebar."""
    name = band.label.split(" (")[0]
    if name in {"fell-short", "supplementary", "autonomous", "exceeded"}:
        name = "UDI-" + name[0]
    if band.lower_lux <= 0:
        return "%s < %g lx" % (name, band.upper_lux)
    if band.upper_lux < 0:
        return "%s > %g lx" % (name, band.lower_lux)
    return "%s %g-%g lx" % (name, band.lower_lux, band.upper_lux)


def _leed_level(levels):
    """(text, passed) for the highest sDA level reached."""
    reached = [level.level for level in levels if level.passed]
    if reached:
        return "LEED v4: %.0f %% level reached" % (100 * max(reached)), True
    return "LEED v4: below the %.0f %% level" % (100 * min(level.level for level in levels)), False


def draw_space_metrics(layout, annual):
    """The space metrics, each with what it means: sDA and its LEED levels, ASE and its limit, DA,
    cDA, the annual mean, the UDI bands, the EN 17037 level. Short lines: the sidebar is narrow."""
    box = layout.box()
    box.label(text="sDA300/50%%: %s" % _percent(annual.spatial_daylight_autonomy), icon='LIGHT_AREA')
    _note(box, "floor ≥ 300 lx half the hours")
    if len(annual.sda_levels):
        text, passed = _leed_level(annual.sda_levels)
        box.label(text=text, icon=_passes(passed))
    box = layout.box()
    if annual.has_ase:
        box.label(text="ASE1000,250: %s" % _percent(annual.annual_sunlight_exposure), icon='LIGHT_SUN')
        _note(box, "floor > 1000 lx sun, > 250 h")
        box.label(text="LEED v4 (≤ 10 %%): %s" % ("passes" if annual.ase_passes else "fails"),
                  icon=_passes(annual.ase_passes))
    else:
        box.label(text="ASE: no direct sun", icon='INFO')
    box = layout.box()
    col = box.column(align=True)
    col.label(text="DA300: %s" % _percent(annual.daylight_autonomy))
    col.label(text="cDA300: %s" % _percent(annual.continuous_daylight_autonomy))
    col.label(text="Annual mean: %.0f lx" % annual.mean_illuminance)
    _note(col, "of the occupied hours, floor mean")
    if len(annual.udi):
        box = layout.box()
        box.label(text="Useful daylight, hours:")
        col = box.column(align=True)
        for band in annual.udi:
            split = col.split(factor=VALUE_COLUMN, align=True)
            split.label(text=_band_name(band))
            split.label(text=_percent(band.space_fraction))
    level = annual.en17037_level
    layout.label(text="EN 17037: %s" % (level if level else "below minimum"), icon=_passes(bool(level)))


def draw_run(layout, annual):
    """What the figures are of: the weather, the occupied hours, the openings, the run."""
    col = layout.column(align=True)
    col.active = False
    col.label(text=annual.weather or "-", icon='WORLD')
    col.label(text="%s, %d h a year" % (annual.occupied_period or "-", annual.occupied_hours))
    col.label(text="%d opening%s, %d paths per sensor" % (annual.openings, "" if annual.openings == 1 else "s",
                                                          annual.paths))
    col.label(text="%.1f s%s" % (annual.seconds, ", light paths reused" if annual.reused else ""))


class FENESTRA_PT_annual(FenestraPanel, bpy.types.Panel):
    bl_label = "Annual Daylight"
    bl_parent_id = "FENESTRA_PT_results"

    @classmethod
    def poll(cls, context):
        settings = context.scene.fenestra
        return settings.sky.type == 'CLIMATE' or settings.annual.valid

    def draw(self, context):
        layout, settings = self.layout, context.scene.fenestra
        annual, display = settings.annual, settings.display
        problem = sky.climate_problem(settings.sky)
        if problem:
            draw_warning(layout, problem)
        if settings.sky.type != 'CLIMATE':
            layout.label(text="Sky is no longer Climate:", icon='INFO')
            _note(layout, "figures of the last run")
        elif not solve_progress.draw(layout):  # while a job runs: its progress and Cancel
            row = layout.row()
            row.enabled = problem is None
            row.operator("fenestra.annual_daylight", icon='TIME')
        if not annual.valid:
            _note(layout, "Of the openings as their cutters stand")
            return
        row = layout.row(align=True)
        row.label(text="Show:")
        row.prop(display, "annual_metric", text="")
        if display.false_colour != 'ANNUAL':
            layout.prop(display, "false_colour", text="False Colour")
        elif display.annual_metric not in false_colour.SHARES_OF_TIME:
            layout.prop(display, "colour_max")
        if annual.note:
            draw_warning(layout, annual.note)
        draw_space_metrics(layout, annual)
        draw_run(layout, annual)


classes = (FENESTRA_PT_annual,)
