#pragma once
// What the climate goals look at (docs/solver.md, "Climate goals"): the goal sensors (the model's
// rows), the hours that can matter (its columns) and the objective. A shard of a study on a cluster
// builds the same problem from the same scene and per-sensor goals.
#include <memory>
#include <vector>

#include "annual/hourly_flip_model.h"
#include "solve/climate_objective.h"
#include "solve/goals.h"

namespace fenestra {

struct AnnualRecords;  // annual/annual_records.h
struct Contributions;  // trace/contributions.h
struct Scene;          // scene/scene.h

struct ClimateProblem {
  std::vector<int> rows;  // the goal sensors, ascending scene indices
  HourlyColumns columns;
  std::unique_ptr<ClimateObjective> objective;
  SolverGoals linear;  // the per-sensor goals it was built with
};

// `linear`: the scene's per-sensor goals (may have none); `annual`: the climate sky's sources and
// hours (RecordQueries::annual), std::invalid_argument when null.
ClimateProblem climate_problem(const Scene& scene, const AnnualRecords* annual, const SolverGoals& linear);
ClimateProblem climate_problem(const Scene& scene, const Contributions& c, const SolverGoals& linear);

}  // namespace fenestra
