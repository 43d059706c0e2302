"""An Annual Daylight run in the model: the native summary's figures into `scene.fenestra.annual`
(annual_properties.py), and each sensor's metrics found by object and vertex for the false colour.
Nothing is computed here: every number is the native core's (docs/climate-metrics.md)."""

import os

from . import sensor_table
from ..study.sky import clock

# Per-sensor metric -> (its property on FenestraAnnualSensor, factor to the unit shown).
METRICS = {
    'DA': ("daylight_autonomy", 100.0),                        # percent of the occupied hours
    'CDA': ("continuous_daylight_autonomy", 100.0),
    'UDI_A': ("udi_autonomous", 100.0),
    'MEAN': ("mean_illuminance", 1.0),                          # lux
    'ASE_HOURS': ("ase_hours", 1.0),                            # hours
}
AUTONOMOUS_BAND = "autonomous"  # the native core's name for the UDI band from 300 to 3000 lx

_table = sensor_table.SensorTable()


def clear(scene):
    """Forgets the run (its figures back to their defaults)."""
    annual = scene.fenestra.annual
    for key in annual.bl_rna.properties.keys():
        if key not in {"rna_type", "name", "sensors", "sda_levels", "udi"}:
            annual.property_unset(key)
    for collection in (annual.sensors, annual.sda_levels, annual.udi):
        collection.clear()
    _table.forget()


def _number(value, default=0.0):
    """A summary value (None when the core left it out, e.g. no direct sun) as a float."""
    return default if value is None else float(value)


def _autonomous(bands):
    """The per-sensor shares of the UDI autonomous band (zeros when the bands are not the usual four)."""
    for band in bands:
        if band.get("name", "").startswith(AUTONOMOUS_BAND):
            return band.get("sensor_fraction") or []
    return []


def apply(scene, study, summary, openings, seconds, reused, study_path):
    """Replaces the previous run's figures with this summary (fenestra.annual()["summary"]); `study`
    (export.Study) maps the sensors, in study order, back to their objects and vertices."""
    clear(scene)
    annual = scene.fenestra.annual
    space, per_sensor = summary["space"], summary["per_sensor"]
    weather = summary.get("weather") or ""
    annual.weather = os.path.basename(weather)
    annual.hours = int(summary.get("hours", 0))
    annual.occupied_hours = int(summary.get("occupied_hours", 0))
    occupied = summary.get("occupied") or {}
    if "start_hour" in occupied and "end_hour" in occupied:
        annual.occupied_period = "%s-%s" % (clock(float(occupied["start_hour"])), clock(float(occupied["end_hour"])))
    annual.openings, annual.seconds, annual.reused = openings, seconds, reused
    annual.paths = int(summary.get("paths_per_sensor", 0))
    annual.study_path = study_path
    annual.note = summary.get("note") or ""
    annual.mean_illuminance = _number(space.get("mean_illuminance_lux"))
    annual.daylight_autonomy = _number(space.get("daylight_autonomy"))
    annual.continuous_daylight_autonomy = _number(space.get("continuous_daylight_autonomy"))
    annual.spatial_daylight_autonomy = _number(space.get("spatial_daylight_autonomy"))
    for entry in space.get("sda_levels", []):
        item = annual.sda_levels.add()
        item.level, item.passed = float(entry["level"]), bool(entry["passed"])
    annual.has_ase = space.get("annual_sunlight_exposure") is not None
    annual.annual_sunlight_exposure = _number(space.get("annual_sunlight_exposure"))
    annual.ase_passes = bool(space.get("ase_passes"))
    for band in space.get("udi", []):
        item = annual.udi.add()
        item.label, item.space_fraction = band["name"], _number(band.get("space_fraction"))
        item.lower_lux, item.upper_lux = _number(band.get("lower_lux"), -1.0), _number(band.get("upper_lux"), -1.0)
    annual.en17037_level = (space.get("en17037") or {}).get("level_reached") or ""

    count = sum(n for _, n in study.sensor_objects)
    columns = {field: per_sensor.get(key) or [] for field, key in (
        ("mean_illuminance", "mean_illuminance_lux"), ("daylight_autonomy", "daylight_autonomy"),
        ("continuous_daylight_autonomy", "continuous_daylight_autonomy"), ("ase_hours", "ase_hours"))}
    columns["udi_autonomous"] = _autonomous(space.get("udi", []))
    owners = [(name, vertex) for name, n in study.sensor_objects for vertex in range(n)]
    for i, (name, vertex) in enumerate(owners[:count]):
        item = annual.sensors.add()
        item.object_name, item.vertex = name, vertex
        for field, values in columns.items():
            setattr(item, field, _number(values[i]) if i < len(values) else 0.0)
    annual.valid = True


def table(annual, metric):
    """{object name: (vertex indices, values in the unit shown)} for the metric, rebuilt when the
    run or the metric changes."""
    if not annual.valid:
        return {}
    field, factor = METRICS[metric]
    return _table.get(annual.sensors, field, factor, (annual.study_path, annual.seconds, annual.openings))


def per_vertex(annual, metric, obj_name, vertex_count):
    """The metric over the object's vertices (NaN where a vertex has none); None when the run has no
    sensor of this object or its vertex count changed since."""
    return sensor_table.per_vertex(table(annual, metric), obj_name, vertex_count)
