"""A solve's climate goals in the model: the result's `climate` object (the native core's figures)
into `scene.fenestra.results.climate`, and each sensor's year (DA300, annual mean, direct-sun
hours) onto the result's sensors for the false colour. Nothing is computed here."""

import re

from . import sensor_table


def _number(value, default=0.0):
    return default if value is None else float(value)


def clear(climate):
    """Back to no climate result (scene.fenestra.results.climate)."""
    for key in climate.bl_rna.properties.keys():
        if key not in {"rna_type", "name", "goals", "rooms"}:
            climate.property_unset(key)
    climate.goals.clear()
    climate.rooms.clear()


def apply(results, climate):
    """Replaces the climate figures with the result's `climate` dict (None or absent: no climate
    goals); results.sensors must already hold the result's sensors in study order."""
    target = results.climate
    clear(target)
    for sensor in results.sensors:
        sensor.daylight_autonomy = sensor.mean_illuminance = sensor.ase_hours = -1.0
    if not climate:
        return
    for goal in climate.get("goals", []):
        item = target.goals.add()
        item.metric, item.description = goal.get("metric", ""), goal.get("description", "")
        item.sense, item.unit = goal.get("sense", ""), goal.get("unit", "")
        item.sensors = len(goal.get("sensors") or [])
        item.required = _number(goal.get("required"))
        item.has_achieved = goal.get("achieved") is not None
        item.achieved = _number(goal.get("achieved"))
        item.met = bool(goal.get("met"))
        item.has_verified = goal.get("verified") is not None
        item.verified = _number(goal.get("verified"))
        item.verified_met = bool(goal.get("verified_met"))
        item.has_records = goal.get("records") is not None
        item.records = _number(goal.get("records"))
        item.apart = bool(goal.get("apart"))
    for room in climate.get("rooms") or []:  # each sensor group the goals name, with the solved year's figures
        item, space = target.rooms.add(), room.get("space") or {}
        item.name, item.sensors = room.get("name", ""), len(room.get("sensors") or [])
        item.spatial_daylight_autonomy = _number(space.get("spatial_daylight_autonomy"))
        item.annual_sunlight_exposure = _number(space.get("annual_sunlight_exposure"))
        item.mean_illuminance = _number(space.get("mean_illuminance_lux"))
    target.all_met = bool(climate.get("all_met"))
    target.has_verified = climate.get("verified_all_met") is not None
    target.verified_all_met = bool(climate.get("verified_all_met"))
    target.unmet = "\n".join(climate.get("unmet") or [])
    target.least_glazing = bool(climate.get("least_glazing"))
    target.headline = climate.get("headline") or "path records"
    target.glazing_area = _number(climate.get("glazing_area_m2"))
    target.tradeoff = bool(climate.get("tradeoff"))
    target.domain_area = _number(climate.get("domain_area_m2"))
    per_sensor = climate.get("per_sensor") or {}
    for field, key in (("daylight_autonomy", "daylight_autonomy"), ("mean_illuminance", "mean_illuminance_lux"),
                       ("ase_hours", "ase_hours")):
        values = per_sensor.get(key) or []
        for sensor, value in zip(results.sensors, values):
            setattr(sensor, field, _number(value, -1.0))
    target.valid = True


def text(value, unit):
    """A figure in its unit as the panel shows it: fractions in percent, lux as lux."""
    if unit == "lux":
        return "%.0f lx" % value
    return "%.1f %%" % (100.0 * value)


def _at(values, k):
    return values[k] if values and k < len(values) else None


def tradeoff_climate(climate, entry):
    """The result's `climate` as trade-off `entry` of result["tradeoffs"] has it: each goal's figure
    and whether it is met (the path records' or real cutters', as the entry's `figures_by` says),
    its glazing; no rooms nor per-sensor year (the core reports them for the answer only)."""
    figures = entry.get("climate") or {}
    cut = figures.get("figures_by") == "cutters"
    goals = []
    for k, goal in enumerate(climate.get("goals", [])):
        achieved, met = _at(figures.get("achieved"), k), _at(figures.get("met"), k)
        goals.append(dict(goal, achieved=achieved, met=met, records=None if cut else achieved,
                          records_met=None if cut else met, verified=achieved if cut else None,
                          verified_met=met if cut else None, apart=None))
    return dict(climate, goals=goals, rooms=[], per_sensor={}, space=None, unmet=[], tradeoff=True,
                all_met=figures.get("all_met"), verified_all_met=None, answer_from_tradeoffs=False,
                headline="real cutters" if cut else "path records", glazing_area_m2=entry.get("glazing_area_m2"))


def tradeoff_line(climate, entry):
    """A trade-off's climate figures in one line: 'sDA 62.0 % met, ASE 3.0 % (West office) met' (a
    goal's sensor group after its figure, so that a narrow panel cuts the group's name, not the
    figure; a ", " in the name loses its space, as the parts are split there: tradeoff_rows)."""
    figures = entry.get("climate") or {}
    parts = []
    for k, goal in enumerate(climate.get("goals", []) if climate else []):
        achieved, met = _at(figures.get("achieved"), k), _at(figures.get("met"), k)
        if achieved is not None:
            state = "" if met is None else " met" if met else " not met"
            group = _GROUP.search(goal.get("description", ""))
            parts.append("%s %s%s%s" % (SHORT.get(goal.get("metric"), goal.get("metric", "")),
                                        text(achieved, goal.get("unit", "")),
                                        " (%s)" % group.group(1).replace(", ", ",") if group else "", state))
    return ", ".join(parts)


def tradeoff_rows(line):
    """A trade-off line's goals, a row each for a narrow panel: [(text, met)], the text without its
    ' met' / ' not met' (the panel draws a check mark or a cross), met None where not known."""
    rows = []
    for part in filter(None, line.split(", ")):
        for suffix, met in ((" not met", False), (" met", True)):
            if part.endswith(suffix):
                rows.append((part[:-len(suffix)], met))
                break
        else:
            rows.append((part, None))
    return rows


# The sensor group a goal's description names at its end: "sDA300/50% >= 50 % (West office)".
_GROUP = re.compile(r"\(([^()]+)\)\s*$")
# Short names of the metrics for one-line summaries.
SHORT = {"sda": "sDA", "ase": "ASE", "en17037": "EN 17037", "udi": "UDI", "mean": "Mean"}


def is_unmet_warning(warning):
    """The solve's warning that repeats an unmet climate goal (shown with the goals instead)."""
    return warning.startswith("climate goals: ") and " is not met: " in warning


# False colour of a climate solve's year per sensor: quantity -> (FenestraSensorResult field, factor
# to the unit shown). DA in percent of the occupied hours, the mean in lux, direct sun in hours.
QUANTITIES = {
    'CLIMATE_DA': ("daylight_autonomy", 100.0),
    'CLIMATE_MEAN': ("mean_illuminance", 1.0),
    'CLIMATE_ASE_HOURS': ("ase_hours", 1.0),
}
_table = sensor_table.SensorTable()


def per_vertex(results, quantity, obj_name, vertex_count):
    """The quantity over the object's vertices (NaN where a vertex has none); None when the result
    has no climate figures or no sensor of this object."""
    if not (results.valid and results.climate.valid):
        return None
    field, factor = QUANTITIES[quantity]
    table = _table.get(results.sensors, field, factor, (results.study_path, results.seconds_total,
                                                        results.climate.glazing_area, results.openings))
    shown = sensor_table.per_vertex(table, obj_name, vertex_count)
    if shown is not None:
        shown[shown < 0] = float("nan")  # (negative: not known)
    return shown
