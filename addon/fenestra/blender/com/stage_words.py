"""A running solve's stage in the user's words, from the native core's status lines (no bpy).

The core names a stage when it starts it ("solving: edges in thick walls, with real cutters"), and
the stages that trace with real cutters (the edge search in thick walls, the trade-offs, the final
check) keep their line while they trace (StageStatus, native/src/util/progress.h): they read
"refining edges in the thick wall: ..." and "checking with real cutters". A trace with real cutters
outside a stage (Evaluate) names itself "tracing the scene with its openings"; one after a thick-wall
stage (should a stage not hold its line) is told by that stage. A second "tracing contribution
paths" after the solver has begun is a finer trace, not a new start. Other lines are shown as the
core words them."""

THICK_WALL_EDGES = "refining edges in the thick wall: tracing finer steps"
THICK_WALL_JOINT = "refining edges in the thick wall: all edges together"
THICK_WALL_MERGES = "refining openings in the thick wall: merged or removed"
FINER_GRID = "refining edges in the thick wall: tracing a finer grid"
CHECK = "checking with real cutters"

CUTS = "tracing the scene with its openings"  # the core's words for any trace with real cutters
CONTRIBUTIONS = "tracing contribution paths"
SOLVING = "solving: "
# The core's stage lines in the thick wall, and what the stage does in the user's words.
THICK_WALL_STAGES = {
    "solving: edges in thick walls, with real cutters": THICK_WALL_EDGES,
    "solving: all edges in thick walls together, with real cutters": THICK_WALL_JOINT,
    "solving: openings in thick walls merged or removed, with real cutters": THICK_WALL_MERGES,
}
CHECK_STAGE = "solving: checking with real cutters"


class StageWords:
    """Follows one solve's status lines, in the order they come; `label` is the current stage's
    words."""

    def __init__(self):
        self.status = None       # the line last seen
        self.stage = None        # the last "solving: ..." line seen
        self.label = ""

    def see(self, status):
        """Takes the core's current line; returns the label."""
        if status == self.status:
            return self.label
        self.status = status
        if status.startswith(SOLVING) or status == "genetic algorithm":
            self.stage = status
        if status in THICK_WALL_STAGES:
            self.label = THICK_WALL_STAGES[status]
        elif status == CHECK_STAGE:
            self.label = CHECK
        elif status == CUTS:
            self.label = THICK_WALL_STAGES.get(self.stage, CHECK if self.stage == CHECK_STAGE else CUTS)
        elif status == CONTRIBUTIONS and self.stage is not None:
            self.label = FINER_GRID
        else:
            self.label = status
        return self.label
