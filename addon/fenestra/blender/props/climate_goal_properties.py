"""Climate goals (the climate sky only): `scene.fenestra.goals.climate`, each one goal on an annual
metric over all sensors or a vertex group of the sensor objects, and what a solve reached,
`scene.fenestra.results.climate` (docs/blender.md, "Climate goals"; the scene file's
`goals.climate`, docs/scene-format.md). Shares are typed in percent and written as fractions."""

import bpy
from bpy.props import BoolProperty, CollectionProperty, EnumProperty, FloatProperty, IntProperty, StringProperty
from bpy.types import PropertyGroup

MAX_LUX = 200000.0     # the core's limit for a goal's illuminance (above full sunlight)
HOURS_PER_YEAR = 8760.0
MAX_WEIGHT = 1e6       # the core's limit for a weight

METRICS = (
    ('SDA', "sDA", "Spatial daylight autonomy (IES LM-83): at least this share of the sensors has at least "
                   "the illuminance for at least the share of the occupied hours"),
    ('ASE', "ASE", "Annual sunlight exposure (IES LM-83): at most this share of the sensors has more than the "
                   "illuminance of direct sun for more than the hours"),
    ('EN17037', "EN 17037", "EN 17037 daylight provision: the level's target illuminances over half and over "
                            "95 % of the sensors, for half the daylight hours"),
    ('UDI', "UDI", "Useful daylight illuminance: at least this share of the sensors lies between the lower and "
                   "upper illuminance for at least half the occupied hours"),
    ('MEAN', "Annual Mean", "The sensors' mean illuminance over the occupied hours, as close to this as can be"),
)
CORE_METRIC = {'SDA': "sda", 'ASE': "ase", 'EN17037': "en17037", 'UDI': "udi", 'MEAN': "mean"}


def _redraw(_goal=None, _context=None):
    from .display_settings import redraw_3d_views
    redraw_3d_views()


def _udi_lower_changed(goal, context):
    """Lower below upper: raising the lower moves the upper along (as Blender's frame range)."""
    if goal.udi_lower >= goal.udi_upper:
        goal.udi_upper = min(MAX_LUX, goal.udi_lower + 1.0)
        if goal.udi_lower >= goal.udi_upper:
            goal.udi_lower = goal.udi_upper - 1.0


def _udi_upper_changed(goal, context):
    if goal.udi_upper <= goal.udi_lower:
        goal.udi_lower = max(0.0, goal.udi_upper - 1.0)


def _vertex_group_names(self, context, text):
    """The search list of the Sensor Group field: the sensor objects (a room's grid each) and their
    vertex groups."""
    sensors = [o for o in context.scene.objects if o.type == 'MESH' and o.fenestra.is_sensor]
    names = sorted({o.name for o in sensors} | {g.name for o in sensors for g in o.vertex_groups})
    return [n for n in names if text.lower() in n.lower()]


class FenestraClimateGoal(PropertyGroup):
    metric: EnumProperty(name="Metric", items=METRICS, default='SDA', update=_redraw)
    sensor_group: StringProperty(
        name="Sensor Group", default="", search=_vertex_group_names,
        description="A sensor object (a room's sensor grid: the goal is on all its sensors) or a vertex group of "
                    "the sensor object(s) (the goal is on the sensors in it, in every sensor object that has a "
                    "vertex group of this name). Empty: all sensors")
    weight: FloatProperty(name="Weight", min=0.01, max=MAX_WEIGHT, soft_max=10.0, default=1.0,
                          description="The goal's share of the objective, relative to the other goals (1: equal)")
    # sDA (defaults: IES LM-83's sDA300/50% and LEED v4's 55 %).
    sda_lux: FloatProperty(name="Illuminance", min=1.0, max=MAX_LUX, soft_max=2000.0, default=300.0,
                           description="Lux a sensor needs (1 to 200 000 lx)")
    sda_time: FloatProperty(name="Time", subtype='PERCENTAGE', min=1.0, max=100.0, default=50.0,
                            description="Percent of the occupied hours a sensor needs at least the illuminance "
                                        "(1 to 100 %)")
    sda_area: FloatProperty(name="Min Area", subtype='PERCENTAGE', min=0.0, max=100.0, default=55.0,
                            description="Percent of the sensors that must reach it, at least (0 to 100 %)")
    # ASE (ASE1000,250 and LEED v4's 10 %).
    ase_lux: FloatProperty(name="Illuminance", min=1.0, max=MAX_LUX, soft_max=5000.0, default=1000.0,
                           description="Lux of direct sun that counts (1 to 200 000 lx)")
    ase_hours: FloatProperty(name="Hours", min=0.0, max=HOURS_PER_YEAR, default=250.0,
                             description="Occupied hours of direct sun above the illuminance a sensor may have "
                                         "(0 to 8760 h)")
    ase_area: FloatProperty(name="Max Area", subtype='PERCENTAGE', min=0.0, max=100.0, default=10.0,
                            description="Percent of the sensors that may have more, at most (0 to 100 %)")
    # EN 17037.
    en17037_level: EnumProperty(
        name="Level", default='MINIMUM',
        items=(('MINIMUM', "Minimum", "300 lx over half the sensors and 100 lx over 95 %, half the daylight hours"),
               ('MEDIUM', "Medium", "500 lx over half the sensors and 300 lx over 95 %, half the daylight hours"),
               ('HIGH', "High", "750 lx over half the sensors and 500 lx over 95 %, half the daylight hours")))
    # UDI.
    udi_lower: FloatProperty(name="From", min=0.0, max=MAX_LUX - 1.0, soft_max=1000.0, default=100.0,
                             update=_udi_lower_changed,
                             description="Lower illuminance of the useful band, lux (below the upper)")
    udi_upper: FloatProperty(name="To", min=1.0, max=MAX_LUX, soft_max=10000.0, default=3000.0,
                             update=_udi_upper_changed,
                             description="Upper illuminance of the useful band, lux (above the lower)")
    udi_area: FloatProperty(name="Min Area", subtype='PERCENTAGE', min=0.0, max=100.0, default=50.0,
                            description="Percent of the sensors within the band for half the occupied hours, "
                                        "at least (0 to 100 %)")
    # Annual mean.
    mean_lux: FloatProperty(name="Illuminance", min=1.0, max=MAX_LUX, soft_max=5000.0, default=500.0,
                            description="Target mean illuminance over the occupied hours, lux (1 to 200 000 lx)")

    def summary(self):
        """One line for the list: the metric and its thresholds (the core's own wording comes with the result)."""
        if self.metric == 'SDA':
            return "sDA%g/%g%% ≥ %g %%" % (self.sda_lux, self.sda_time, self.sda_area)
        if self.metric == 'ASE':
            return "ASE%g,%g ≤ %g %%" % (self.ase_lux, self.ase_hours, self.ase_area)
        if self.metric == 'EN17037':
            return "EN 17037 %s" % self.en17037_level.lower()
        if self.metric == 'UDI':
            return "UDI %g-%g lx ≥ %g %%" % (self.udi_lower, self.udi_upper, self.udi_area)
        return "Annual mean %g lx" % self.mean_lux

    def fields(self):
        """The threshold properties of the chosen metric, in the order drawn."""
        return {'SDA': ("sda_lux", "sda_time", "sda_area"), 'ASE': ("ase_lux", "ase_hours", "ase_area"),
                'EN17037': ("en17037_level",), 'UDI': ("udi_lower", "udi_upper", "udi_area"),
                'MEAN': ("mean_lux",)}[self.metric]

    def as_dict(self, sensors):
        """The scene file's entry of goals.climate; `sensors` is "all" or the group's name."""
        out = {"metric": CORE_METRIC[self.metric], "sensors": sensors}
        if self.metric == 'SDA':
            out.update(illuminance_lux=self.sda_lux, time_fraction=self.sda_time / 100.0,
                       min_area_fraction=self.sda_area / 100.0)
        elif self.metric == 'ASE':
            out.update(illuminance_lux=self.ase_lux, hours=self.ase_hours, max_area_fraction=self.ase_area / 100.0)
        elif self.metric == 'EN17037':
            out["level"] = self.en17037_level.lower()
        elif self.metric == 'UDI':
            out.update(lower_lux=self.udi_lower, upper_lux=self.udi_upper, min_area_fraction=self.udi_area / 100.0)
        else:
            out["illuminance_lux"] = self.mean_lux
        if self.weight != 1.0:
            out["weight"] = self.weight
        return {k: (round(v, 6) if isinstance(v, float) else v) for k, v in out.items()}


class FenestraClimateGoalResult(PropertyGroup):
    """One climate goal of the result, as the native core reports it."""
    metric: StringProperty(name="Metric", description="sda, ase, en17037, udi or mean")
    description: StringProperty(name="Goal", description="The goal in words, as the native core states it")
    sense: StringProperty(name="Sense", description="at_least, at_most or target (the annual mean)")
    unit: StringProperty(name="Unit", description="area fraction, hours fraction (fractions 0 to 1) or lux")
    sensors: IntProperty(name="Sensors", description="How many sensors the goal is on")
    required: FloatProperty(name="Required", description="The goal's figure, in its unit")
    has_achieved: BoolProperty(default=False)
    achieved: FloatProperty(name="Achieved", description="What the openings reach, from the solve's light paths "
                                                         "(their records), in the goal's unit")
    met: BoolProperty(name="Met")
    has_verified: BoolProperty(default=False)
    verified: FloatProperty(name="Verified", description="What the openings reach with real cutters and "
                                                         "independent paths, in the goal's unit")
    verified_met: BoolProperty(name="Verified Met")
    has_records: BoolProperty(default=False)
    records: FloatProperty(name="Path Records", description="What the openings reach from the path records, in the "
                                                             "goal's unit")
    apart: BoolProperty(name="Apart", description="The path records' figure and the real cutters' disagree beyond the "
                                                  "noise: the cutters' is the one to trust")

    def lead(self):
        """(figure, met, source) the panel leads with: the real cutters' where they exist, else the
        path records' (the core's headline)."""
        if self.has_verified:
            return self.verified, self.verified_met, "real cutters"
        return self.achieved, self.met, "path records"


class FenestraClimateRoomResult(PropertyGroup):
    """One room of the result: a sensor group a climate goal names, and its figures of the solved year."""
    name: StringProperty(name="Room", description="The sensor object or vertex group the goals name")
    sensors: IntProperty(name="Sensors", description="How many sensors the room has")
    spatial_daylight_autonomy: FloatProperty(name="sDA", description="sDA300/50% of the room's sensors, 0 to 1")
    annual_sunlight_exposure: FloatProperty(name="ASE", description="ASE1000,250 of the room's sensors, 0 to 1")
    mean_illuminance: FloatProperty(name="Mean", description="The room's mean illuminance of the occupied hours, lux")


class FenestraClimateResult(PropertyGroup):
    valid: BoolProperty(default=False, description="The last solve had climate goals")
    goals: CollectionProperty(type=FenestraClimateGoalResult)
    rooms: CollectionProperty(type=FenestraClimateRoomResult)
    all_met: BoolProperty(name="All Met")
    has_verified: BoolProperty(default=False)
    verified_all_met: BoolProperty(name="All Met, Verified")
    tradeoff: BoolProperty(name="Of a Trade-off", description="The figures are a trade-off's (the best found with "
                                                               "fewer openings), not the answer's")
    unmet: StringProperty(name="Unmet", description="Each goal not met, one per line (the native core's words)")
    least_glazing: BoolProperty(name="Least Glazing")
    headline: StringProperty(name="Figures Of", description="Which year the Achieved figures are of: \"path records\", "
                                                            "or \"real cutters\" where the two disagreed beyond the noise",
                             default="path records")
    glazing_area: FloatProperty(name="Glazing Area", description="Open area of the openings, m²")
    domain_area: FloatProperty(name="Domain Area", description="Area of the opening domain's elements, m²")


classes = (FenestraClimateGoal, FenestraClimateGoalResult, FenestraClimateRoomResult, FenestraClimateResult)
