"""A solve's stages in the user's words (addon/fenestra/blender/com/stage_words.py, no bpy): the
late traces with real cutters are named by the stage that runs them, so that the refinement of edges
in a thick wall and the final check do not read as the contributions traced again; and the core's
status lines the words are told from are still the core's."""

import importlib.util
import os
import re

from conftest import ROOT

NATIVE = os.path.join(ROOT, "native", "src")
spec = importlib.util.spec_from_file_location(  # a module without bpy, loaded without the package (which has)
    "fenestra_blender_stage_words", os.path.join(ROOT, "addon", "fenestra", "blender", "com", "stage_words.py"))
stage_words = importlib.util.module_from_spec(spec)
spec.loader.exec_module(stage_words)

# The lines a thick-walled study's solve shows, in order (examples/thick_walls_study): the stages that
# trace with real cutters keep their own line while they trace.
THICK_WALL_SOLVE = [
    "tracing contribution paths", "assembling the contribution matrix", "assembling the transport matrix",
    "solving: linear start", "genetic algorithm", "solving: exact evaluation",
    "solving: openings within the constraints", "solving: local search over openings",
    "solving: elements within the constraints", "genetic algorithm", "solving: local search over openings",
    "solving: searching whole openings", "solving: openings for edges off the grid in thick walls",
    "solving: what the constraints cost", "solving: local search over openings",
    "solving: edges off the element grid", "solving: edges in thick walls, with real cutters",
    "solving: openings in thick walls merged or removed, with real cutters",
    "solving: all edges in thick walls together, with real cutters",
    "solving: fewer openings", "solving: checking with real cutters",
]
# As an earlier core showed them: each trace with real cutters named itself.
TRACES_NAMED = [
    "solving: edges in thick walls, with real cutters", "tracing the scene with its openings",
    "solving: openings in thick walls merged or removed, with real cutters", "tracing the scene with its openings",
    "solving: all edges in thick walls together, with real cutters", "tracing the scene with its openings",
]


def labels(lines):
    words = stage_words.StageWords()
    return [words.see(line) for line in lines]


def test_thick_wall_traces_are_named_by_their_stage_and_the_last_is_the_check():
    seen = labels(THICK_WALL_SOLVE)
    assert seen[0] == "tracing contribution paths"
    assert seen.count("tracing contribution paths") == 1  # never again: no restart
    assert "tracing the scene with its openings" not in seen
    late = seen[THICK_WALL_SOLVE.index("solving: edges in thick walls, with real cutters"):]
    assert late == [stage_words.THICK_WALL_EDGES, stage_words.THICK_WALL_MERGES, stage_words.THICK_WALL_JOINT,
                    "solving: fewer openings", stage_words.CHECK]
    assert labels(TRACES_NAMED) == [stage_words.THICK_WALL_EDGES, stage_words.THICK_WALL_EDGES,
                                    stage_words.THICK_WALL_MERGES, stage_words.THICK_WALL_MERGES,
                                    stage_words.THICK_WALL_JOINT, stage_words.THICK_WALL_JOINT]


def test_the_check_reads_as_the_check_and_evaluate_as_a_trace():
    seen = labels(["tracing contribution paths", "solving: linear start", "genetic algorithm",
                   "solving: edges off the element grid", "solving: checking with real cutters",
                   "tracing the scene with its openings"])
    assert seen[-2:] == [stage_words.CHECK, stage_words.CHECK]
    assert labels(["tracing the scene with its openings"]) == ["tracing the scene with its openings"]


def test_contributions_traced_again_within_the_solve_are_a_finer_grid_not_a_restart():
    seen = labels(["tracing contribution paths", "solving: linear start", "solving: edges off the element grid",
                   "tracing contribution paths", "assembling the contribution matrix"])
    assert seen[0] == "tracing contribution paths"
    assert seen[3] == stage_words.FINER_GRID
    assert seen[4] == "assembling the contribution matrix"


def test_the_same_line_again_keeps_its_label():
    words = stage_words.StageWords()
    words.see("solving: edges in thick walls, with real cutters")
    assert words.see("tracing the scene with its openings") == words.see("tracing the scene with its openings")


def native_status_lines():
    """Every line the core starts a stage with (Progress::start's first argument)."""
    found = set()
    for folder, _, files in os.walk(NATIVE):
        for name in files:
            if name.endswith((".cpp", ".h")):
                text = open(os.path.join(folder, name)).read()
                found.update(re.findall(r'progress_?->start\(\s*"([^"]+)"', text))
                found.update(re.findall(r'StageStatus \w+\(\s*progress_?,\s*"([^"]+)"', text))
    return found


def test_the_lines_the_words_are_told_from_are_the_cores():
    lines = native_status_lines()
    told = set(stage_words.THICK_WALL_STAGES) | {stage_words.CUTS, stage_words.CONTRIBUTIONS,
                                                  stage_words.CHECK_STAGE}
    assert told <= lines, told - lines
    assert {line for line in lines if "thick wall" in line and "real cutters" in line} == set(stage_words.THICK_WALL_STAGES)
