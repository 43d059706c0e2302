"""The Annual Daylight sub-panel of Results: the button (or the running job's progress and Cancel),
and the last run's space metrics in the words of daylighting practice (docs/climate-metrics.md).
Drawing only: every figure is the native core's, kept in scene.fenestra.annual."""

import bpy

from . import false_colour, sky, solve_progress
from .panels import FenestraPanel, draw_warning

VALUE_COLUMN = 0.64  # share of the width for the names; the values to the right


def _percent(fraction):
    return "%.0f %%" % (100.0 * fraction)


def _row(layout, name, value, icon='NONE'):
    split = layout.split(factor=VALUE_COLUMN, align=True)
    split.label(text=name, icon=icon)
    split.label(text=value)


def _passes(passed):
    return 'CHECKMARK' if passed else 'X'


def draw_space_metrics(layout, annual):
    """The space metrics: sDA with its pass levels, ASE, DA, cDA, UDI, the mean, EN 17037."""
    box = layout.box()
    _row(box, "Spatial daylight autonomy", _percent(annual.spatial_daylight_autonomy), 'LIGHT_AREA')
    box.label(text="sDA300/50%: floor with ≥ 300 lx half the occupied hours")
    if len(annual.sda_levels):
        row = box.row(align=True)
        row.label(text="LEED v4 levels:")
        for level in annual.sda_levels:
            row.label(text="%.0f %%" % (100 * level.level), icon=_passes(level.passed))
    box = layout.box()
    if annual.has_ase:
        _row(box, "Annual sunlight exposure", _percent(annual.annual_sunlight_exposure), 'LIGHT_SUN')
        box.label(text="ASE1000,250: floor with > 1000 lx of direct sun > 250 h")
        box.label(text="LEED v4: at most 10 %%: %s" % ("passes" if annual.ase_passes else "fails"),
                  icon=_passes(annual.ase_passes))
    else:
        box.label(text="Annual sunlight exposure: not computed (no direct sun)", icon='INFO')
    col = layout.column(align=True)
    _row(col, "Daylight autonomy DA300", _percent(annual.daylight_autonomy))
    _row(col, "Continuous DA300", _percent(annual.continuous_daylight_autonomy))
    _row(col, "Annual mean illuminance", "%.0f lx" % annual.mean_illuminance)
    col.label(text="(shares of the occupied hours, floor mean)")
    if len(annual.udi):
        box = layout.box()
        box.label(text="Useful daylight illuminance (UDI):")
        col = box.column(align=True)
        for band in annual.udi:
            _row(col, band.label, _percent(band.space_fraction))
    level = annual.en17037_level
    _row(layout, "EN 17037 daylight provision", level if level else "not met", _passes(bool(level)))


def draw_run(layout, annual):
    """What the figures are of: the weather, the occupied hours, the openings, the run."""
    col = layout.column(align=True)
    col.label(text="Weather: %s" % (annual.weather or "-"), icon='WORLD')
    col.label(text="Occupied %s local standard time, %d h a year" % (annual.occupied_period or "-",
                                                                     annual.occupied_hours))
    col.label(text="%d opening%s open, %d paths per sensor" % (annual.openings, "" if annual.openings == 1 else "s",
                                                               annual.paths))
    col.label(text="%.1f s%s" % (annual.seconds, " (light paths reused)" if annual.reused else ""))


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
            layout.label(text="The last run's figures (the sky is no longer Climate)", icon='INFO')
        elif not solve_progress.draw(layout):  # while a job runs: its progress and Cancel
            row = layout.row()
            row.enabled = problem is None
            row.operator("fenestra.annual_daylight", icon='TIME')
        if not annual.valid:
            layout.label(text="No annual run yet: it uses the openings as their cutters stand")
            return
        row = layout.row(align=True)
        row.label(text="Show:")
        row.prop(display, "annual_metric", text="")
        if display.false_colour != 'ANNUAL':
            layout.prop(display, "false_colour", text="False Colour")
        elif display.annual_metric not in false_colour.SHARES_OF_TIME:
            layout.prop(display, "colour_max")
        draw_space_metrics(layout, annual)
        draw_run(layout, annual)


classes = (FENESTRA_PT_annual,)
