"""The stages a solve lists in its result's "stages" (docs/solver.md, "Stages"), read from that page so
that the solver and its documentation cannot drift apart."""

import pathlib
import re

ROOT = pathlib.Path(__file__).resolve().parent.parent
SOLVER_MD = ROOT / "docs" / "solver.md"
STOP_REASONS_H = ROOT / "native" / "src" / "solve" / "solve_stage.h"
PER_SENSOR_ONLY = {"coarse grids", "genetic", "successive linearisation", "exact evaluation"}
CLIMATE_ONLY = {"climate model", "climate search", "climate linearisation"}


def _first_column_of_tables():
    section = SOLVER_MD.read_text().split("\n### Stages\n", 1)[1]
    tables, rows = [], []
    for line in section.splitlines():
        if line.startswith("|"):
            rows.append(line)
        elif rows:
            tables.append(rows)
            rows = []
    if rows:
        tables.append(rows)
    return [[re.match(r"\| `([^`]+)` \|", row).group(1) for row in table[2:]] for table in tables]


def documented():
    """(the stages in their documented order, the documented reasons a stage stopped)."""
    names, reasons = _first_column_of_tables()[:2]
    return names, set(reasons)


def in_the_code():
    """The reasons the solver's code can give (solve/solve_stage.h, namespace stop_reason)."""
    section = STOP_REASONS_H.read_text().split("namespace stop_reason {", 1)[1].split("}  // namespace stop_reason")[0]
    return set(re.findall(r'= "([^"]+)";', section))


def check(stages, climate, traced=True):
    """Every stage of the solve's kind listed once, in order, with seconds >= 0 and a documented reason;
    "contributions" first when the solve traced them. Returns {name: reason}."""
    names, reasons = documented()
    others = PER_SENSOR_ONLY if climate else CLIMATE_ONLY
    expected = [n for n in names if n not in others and (traced or n != "contributions")]
    assert [s["name"] for s in stages] == expected
    for s in stages:
        assert s["seconds"] >= 0.0, s
        assert s["stopped_because"] in reasons, s
    return {s["name"]: s["stopped_because"] for s in stages}
