#include "solve/climate_stage.h"

#include <algorithm>

#include "solve/catalogue_snap.h"
#include "solve/linear_objective.h"
#include "solve/linear_start.h"
#include "solve/record_queries.h"
#include "util/progress.h"

namespace fenestra {
namespace {

// Per sensor, whether the scene gives it a goal of its own.
std::vector<uint8_t> scene_goal_weight(const Scene& scene, const Contributions& c) {
  const SolverGoals own = resolve_goals(scene, c);
  std::vector<uint8_t> has(own.weight.size());
  for (Eigen::Index i = 0; i < own.weight.size(); ++i) has[i] = own.weight[i] > 0.0;
  return has;
}

}  // namespace

SolverGoals goals_following(SolverGoals goals, const std::vector<int>& rows, const SensorValues& answer) {
  for (int i : rows) {
    if (goals.weight[i] > 0.0) continue;
    goals.target[i] = answer.value[i];
    goals.weight[i] = 1.0;
  }
  return goals;
}

ElementStage climate_element_stages(const Scene& scene, const ElementGrid& grid, const GeneticSettings& ga,
                                    const OpeningConstraints& constraints, RecordQueries& records,
                                    LinearObjective* objective, SolveResult& out,
                                    std::optional<ClimateProblem>* problem, Progress* progress) {
  const Contributions& c = records.contributions();
  // Elements no admissible opening can cover stay closed: the answer must survive the constraints.
  const std::vector<uint8_t> excluded = elements_out_of_bounds(scene.domain, grid_search_constraints(scene.domain, constraints));
  problem->emplace(climate_problem(scene, records.annual().get(), out.goals));
  std::vector<std::vector<uint8_t>> seeds;
  if (out.goals.count() > 0) {
    run_stage(&out.stages, "linear start", [&] {
      const LinearStart start = linear_start(*objective, grid, progress);
      seeds.push_back(start.open);
      return start.converged ? stop_reason::kConverged : stop_reason::kIterationLimit;
    });
  } else {
    skip_stage(&out.stages, "linear start", stop_reason::kNoSensorGoals);
  }
  const ClimateDesign design = design_for_climate(records, **problem, grid, ga, seeds, excluded, progress);
  out.history = design.history;
  out.generations = design.generations;
  out.climate.active = true;
  out.climate.element_figures = design.figures;
  out.climate.all_open_figures = design.all_open_figures;
  out.climate.linearisations = design.linearisations;
  out.climate.model_bytes = design.model_bytes;
  out.timings.push_back({"climate model", design.seconds_model});
  out.timings.push_back({"climate search", design.seconds_search});
  out.stages.insert(out.stages.end(), design.stages.begin(), design.stages.end());

  ElementStage stage;
  stage.open = stage.start_open = design.open;
  stage.values = records.exact(design.open);
  out.goals = goals_following(out.goals, (*problem)->rows, stage.values);
  *objective = linear_objective(c, out.goals, scene.solver.bound_weight);
  stage.fitness = exact_fitness(*objective, grid, ga.shape, stage.open, stage.values.value - c.closed.value);
  out.open = design.open;
  out.start_error = goal_error(out.goals, stage.values.value);
  out.unconstrained_open = out.open;
  out.unconstrained_openings = merge_into_rectangles(scene.domain, out.open);
  out.unconstrained_error = out.start_error;
  return stage;
}

ClimateScore climate_score(RecordQueries& records, const ClimateProblem& problem, const std::vector<uint8_t>& open) {
  const ClimateYear year = climate_year(records, problem, open);
  ClimateScore score;
  score.error = year.error;
  const std::vector<ClimateFigure> figures = problem.objective->figures(year.tally);
  score.all_met = true;
  std::vector<int> rows;
  for (size_t g = 0; g < figures.size(); ++g) {
    const ClimateGoal& goal = problem.objective->goals().goals[g];
    if (figure_meets(goal, figures[g].achieved)) continue;
    score.all_met = false;
    if (goal.sense() == GoalSense::AtLeast || (goal.sense() == GoalSense::Target && figures[g].achieved < goal.required()))
      rows.insert(rows.end(), goal.sensors.begin(), goal.sensors.end());
  }
  std::sort(rows.begin(), rows.end());
  rows.erase(std::unique(rows.begin(), rows.end()), rows.end());
  score.short_rows = std::move(rows);
  return score;
}

SolverGoals raised_goals(const Scene& scene, const Contributions& c, SolverGoals goals, const SolverGoals& followed,
                         const std::vector<int>& rows, double gain) {
  const std::vector<uint8_t> own = scene_goal_weight(scene, c);
  for (int i : rows)
    if (!own[i]) goals.target[i] = followed.target[i] * gain;
  return goals;
}

}  // namespace fenestra
