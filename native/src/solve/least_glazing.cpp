#include "solve/least_glazing.h"

#include <algorithm>

#include "annual/annual_study.h"
#include "solve/climate_report.h"
#include "solve/record_queries.h"

namespace fenestra {
namespace {

// Whether every climate goal is met by `figures` (false when they are unknown).
bool all_climate_goals_met(const ClimateGoals& goals, const std::vector<ClimateFigure>& figures) {
  if (figures.size() != goals.goals.size()) return false;
  for (size_t g = 0; g < figures.size(); ++g)
    if (!figure_meets(goals.goals[g], figures[g].achieved)) return false;
  return true;
}

double glazing_area(const std::vector<OpeningRectangle>& openings) {
  double area = 0.0;
  for (const OpeningRectangle& o : openings) area += o.width * o.height;
  return area;
}

}  // namespace

std::vector<size_t> passing_by_glazing(const std::vector<GlazingCandidate>& candidates) {
  std::vector<size_t> left;
  for (size_t i = 0; i < candidates.size(); ++i)
    if (candidates[i].meets) left.push_back(i);
  std::stable_sort(left.begin(), left.end(),
                   [&](size_t a, size_t b) { return candidates[a].area_m2 < candidates[b].area_m2; });
  std::vector<size_t> order;
  while (!left.empty()) {
    const double equal = candidates[left.front()].area_m2 * (1.0 + kEqualGlazingShare);
    size_t pick = 0;  // the fewest openings among the equal glazing; the least glass breaks ties
    for (size_t k = 1; k < left.size() && candidates[left[k]].area_m2 <= equal; ++k)
      if (candidates[left[k]].openings < candidates[left[pick]].openings) pick = k;
    order.push_back(left[pick]);
    left.erase(left.begin() + static_cast<std::ptrdiff_t>(pick));
  }
  return order;
}

int least_glazing_entry(const Scene& scene, RecordQueries& records, const ClimateProblem& problem,
                        const std::vector<ClimateFigure>& answer_figures, bool verify, int verify_paths,
                        std::vector<TradeoffResult>* tradeoffs) {
  const ClimateGoals& goals = scene.sensors.climate_goals;
  std::vector<GlazingCandidate> candidates;
  for (TradeoffResult& entry : *tradeoffs) {
    entry.climate = entry.answer ? answer_figures : tradeoff_climate(records, problem, entry, SolveResult());
    candidates.push_back({glazing_area(entry.openings), all_climate_goals_met(goals, entry.climate),
                          static_cast<int>(entry.openings.size())});
  }
  for (size_t i : passing_by_glazing(candidates)) {
    TradeoffResult& entry = (*tradeoffs)[i];
    if (verify && !entry.answer) {
      std::vector<OpeningInput> cutters;
      for (const OpeningRectangle& o : entry.openings) cutters.emplace_back(o.parameter);
      const AnnualStudy cut = records.annual_cut(cutters, verify_paths);
      // The real cutters' figures are shown for it: a design with less glass listed as meeting the
      // goals beside an answer with more would contradict least glazing.
      entry.climate = climate_figures(problem, cut.illuminance.total, cut.illuminance.direct);
      entry.climate_cut = true;
      if (!all_climate_goals_met(goals, entry.climate)) continue;
    }
    return static_cast<int>(i);
  }
  return -1;
}

}  // namespace fenestra
