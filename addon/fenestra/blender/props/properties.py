"""Settings of a study: `scene.fenestra` (one PropertyGroup per concern) and `object.fenestra`."""

import datetime

import bpy
from bpy.props import (BoolProperty, CollectionProperty, EnumProperty, FloatProperty, IntProperty,
                       PointerProperty, StringProperty)
from bpy.types import PropertyGroup

from . import annual_properties, climate_goal_properties, goal_bounds
from ..result import sky_preview
from .annual_properties import FenestraAnnualResults
from .climate_goal_properties import FenestraClimateGoal, FenestraClimateResult
from .display_settings import FenestraDisplaySettings

TODAY = datetime.date.today()


class FenestraObjectSettings(PropertyGroup):
    is_sensor: BoolProperty(
        name="Sensor", default=False,
        description="The vertices of this object are sensor points (vertex normals give their orientation); "
                    "it is not part of the lit geometry")
    is_opening: BoolProperty(
        name="Opening", default=False,
        description="A cutter made by Solve Openings (replaced by the next solve, not part of the geometry)")


class FenestraSkySettings(PropertyGroup):
    type: EnumProperty(
        name="Sky", default='PREETHAM',
        items=(('PREETHAM', "Preetham + Sun", "Clear sky and sun for a place, dates and hours"),
               ('CIE_CLEAR', "CIE Clear + Sun", "CIE standard clear sky with the same sun"),
               ('CIE_OVERCAST', "CIE Overcast", "CIE standard overcast sky (daylight factors)"),
               ('UNIFORM', "Uniform", "The same radiance from every direction"),
               ('CLIMATE', "Climate (weather file)", "A year of a weather file: annual daylight metrics "
                "(Annual Daylight), and the mean sky of the occupied hours for solving")))
    use_sun_position: BoolProperty(
        name="Use Sun Position", default=True,
        description="Take place, time zone, date and north from the Sun Position add-on when it is enabled")
    latitude: FloatProperty(name="Latitude", description="Degrees, north positive",
                            min=-90.0, max=90.0, default=48.85, precision=3)
    longitude: FloatProperty(name="Longitude", description="Degrees, east positive",
                             min=-180.0, max=180.0, default=2.35, precision=3)
    utc_offset: FloatProperty(name="UTC Offset", description="Hours the local clock is ahead of UTC",
                              min=-14.0, max=14.0, default=1.0, step=50)
    north_offset: FloatProperty(name="North Offset", subtype='ANGLE', default=0.0,
                                description="True north, clockwise from +Y seen from above")
    year: IntProperty(name="Year", min=1, max=4000, default=TODAY.year)
    month: IntProperty(name="Month", min=1, max=12, default=6)
    day: IntProperty(name="Day", min=1, max=31, default=21)
    use_date_end: BoolProperty(name="Date Range", default=False,
                               description="Average every day from the date to an end date")
    end_year: IntProperty(name="End Year", min=1, max=4000, default=TODAY.year)
    end_month: IntProperty(name="End Month", min=1, max=12, default=6)
    end_day: IntProperty(name="End Day", min=1, max=31, default=21)
    start_time: FloatProperty(name="Start", description="Local clock, hours", min=0.0, max=24.0,
                              default=9.0, precision=2)
    end_time: FloatProperty(name="End", description="Local clock, hours (before the start: past midnight)",
                            min=0.0, max=24.0, default=17.0, precision=2)
    step_minutes: FloatProperty(name="Step", description="Time step, minutes", min=1.0, max=240.0, default=15.0)
    turbidity: FloatProperty(name="Turbidity", description="1.7 (very clear) to 10 (hazy)",
                             min=1.7, max=10.0, default=3.0)
    ground_reflectance: FloatProperty(name="Ground Reflectance", min=0.0, max=1.0, default=0.2)
    horizontal_illuminance: FloatProperty(
        name="Illuminance", description="Overcast and uniform skies: lux on an unobstructed "
        "horizontal surface", min=1.0, default=10000.0)
    map_width: IntProperty(name="Map Width", description="Width of the sky map in pixels (height: half)",
                           min=16, max=8192, default=1024)
    # Climate sky (docs/blender.md, "Climate-based daylight"): the place is the weather file's.
    weather_file: StringProperty(
        name="Weather File", subtype='FILE_PATH', default="",
        description="An EnergyPlus weather file (.epw) or a Daysim/Radiance .wea file: a year of hourly "
                    "sun and sky; the place (latitude, longitude, time zone) is the file's")
    occupied_start: FloatProperty(
        name="Occupied", min=0.0, max=24.0, default=8.0, precision=2,
        description="Start of the occupied hours, every day, local standard time (no daylight saving), hours")
    occupied_end: FloatProperty(
        name="To", min=0.0, max=24.0, default=18.0, precision=2,
        description="End of the occupied hours, every day, local standard time (no daylight saving), hours; "
                    "after the start (the period cannot cross midnight)")
    patches: EnumProperty(
        name="Sky Patches", default='1',
        items=(('1', "Tregenza (145)", "145 sky patches of about 12°: quickest"),
               ('2', "Reinhart (577)", "577 sky patches of about 6°"),
               ('4', "Reinhart (2305)", "2305 sky patches of about 3°: the finest sky, the most memory")),
        description="How finely the sky is divided for the annual study")
    preview_strength: FloatProperty(
        name="Preview Strength", min=0.0, default=0.001, precision=5,
        description="World strength of the previewed sky map (1 = cd/m², as Fenestra lights the scene); "
                    "applied at once, the map is not computed again",
        update=sky_preview.strength_changed)


class FenestraGoalSettings(PropertyGroup):
    source: EnumProperty(
        name="Goals", default='UNIFORM',
        items=(('UNIFORM', "Uniform", "One goal for every sensor, with optional bounds"),
               ('ATTRIBUTE', "Painted", "Per vertex from the sensor mesh's 'fenestra_goal' attribute: "
                "a colour attribute (its brightness) or a float attribute, times the scale"),
               ('NONE', "Climate Goals Only", "No goal per sensor: the climate goals alone (climate sky)")))
    units: EnumProperty(
        name="Units", default='NORMALIZED',
        items=(('NORMALIZED', "Normalized", "0 = dark, 1 = the sensor's value with every element open"),
               ('LUX', "Lux", "Illuminance"),
               ('DAYLIGHT_FACTOR', "Daylight Factor", "Percent of the unobstructed horizontal illuminance")),
        update=goal_bounds.units_changed)
    # Hard limits hold every unit's range; the callbacks clamp to the chosen units' (goal_bounds.py).
    level: FloatProperty(name="Goal", min=0.0, max=goal_bounds.HARD_MAX, soft_max=1000.0, default=0.5,
                         update=goal_bounds.level_changed,
                         description="Uniform goal, in the goal units: normalized 0 to 1, daylight factor "
                                     "0 to 100 %, lux from 0")
    use_min: BoolProperty(name="Minimum", default=False)
    min: FloatProperty(name="Minimum", min=0.0, max=goal_bounds.HARD_MAX, soft_max=1000.0, default=0.3,
                       update=goal_bounds.min_changed,
                       description="Penalised below this, goal units (at most the goal)")
    use_max: BoolProperty(name="Maximum", default=False)
    max: FloatProperty(name="Maximum", min=0.0, max=goal_bounds.HARD_MAX, soft_max=1000.0, default=0.8,
                       update=goal_bounds.max_changed,
                       description="Penalised above this, goal units (at least the goal)")
    scale: FloatProperty(name="Scale", min=0.0, default=1.0,
                         description="Painted goals: the goal of a white vertex (or of a float value 1)")
    # Climate goals (climate sky): annual metrics over all sensors or a vertex group (climate_goal_properties.py).
    climate: CollectionProperty(type=FenestraClimateGoal)
    climate_index: IntProperty(name="Active Climate Goal", default=0, min=0)
    least_glazing: BoolProperty(
        name="Least Glazing", default=False,
        description="Among the designs that meet the climate goals, prefer the one with the least open area")


CATALOGUES = (('NONE', "Free Sizes", "Any size within the limits below"),
              ('residential', "Residential", "Walls 0.6-1.8 m wide x 1.2-2.1 m high; common roof-window sizes"),
              ('commercial', "Commercial", "Walls 1.2-3.0 m wide x 1.5-2.4 m high; skylights 1.2-2.4 m"))


class FenestraConstraints(PropertyGroup):
    """Architectural constraints on the openings; 0 leaves one unset (automatic, when on)."""
    automatic: BoolProperty(
        name="Automatic", default=True,
        description="Keys left at 0 take the solver's automatic values (shown greyed): openings at least "
                    "0.5 m, a 0.5 m pier between them, clear of panel edges, sills and heads off the "
                    "floor and ceiling, a few openings per panel")
    full_height: BoolProperty(name="Doors / Full-Height Glazing", default=False,
                              description="No automatic sill, head or margin: openings may reach the floor "
                                          "and ceiling")
    catalogue: EnumProperty(name="Catalogue", items=CATALOGUES, default='NONE',
                            description="Every opening takes one of the catalogue's sizes")
    min_area: FloatProperty(name="Min Area", min=0.0, default=0.0, unit='AREA')
    max_area: FloatProperty(name="Max Area", min=0.0, default=0.0, unit='AREA')
    min_aspect: FloatProperty(name="Min Aspect", min=0.0, default=0.0, description="Width / height")
    max_aspect: FloatProperty(name="Max Aspect", min=0.0, default=0.0, description="Width / height")
    min_width: FloatProperty(name="Min Width", min=0.0, default=0.0, unit='LENGTH')
    max_width: FloatProperty(name="Max Width", min=0.0, default=0.0, unit='LENGTH')
    min_height: FloatProperty(name="Min Height", min=0.0, default=0.0, unit='LENGTH')
    max_height: FloatProperty(name="Max Height", min=0.0, default=0.0, unit='LENGTH')
    max_openings: IntProperty(name="Max Openings", min=0, default=0)
    max_openings_per_panel: IntProperty(name="Max per Panel", min=0, default=0,
                                        description="Openings on one panel (a face group of one plane)")
    panel_width_per_opening: FloatProperty(name="Width per Opening", min=0.0, default=0.0, unit='LENGTH',
                                           description="At most one opening per this much of a panel's width")
    min_gap: FloatProperty(name="Min Gap", min=0.0, default=0.0, unit='LENGTH',
                           description="Between two openings")
    margin: FloatProperty(name="Margin", min=0.0, default=0.0, unit='LENGTH',
                          description="From the edges of a panel")
    sill_min: FloatProperty(name="Min Sill", min=0.0, default=0.0, unit='LENGTH',
                            description="Lowest sill height above the panel's bottom")
    head_max: FloatProperty(name="Max Head", min=0.0, default=0.0, unit='LENGTH',
                            description="Highest head height above the panel's bottom")
    head_clearance: FloatProperty(name="Head Clearance", min=0.0, default=0.0, unit='LENGTH',
                                  description="Least distance between a head and the wall's top")

    # Facade composition (coplanar walls): each rule is solver.constraints' key of the same name.
    align_sills: BoolProperty(name="Align Sills", default=False, description="One sill height per facade")
    align_heads: BoolProperty(name="Align Heads", default=False, description="One head height per facade")
    equal_widths: BoolProperty(name="Equal Widths", default=False, description="One opening width per facade")
    same_type_in_row: BoolProperty(name="Same Type in a Row", default=False,
                                   description="The openings of a row (one sill) have one size")
    symmetric: BoolProperty(name="Symmetric", default=False,
                            description="Each wall's openings mirror about its vertical axis")
    equal_spacing: BoolProperty(name="Equal Spacing", default=False,
                                description="Equal piers between the openings of each row of three or more")
    sill_heights: StringProperty(
        name="Sill Heights", default="",
        description="Allowed sill heights in meters above the wall's base, separated by commas "
                    "(e.g. 0.9 or 0.45, 0.9); empty: any")

    COMPOSITION = ("align_sills", "align_heads", "equal_widths", "same_type_in_row", "symmetric", "equal_spacing")

    KEYS = ("min_area", "max_area", "min_aspect", "max_aspect", "min_width", "max_width", "min_height",
            "max_height", "max_openings", "max_openings_per_panel", "panel_width_per_opening", "min_gap",
            "margin", "sill_min", "head_max", "head_clearance")

    def as_dict(self):
        """The constraints that are set, as the scene file's solver.constraints (keys left out take
        their automatic value in the solver)."""
        out = {k: getattr(self, k) for k in self.KEYS if getattr(self, k) > 0}
        if not self.automatic:
            out["automatic"] = False
        if self.full_height:
            out["full_height"] = True
        if self.catalogue != 'NONE':
            out["catalogue"] = self.catalogue
        out.update({k: True for k in self.COMPOSITION if getattr(self, k)})
        heights = sill_heights_of(self.sill_heights)
        if heights:
            out["sill_heights"] = heights
        return out


def sill_heights_of(text):
    """The Sill Heights field as a list of meters; ValueError naming the entry that is not a number."""
    heights = []
    for item in text.replace(";", ",").split(","):
        item = item.strip().removesuffix("m").strip()
        if not item:
            continue
        try:
            heights.append(float(item))
        except ValueError:
            raise ValueError("Sill Heights: %r is not a height in meters (write e.g. 0.9 or 0.45, 0.9)"
                             % item) from None
    return heights


QUALITY = {'PREVIEW': (2048, 150, 32), 'FINAL': (16384, 500, 64)}  # paths, generations, population
# Paths per sensor of the check with real cutters (solver.verify_paths; 0: the solve's paths). A
# quarter at Preview: its standard error is twice the prediction's, and a re-solve stays quick.
VERIFY_PATHS = {'PREVIEW': 512, 'FINAL': 0, 'CUSTOM': 0}


class FenestraSolveSettings(PropertyGroup):
    element_size: FloatProperty(name="Element Size", min=0.001, soft_min=0.05, soft_max=2.0, default=0.25,
                                unit='LENGTH', description="Side of the square opening elements")
    wall_thickness: FloatProperty(
        name="Wall Thickness", min=0.0, default=0.0, unit='LENGTH',
        description="Depth the openings cut through, away from the sensors, in meters. 0: measured "
                    "from the model at each wall (0 where the wall is a single face)")
    quality: EnumProperty(
        name="Quality", default='PREVIEW',
        items=(('PREVIEW', "Preview", "%d paths per sensor, %d generations, checked with %d paths"
                % (QUALITY['PREVIEW'][:2] + (VERIFY_PATHS['PREVIEW'],))),
               ('FINAL', "Final", "%d paths per sensor, %d generations" % QUALITY['FINAL'][:2]),
               ('CUSTOM', "Custom", "Paths, generations and population as set")))
    paths: IntProperty(name="Paths", min=16, default=4096, description="Paths per sensor")
    generations: IntProperty(name="Generations", min=0, default=300)
    population: IntProperty(name="Population", min=4, default=64)
    seed: IntProperty(name="Seed", min=0, default=1)
    constraints: PointerProperty(type=FenestraConstraints)
    edges_on_grid: BoolProperty(
        name="Edges on Element Grid", default=False,
        description="Keep the openings' edges on the element grid (the solver otherwise moves them between "
                    "its lines where the error falls). Annual Daylight needs it for openings in a thick wall")
    use_booleans: BoolProperty(name="Cut Domain Objects", default=True,
                               description="Cut the openings through the walls: a Boolean Difference with "
                                           "the openings on the domain objects and on every object the "
                                           "openings reach")
    cutter_margin: FloatProperty(name="Cutter Margin", min=0.0, default=0.02, unit='LENGTH',
                                 description="The cutters reach this far beyond the wall on both sides")
    study_directory: StringProperty(
        name="Study Folder", subtype='DIR_PATH', default="",
        description="Where scene.json, scene.obj and result.json are written (empty: next to the .blend "
                    "file, or Blender's temporary folder for an unsaved file)")

    def budget(self):
        """(paths per sensor, generations, population) of the chosen quality."""
        if self.quality == 'CUSTOM':
            return self.paths, self.generations, self.population
        return QUALITY[self.quality]

    def verify_paths(self):
        """Paths per sensor of the check with real cutters; 0: as many as the solve's."""
        return VERIFY_PATHS[self.quality]


class FenestraSensorResult(PropertyGroup):
    goal: FloatProperty(name="Goal", description="Lux (negative: no goal)")
    achieved: FloatProperty(name="Achieved", description="Lux")
    object_name: StringProperty(name="Object", description="The sensor object this sensor is a vertex of")
    vertex: IntProperty(name="Vertex", description="Its vertex index in that object")
    # A solve with climate goals: the solved openings' year at this sensor (negative: not known).
    daylight_autonomy: FloatProperty(name="DA300", default=-1.0,
                                     description="Share of the occupied hours with at least 300 lx (0 to 1)")
    mean_illuminance: FloatProperty(name="Annual Mean", default=-1.0,
                                    description="Mean illuminance over the occupied hours, lux")
    ase_hours: FloatProperty(name="Direct Sun Hours", default=-1.0,
                             description="Occupied hours with more than 1000 lx of direct sun")


class FenestraTradeoff(PropertyGroup):
    openings: IntProperty(name="Openings")
    relative_rms: FloatProperty(name="Relative RMS Error")
    glazing_area: FloatProperty(name="Glazing Area", unit='AREA', description="Total area of the openings")
    climate_met: IntProperty(name="Climate Goals Met", default=-1, min=-1, max=1,
                             description="With climate goals: 1 when these openings meet them all, 0 when not, "
                                         "-1 when unknown")
    climate_by_cutters: BoolProperty(name="Checked with Real Cutters",
                                     description="The climate figures are real cutters' (least glazing checked this "
                                                 "design with less glass than the answer), not the path records'")
    climate_line: StringProperty(name="Climate Figures",
                                 description="Each climate goal's figure with these openings, and whether it is met")


class FenestraResults(PropertyGroup):
    valid: BoolProperty(default=False)
    tradeoffs: CollectionProperty(type=FenestraTradeoff,
                                  description="The answer and the best found with fewer openings")
    tradeoff_shown: IntProperty(name="Shown Trade-off", default=0,
                                description="Which of the trade-offs the cutters show (0: the answer)")
    relative_rms: FloatProperty(name="Relative RMS Error")
    verified_rms: FloatProperty(name="Checked Error", default=-1.0,
                                description="Relative RMS error path-traced with the openings really cut "
                                            "(negative: not checked)")
    verified_noise: FloatProperty(name="Checked Noise", default=0.0,
                                  description="Monte Carlo noise of the checked error (relative RMS of its "
                                              "standard errors): fewer paths read worse by about this much")
    warnings: StringProperty(name="Warnings", description="What to know before trusting the result, one per line")
    evaluated: BoolProperty(name="Evaluated", default=False,
                            description="The values and errors are path-traced with the cutters as they stand "
                                        "(Evaluate), not the solve's")
    max_relative: FloatProperty(name="Worst Sensor Error")
    openings: IntProperty(name="Openings")
    open_elements: IntProperty(name="Open Elements", description="Elements open in the answer (-1: a trade-off is "
                                                                  "shown, whose openings are rectangles)")
    elements: IntProperty(name="Elements")
    seconds_total: FloatProperty(name="Total", unit='TIME_ABSOLUTE')
    seconds_contributions: FloatProperty(name="Contributions", unit='TIME_ABSOLUTE')
    seconds_solver: FloatProperty(name="Solver", unit='TIME_ABSOLUTE')
    study_path: StringProperty(name="Study", subtype='FILE_PATH')
    sensors: CollectionProperty(type=FenestraSensorResult)
    horizontal_illuminance: FloatProperty(
        name="Unobstructed Horizontal Illuminance", default=0.0,
        description="Lux of the solved sky on an unobstructed horizontal surface, for daylight factors "
                    "(0: not known yet)")
    climate: PointerProperty(type=FenestraClimateResult, description="The climate goals and what the openings reach")


class FenestraSceneSettings(PropertyGroup):
    sky: PointerProperty(type=FenestraSkySettings)
    goals: PointerProperty(type=FenestraGoalSettings)
    solve: PointerProperty(type=FenestraSolveSettings)
    results: PointerProperty(type=FenestraResults)
    annual: PointerProperty(type=FenestraAnnualResults)
    display: PointerProperty(type=FenestraDisplaySettings)
    sensor_height: FloatProperty(name="Height", min=0.01, default=0.8, unit='LENGTH',
                                 description="Sensor grid: height above the floor's upper face (m)")
    sensor_spacing: FloatProperty(name="Spacing", min=0.05, default=0.5, unit='LENGTH',
                                  description="Sensor grid: distance between neighbouring sensors (m)")
    sensor_inset_auto: BoolProperty(name="Automatic Inset", default=True,
                                    description="Sensor grid: keep sensors half the spacing off the walls, at least "
                                                "0.25 m (as sDA and EN 17037 practice does)")
    sensor_inset: FloatProperty(name="Wall Inset", min=0.0, max=100.0, default=0.5, unit='LENGTH',
                                description="Sensor grid: distance kept between the sensors and the walls (m)")
    domain_faces: IntProperty(name="Domain Faces", description="Faces marked as opening domain (last count)")
    show_domain: BoolProperty(name="Highlight Domain", default=True,
                              description="Draw the opening domain's faces highlighted in the viewport (not over the openings cut)")
    domain_area: FloatProperty(name="Domain Area", unit='AREA', description="Their area (last count)")
    setup_warnings: StringProperty(name="Setup Warnings",
                                   description="What the last setup check found (check_setup.py), one per line")
    setup_checked: BoolProperty(name="Setup Checked", default=False)


classes = climate_goal_properties.classes + (
    FenestraObjectSettings,
    FenestraSkySettings,
    FenestraGoalSettings,
    FenestraConstraints,
    FenestraTradeoff,
    FenestraSolveSettings,
    FenestraSensorResult,
    FenestraResults,
    FenestraDisplaySettings,
) + annual_properties.classes + (
    FenestraSceneSettings,
)


def register():
    bpy.types.Scene.fenestra = PointerProperty(type=FenestraSceneSettings)
    bpy.types.Object.fenestra = PointerProperty(type=FenestraObjectSettings)


def unregister():
    del bpy.types.Object.fenestra
    del bpy.types.Scene.fenestra
