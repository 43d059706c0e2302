"""The last Annual Daylight run, as read-only figures: `scene.fenestra.annual` (what the native
core's annual summary says, docs/climate-metrics.md), and each sensor's metrics by object and
vertex for the false colour. Fractions are stored as fractions (0..1); the panel shows percent."""

from bpy.props import BoolProperty, CollectionProperty, FloatProperty, IntProperty, StringProperty
from bpy.types import PropertyGroup


class FenestraAnnualSensor(PropertyGroup):
    object_name: StringProperty(name="Object", description="The sensor object this sensor is a vertex of")
    vertex: IntProperty(name="Vertex", description="Its vertex index in that object")
    mean_illuminance: FloatProperty(name="Annual Mean", description="Mean over the occupied hours, lux")
    daylight_autonomy: FloatProperty(name="DA", description="Share of the occupied hours with at least 300 lx")
    continuous_daylight_autonomy: FloatProperty(
        name="cDA", description="As DA, an hour below 300 lx counting for its share of 300 lx")
    udi_autonomous: FloatProperty(name="UDI Autonomous",
                                  description="Share of the occupied hours from 300 to 3000 lx")
    ase_hours: FloatProperty(name="Direct Sun Hours",
                             description="Occupied hours with more than 1000 lx of direct sun")


class FenestraAnnualBand(PropertyGroup):
    label: StringProperty(name="Band", description="The band's name and range, as the native core gives it")
    lower_lux: FloatProperty(name="From", description="Lux (negative: none, the band starts at 0)", default=-1.0)
    upper_lux: FloatProperty(name="To", description="Lux (negative: none, the band has no top)", default=-1.0)
    space_fraction: FloatProperty(name="Share", description="Share of the occupied hours in this band, "
                                                            "averaged over the sensors")


class FenestraAnnualLevel(PropertyGroup):
    level: FloatProperty(name="Level", description="sDA pass level (share of the floor)")
    passed: BoolProperty(name="Passed")


class FenestraAnnualResults(PropertyGroup):
    valid: BoolProperty(default=False)
    weather: StringProperty(name="Weather", description="The weather file and place of the run")
    hours: IntProperty(name="Hours", description="Hours of the weather file's year")
    occupied_hours: IntProperty(name="Occupied Hours", description="Hours in the occupied period over the year")
    occupied_period: StringProperty(name="Occupied Period",
                                    description="The occupied hours of every day, local standard time")
    openings: IntProperty(name="Openings", description="Openings (cutters) open in the run")
    paths: IntProperty(name="Paths", description="Paths per sensor")
    seconds: FloatProperty(name="Time", unit='TIME_ABSOLUTE')
    reused: BoolProperty(name="Contributions Reused",
                         description="The light paths of a previous run or solve were reused: only the "
                                     "openings changed")
    note: StringProperty(name="Note", description="The native core's word on the figures, e.g. that they are the "
                                                  "real cutters' year because the records' disagreed beyond the noise")
    study_path: StringProperty(name="Study", subtype='FILE_PATH',
                               description="The scene.json of the run (its folder also holds annual.json)")

    mean_illuminance: FloatProperty(name="Annual Mean Illuminance", description="Lux, over the occupied hours")
    daylight_autonomy: FloatProperty(name="Daylight Autonomy")
    continuous_daylight_autonomy: FloatProperty(name="Continuous Daylight Autonomy")
    spatial_daylight_autonomy: FloatProperty(
        name="sDA300/50%", description="Share of the floor with at least 300 lx for half the occupied hours")
    sda_levels: CollectionProperty(type=FenestraAnnualLevel)
    has_ase: BoolProperty(default=False)
    annual_sunlight_exposure: FloatProperty(
        name="ASE1000,250", description="Share of the floor with more than 1000 lx of direct sun for more "
                                        "than 250 occupied hours")
    ase_passes: BoolProperty(name="ASE Passes", description="ASE at most 10 % (LEED v4)")
    udi: CollectionProperty(type=FenestraAnnualBand)
    en17037_level: StringProperty(name="EN 17037",
                                  description="Daylight provision level reached (empty: none)")
    sensors: CollectionProperty(type=FenestraAnnualSensor)


classes = (FenestraAnnualSensor, FenestraAnnualBand, FenestraAnnualLevel, FenestraAnnualResults)
