"""The native core's messages in the add-on user's words.

The core speaks to whoever wrote the scene file: it names files, JSON keys
(`opening_domain.element_size`, `goals.uniform[0].level`), command-line options and OBJ groups
("material 'Plaster', group 'Room.domain'"). The add-on wrote that file, so its user knows none of
these: they know objects, marked faces and the fields of the Fenestra tab. for_user() rewrites a
message into those terms and leaves the core's text for the command line as it is.

No bpy here (tests run it on the core's real messages without Blender).
"""

import re

# Keys of the scene file -> the field of the Fenestra tab that writes them.
FIELDS = {
    "opening_domain.element_size": "Element Size",
    "solver.element_size": "Element Size",
    "element_size": "Element Size",
    "opening_domain.thickness": "Wall Thickness",
    "solver.paths": "Paths",
    "render.paths_per_sensor": "Paths",
    "solver.generations": "Generations",
    "solver.population": "Population",
    "solver.seed": "Seed",
    "render.seed": "Seed",
    "sky.turbidity": "Turbidity",
    "sky.ground_reflectance": "Ground Reflectance",
    "sky.horizontal_illuminance": "Illuminance",
    "sky.radiance": "Illuminance",
    "sky.latitude": "Latitude",
    "sky.longitude": "Longitude",
    "sky.utc_offset": "UTC Offset",
    "sky.north_offset_deg": "North Offset",
    "sky.step_minutes": "Step",
    "sky.start": "Start",
    "sky.end": "End",
    "sky.date": "the date",
    "sky.date_end": "the end date",
    "sky.resolution": "Map Width",
    "sky.weather": "Weather File",
    "sky.patches": "Sky Patches",
    "sky.occupied": "Occupied From / To",
}
CONSTRAINTS = {
    "min_area": "Min Area", "max_area": "Max Area", "min_aspect": "Min Aspect", "max_aspect": "Max Aspect",
    "min_width": "Min Width", "max_width": "Max Width", "min_height": "Min Height", "max_height": "Max Height",
    "max_openings": "Max Openings", "min_gap": "Min Gap", "margin": "Margin", "sill_min": "Min Sill",
    "head_max": "Max Head", "head_clearance": "Head Clearance", "max_openings_per_panel": "Max per Panel",
    "panel_width_per_opening": "Width per Opening", "automatic": "Automatic",
    "full_height": "Doors / Full-Height Glazing", "catalogue": "Catalogue",
    "align_sills": "Align Sills", "align_heads": "Align Heads", "equal_widths": "Equal Widths",
    "same_type_in_row": "Same Type in a Row", "symmetric": "Symmetric", "equal_spacing": "Equal Spacing",
    "sill_heights": "Sill Heights",
}
FIELDS.update({"solver.constraints." + k: v for k, v in CONSTRAINTS.items()})
# What is left of a key the tab has no field for: the part of the study it belongs to.
SECTIONS = {
    "opening_domain": "the opening domain", "sensors": "the sensors", "goals": "the goals", "sky": "the sky",
    "solver": "the solve settings", "render": "the solve settings", "materials": "a material",
    "geometry": "the exported geometry",
}
UNITS = {"normalized": "normalized", "daylight_factor": "daylight factor", "lux": "lux"}

_KEY = r"[a-z_]+(?:\[\d+\])?(?:\.[A-Za-z0-9_]+(?:\[\d+\])?)*"
_PREFIX = re.compile(r"^scene '[^']*': ")
_PANEL = re.compile(r"(?:the (curved )?opening-domain panel of )?material '([^']*)'(?:, group '([^']*)')?")


def _number(text):
    """A core number ("1.000000", "1e+12") as the user would write it."""
    return "%g" % float(text)


class _Context:
    """What the add-on knows about the study: which object each OBJ group and sensor came from."""

    def __init__(self, study, openings):
        self.group_objects = dict(getattr(study, "group_objects", {}) or {})
        self.sensor_objects = list(getattr(study, "sensor_objects", []) or [])
        self.openings = list(openings or [])

    def object_of_group(self, group):
        if group in self.group_objects:
            return self.group_objects[group]
        return group[:-len(".domain")] if group.endswith(".domain") else group

    def sensor(self, index):
        """'vertex k of 'Object'' for the sensor at index in the study's order."""
        start = 0
        for name, count in self.sensor_objects:
            if index < start + count:
                return "vertex %d of '%s'" % (index - start, name)
            start += count
        return "sensor %d" % index

    def opening(self, index):
        return "'%s'" % self.openings[index] if index < len(self.openings) else "opening %d" % (index + 1)


def _panel(match, ctx):
    """A core panel label as the faces the user marked."""
    curved, material, group = match.group(1), match.group(2), match.group(3)
    faces = "the curved domain faces" if curved else "the domain faces"
    if group:
        text = "%s of '%s'" % (faces, ctx.object_of_group(group))
        return text + (" (material '%s')" % material if material != "default" else "")
    return "%s of material '%s'" % (faces, material)


def _goal_limit(match, ctx):
    """"a goal in U units must not exceed TOP, got V" at a goal key."""
    key, units, top, value = match.group(1), match.group(2), _number(match.group(3)), _number(match.group(4))
    words = UNITS.get(units, units)
    limit = {"normalized": "at most 1 (the light with every element open)",
             "daylight_factor": "at most 100 %"}.get(units, "at most %s" % top)
    painted = re.match(r"(?:sensors\.)?goals\[(\d+)\]$", key)
    if painted:
        return ("The painted goal of %s is %s: a %s goal is %s. Lower Scale, or paint it darker"
                % (ctx.sensor(int(painted.group(1))), value, words, limit))
    field = {"min": "Minimum", "max": "Maximum"}.get(key.rsplit(".", 1)[-1], "Goal")
    return "%s %s is too high: a %s goal is %s" % (field, value, words, limit)


def _negative_goal(match, ctx):
    key, value = match.group(1), _number(match.group(2))
    painted = re.match(r"(?:sensors\.)?goals\[(\d+)\]$", key)
    if painted:
        return "The painted goal of %s is %s: goals must not be negative" % (ctx.sensor(int(painted.group(1))), value)
    return "Goal %s: goals must not be negative" % value


# (pattern, replacement) tried in order on the message without its "scene '...': " prefix.
RULES = [
    # A panel on which no whole element fits: its bounding box (the core's width x height) says
    # nothing of an L-shaped panel's narrow arms, so it is left out.
    (re.compile(r"^(?:opening_domain: )?opening_domain\.element_size ([\d.e+-]+) m is larger than (.*?) "
                r"\([\d.e+-]+ m x [\d.e+-]+ m\): no element fits$"),
     lambda m, c: ("Element Size %s m is too large for %s: not one whole element fits on a flat part of "
                   "them. Use a smaller Element Size, or mark a larger area" % (_number(m.group(1)), m.group(2)))),
    (re.compile(r"^(" + _KEY + r"): a goal in (\w+) units must not exceed ([\d.e+-]+), got ([\d.e+-]+)$"), _goal_limit),
    (re.compile(r"^(" + _KEY + r"): a goal must not be negative, got ([\d.e+-]+)$"), _negative_goal),
    (re.compile(r"^goals\.uniform\[\d+\]: needs min <= level <= max$"),
     lambda m, c: "The goal's bounds are crossed: Minimum must not exceed Goal, nor Goal exceed Maximum"),
    (re.compile(r"^(?:opening_domain: )?opening_domain\.thickness ([\d.e+-]+ m) disagrees with the wall modelled behind "
                r"(.*?): its outer face is ([\d.e+-]+ m) behind the marked face \(leave thickness out to use the "
                r"model's\)$"),
     lambda m, c: ("Wall Thickness %s disagrees with the wall modelled behind %s: its outer face is %s behind "
                   "them. Set Wall Thickness to 0 to use the model's" % m.groups())),
    # The face's number counts the OBJ group's triangles, not the object's faces: left out.
    (re.compile(r"^(?:geometry: )?geometry '[^']*': face \d+ of group '([^']*)' is degenerate \(zero area\)$"),
     lambda m, c: ("A face of '%s'%s has no area (a zero-length edge, or corners in a line): delete it, for instance "
                   "with Mesh > Clean Up > Degenerate Dissolve in Edit Mode"
                   % (c.object_of_group(m.group(1)), " (one of its domain faces)" if m.group(1).endswith(".domain")
                      and m.group(1) in c.group_objects else ""))),
    (re.compile(r"^opening (\d+) (does not lie on any flat opening-domain panel).*$"),
     lambda m, c: ("%s does not lie flat on the opening domain: move it back onto the marked faces"
                   % c.opening(int(m.group(1))))),
    # Annual Daylight reads light through a thick wall element by element (its records follow each
    # element's tube): an edge between grid lines cannot be counted there.
    (re.compile(r"^opening (\d+) has an edge between the element grid's lines \(.*?; lines every ([\d.e+-]+) m\) "
                r"on panel \d+ \((.*)\), whose wall is ([\d.e+-]+) m thick: .*$"),
     lambda m, c: ("%s has an edge between the lines of the element grid (every %s m) on %s, whose wall is %s m "
                   "thick: Annual Daylight counts the light through a thick wall element by element. Solve again "
                   "with Edges on Element Grid (Solve panel), or move and scale the cutter onto the grid"
                   % (c.opening(int(m.group(1))), _number(m.group(2)), m.group(3), _number(m.group(4))))),
    (re.compile(r"^opening (\d+) reaches beyond the elements of panel \d+ \((.*); its grid spans (u [\d.e+-]+\.\.[\d.e+-]+ m, "
                r"v [\d.e+-]+\.\.[\d.e+-]+ m)\): paths are recorded by element.*$"),
     lambda m, c: ("%s reaches beyond the element grid of %s (%s): Annual Daylight counts the light element by "
                   "element, so an opening must lie within the grid. Move or scale the cutter back"
                   % (c.opening(int(m.group(1))), m.group(2), m.group(3)))),
    (re.compile(r"^opening (\d+) (.*)$"), lambda m, c: "%s %s" % (c.opening(int(m.group(1))), m.group(2))),
]
# The cost model's advice, in the tab's terms.
REPHRASED = [
    (re.compile(r"fewer paths \((?:solver\.paths, )?render\.paths_per_sensor, --paths\)"),
     "fewer paths (a lower Quality, or Quality Custom with fewer Paths)"),
    (re.compile(r"a larger element_size \(opening_domain\.element_size or solver\.element_size\)"),
     "a larger Element Size"),
]
# Clauses about what only the command line or the Python API can do.
DROPPED = [
    re.compile(r",? or raise the limit with --max-memory \(max_memory= in Python\)"),
    re.compile(r",? or a solver\.time_budget_s"),
    re.compile(r" \(MemAvailable\)"),
    re.compile(r" \(constraint_costs in the result\)"),
    re.compile(r"EnvironmentMap\((?:[^()]|\([^()]*\))*\): "),
]


def _field(key):
    """A key as the field that writes it, or the part of the study it belongs to; None for a flag."""
    key = key.strip()
    if key.startswith("-"):
        return None
    climate = re.match(r"goals\.climate\[(\d+)\]", key)
    if climate:  # its place in the Climate Goals list, numbered from 1
        return "Climate goal %d" % (int(climate.group(1)) + 1)
    if key.startswith("sensors.groups"):
        return "the climate goals' sensor groups"
    bare = re.sub(r"\[\d+\]", "", key)
    if bare in FIELDS:
        return FIELDS[bare]
    if bare.startswith("goals.uniform"):
        return {"min": "Minimum", "max": "Maximum"}.get(bare.rsplit(".", 1)[-1], "Goal")
    if bare.startswith("solver.constraints"):
        return "the constraints"
    return SECTIONS.get(bare.split(".")[0], "the study")


def _key_lists(text):
    """"(solver.paths, render.paths_per_sensor, --paths)": the fields once, or nothing when the
    text before already names them."""
    def replace(match):
        items = [i for i in re.split(r",\s*|\s+or\s+", match.group(1)) if i]
        if not all(re.fullmatch(_KEY, i) or i.startswith("--") for i in items):
            return match.group(0)
        names = []
        for item in items:
            name = _field(item)
            if name and name not in names:
                names.append(name)
        before = text[max(0, match.start() - 40):match.start()]
        if not names or all(n.lower() in before.lower() for n in names):
            return ""
        return " (%s)" % " or ".join(names)
    return re.sub(r" \(([^()]*)\)", replace, text)


def _keys(text):
    """The remaining keys (dotted, or snake_case constraint names) as fields."""
    text = re.sub(r"\b(?:opening_domain|solver|render|sensors|goals|sky|materials)(?:\[\d+\])?"
                  r"(?:\.[A-Za-z0-9_]+(?:\[\d+\])?)+", lambda m: _field(m.group(0)), text)
    text = re.sub(r"\b(" + "|".join(CONSTRAINTS) + r"|element_size)\b",
                  lambda m: FIELDS.get(m.group(1), CONSTRAINTS.get(m.group(1))), text)
    return text


def _paths(text):
    """File paths (the study's, a sky map's) are the add-on's business, not the user's."""
    text = re.sub(r"(geometry|scene|openings|environment map) '(?:/|[A-Za-z]:\\)[^']*'", r"the study's \1", text)
    text = re.sub(r"'(?:/|[A-Za-z]:\\)[^']*'", "a file of the study", text)
    return re.sub(r"(?<![\w.])/(?:[\w.-]+/)+[\w.-]*", "a file of the study", text)


def for_user(message, study=None, openings=()):
    """The message (a string or an exception) in the add-on user's words. study (export.Study)
    names the objects behind OBJ groups and sensor indices; openings names the cutters, in the
    order they were given to the core."""
    ctx = _Context(study, openings)
    text = _PREFIX.sub("", str(message).strip())
    for pattern in DROPPED:
        text = pattern.sub("", text)
    for pattern, words in REPHRASED:
        text = pattern.sub(words, text)
    text = _PANEL.sub(lambda m: _panel(m, ctx), text)
    for pattern, rewrite in RULES:
        match = pattern.match(text)
        if match:
            text = rewrite(match, ctx)
            break
    else:
        # "key: what is wrong": the field, or the part of the study, then what is wrong.
        keyed = re.match(r"^(" + _KEY + r"): (?:" + _KEY + r": )?(.*)$", text)
        if keyed and ("." in keyed.group(1) or keyed.group(1) in SECTIONS):
            text = "%s: %s" % (_field(keyed.group(1)), keyed.group(2))
    text = _paths(_keys(_key_lists(text)))
    return text[:1].upper() + text[1:]
