#include "solve/climate_problem.h"

#include <set>
#include <stdexcept>

#include "annual/annual_records.h"
#include "scene/scene.h"
#include "trace/contributions.h"

namespace fenestra {

ClimateProblem climate_problem(const Scene& scene, const Contributions& c, const SolverGoals& linear) {
  return climate_problem(scene, c.annual.get(), linear);
}

ClimateProblem climate_problem(const Scene& scene, const AnnualRecords* annual, const SolverGoals& linear) {
  if (!annual) throw std::invalid_argument("scene '" + scene.source + "': climate goals need a climate sky's contributions");
  const ClimateGoals& goals = scene.sensors.climate_goals;
  ClimateProblem p;
  std::set<int> rows;
  bool en17037 = false;
  for (const ClimateGoal& g : goals.goals) {
    rows.insert(g.sensors.begin(), g.sensors.end());
    en17037 = en17037 || g.metric == ClimateMetric::En17037;
  }
  for (Eigen::Index i = 0; i < linear.weight.size(); ++i)
    if (linear.weight[i] > 0.0) rows.insert(static_cast<int>(i));
  p.rows.assign(rows.begin(), rows.end());
  p.columns = hourly_columns(*annual, en17037);
  std::vector<double> area;
  for (const Element& e : scene.domain.elements()) area.push_back(static_cast<double>(e.width()) * e.height());
  ClimateObjectiveSettings settings;
  settings.glazing_weight = goals.least_glazing ? 0.05 : 0.0;
  settings.bound_weight = scene.solver.bound_weight;
  settings.horizontal_openings = annual->metric_settings.en17037_openings == DaylightOpenings::Horizontal;
  p.objective = std::make_unique<ClimateObjective>(goals, p.columns, p.rows, &linear, std::move(area), settings);
  p.linear = linear;
  return p;
}

}  // namespace fenestra
