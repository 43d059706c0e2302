#pragma once
// The solver's stages on climate goals (docs/solver.md, "Climate goals"): the answer in elements
// from the year's hourly model (solve/climate_design.h), the per-sensor goals the constraints stage
// then follows, and what raises that light when openings within the constraints miss a goal.
#include <cstdint>
#include <optional>
#include <vector>

#include "scene/scene.h"
#include "solve/climate_design.h"
#include "solve/element_grid.h"
#include "solve/genetic.h"
#include "solve/goals.h"
#include "solve/linear_stage.h"
#include "solve/solve_result.h"

namespace fenestra {

class Progress;
class RecordQueries;  // solve/record_queries.h

// The stages "linear start" (the per-sensor goals' start, a seed), "climate model", "climate search"
// and "climate linearisation". `constraints`: as the solver measures them (elements no admissible
// opening can cover stay closed). Sets *problem, and *objective to the per-sensor goals the
// constraints stage follows (out.goals: goals_following); fills `out`'s element answer, climate
// figures, timings and stages.
ElementStage climate_element_stages(const Scene& scene, const ElementGrid& grid, const GeneticSettings& ga,
                                    const OpeningConstraints& constraints, RecordQueries& records,
                                    LinearObjective* objective, SolveResult& out,
                                    std::optional<ClimateProblem>* problem, Progress* progress);

// The per-sensor goals the constraints stage follows after a climate search: each sensor the
// climate goals look at takes the answer's mean illuminance of the occupied hours as its goal
// (sensors with a goal of their own keep it), so that openings within the constraints give the
// light that met the climate goals.
SolverGoals goals_following(SolverGoals goals, const std::vector<int>& rows, const SensorValues& answer);

// Gains on the followed light of the sensors whose goals the openings within the constraints miss
// from below (a room of a floor, the others kept), one per round.
constexpr double kClimateFollowGains[] = {1.15, 1.35, 1.6, 1.9, 2.25, 2.7};

// The year of a set of open elements scored by the climate objective, and whether every goal is met.
struct ClimateScore {
  double error = 0.0;
  bool all_met = false;
  // The sensors of the goals missed from below (sDA, UDI, EN 17037, a mean short of its target):
  // more light is what they need. Ascending, distinct.
  std::vector<int> short_rows;
};
ClimateScore climate_score(RecordQueries& records, const ClimateProblem& problem, const std::vector<uint8_t>& open);

// `goals` with the light of `rows` set to `followed`'s times `gain`, but for the sensors that have a
// goal in the scene itself (those are not raised).
SolverGoals raised_goals(const Scene& scene, const Contributions& c, SolverGoals goals, const SolverGoals& followed,
                         const std::vector<int>& rows, double gain);

}  // namespace fenestra
