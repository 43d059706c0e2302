// Benchmark of design for climate goals on the paper-scale scene (100 sensors x 200 elements,
// Chicago year, sDA300/50 % >= 55 % and ASE1000,250 <= 10 %, least glazing): the hourly model,
// 500 generations of the genetic algorithm on it, and the whole solve; beside them, what the same
// number of candidates would cost as forward annual studies from the same records (the way an
// optimiser wrapped around a simulation works). Ratios are what to read: timings are noisy here.
#include <chrono>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>

#include "annual/annual_contributions.h"
#include "annual/annual_study.h"
#include "scene/scene.h"
#include "solve/climate_design.h"
#include "solve/climate_search.h"
#include "solve/record_queries.h"
#include "solve/element_grid.h"
#include "solve/solver.h"
#include "trace/contributions.h"

namespace {

using namespace fenestra;
using json = nlohmann::json;

const std::string kExamples = FENESTRA_EXAMPLES;

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

Scene paper_scale_climate() {
  std::ifstream in(kExamples + "/paper_scale/scene.json");
  json scene = json::parse(in);
  scene["sky"] = {{"type", "climate"}, {"weather", kExamples + "/weather/USA_IL_Chicago-OHare.Intl.AP.725300_TMY3.epw"}};
  scene["goals"] = {{"climate", {{{"metric", "sda"}, {"min_area_fraction", 0.55}}, {{"metric", "ase"}, {"max_area_fraction", 0.10}}}},
                    {"least_glazing", true}};
  scene["solver"] = {{"generations", 500}, {"verify", false}, {"tradeoffs", false}};
  return parse_scene(scene.dump(), kExamples + "/paper_scale", "paper_scale (climate goals)");
}

}  // namespace

int main() {
  const Scene scene = paper_scale_climate();
  auto t = std::chrono::steady_clock::now();
  const Contributions c = compute_contributions(scene);
  const double contributions_s = seconds_since(t);
  const SolverGoals goals = resolve_goals(scene, c);
  const ClimateProblem problem = climate_problem(scene, c, goals);
  const ElementGrid grid = ElementGrid::from_domain(scene.domain);
  std::printf("[climate design] paper_scale: %zu sensors x %zu elements, %zu hours in the model (%d occupied), "
              "%d paths per sensor; contributions %.2f s\n",
              c.sensor_count(), c.element_count(), problem.columns.hour.size(), problem.columns.occupied_hours,
              c.paths_per_sensor, contributions_s);

  t = std::chrono::steady_clock::now();
  LocalRecordQueries records(scene, c, nullptr);
  const std::unique_ptr<ClimateModel> model = records.climate_model(problem, std::vector<uint8_t>(c.element_count(), 0), {});
  const double model_s = seconds_since(t);
  std::printf("  hourly model: %.2f s, %.0f MB\n", model_s, model->model_bytes() / 1e6);

  GeneticSettings ga;
  ga.generations = 500;
  t = std::chrono::steady_clock::now();
  const GeneticResult r =
      run_climate_genetic(*model, *problem.objective, grid, {std::vector<uint8_t>(c.element_count(), 0)}, ga);
  const double ga_s = seconds_since(t);
  const double children = static_cast<double>(r.generations) * ga.population;
  std::printf("  genetic algorithm: %d generations x %d children in %.2f s (%.0f children/s; target: 500 "
              "generations <= 30 s)\n",
              r.generations, ga.population, ga_s, children / ga_s);

  t = std::chrono::steady_clock::now();
  const int studies = 5;
  for (int i = 0; i < studies; ++i) annual_study(c, r.best);
  const double study_s = seconds_since(t) / studies;
  std::printf("  one forward annual study from the records: %.3f s; %.0f candidates that way: %.0f s, %.0fx the "
              "genetic algorithm\n",
              study_s, children, study_s * children, study_s * children / ga_s);

  t = std::chrono::steady_clock::now();
  const SolveResult solved = solve_openings(scene, c);
  const double solve_s = seconds_since(t);
  std::printf("  whole solve (model, search, linearisation, constraints): %.2f s;", solve_s);
  for (size_t g = 0; g < solved.climate.achieved.size(); ++g)
    std::printf(" %s: %.1f %%;", scene.sensors.climate_goals.goals[g].describe().c_str(),
                100.0 * solved.climate.achieved[g].achieved);
  std::printf(" glazing %.2f of %.2f m^2\n", solved.climate.glazing_area_m2, solved.climate.domain_area_m2);
  return 0;
}
