#pragma once
// The opening solver (the paper's section 2): from the contributions and the goals, which
// elements to open, then admissible openings. A sequence of named stages (docs/solver.md, "Stages"),
// each listed in SolveResult::stages with its seconds and why it stopped: the answer in elements
// (solve/linear_stage.h on per-sensor goals, solve/climate_stage.h on climate goals), rectangles and
// the local search, the second start, the climate openings, constraint costs, catalogue sizes, edges
// off the grid (in thick walls too), facade composition, trade-offs, least glazing, verification and
// the climate figures.
#include <string>
#include <vector>

#include "solve/record_queries.h"
#include "solve/solve_result.h"
#include "trace/contributions.h"
#include "util/progress.h"

namespace fenestra {

// Contributions already computed for this scene.
SolveResult solve_openings(const Scene& scene, const Contributions& contributions, Progress* progress = nullptr);
// The same reading the path records through `records` (e.g. a study's shards on a cluster); its
// contributions() holds the dense arrays.
SolveResult solve_openings(const Scene& scene, RecordQueries& records, Progress* progress = nullptr);
// What openings break of the scene's constraints (constraint_violations, with sills and heads
// measured from each panel's faces as the solver measures them).
std::vector<std::string> solved_constraint_violations(const Scene& scene, const std::vector<PanelRectangle>& openings);
// Computes the contributions first (solver.paths or render.paths_per_sensor paths per sensor).
SolveResult solve_openings(const Scene& scene, Progress* progress = nullptr);

}  // namespace fenestra
