#include "solve/linear_stage.h"

#include <algorithm>
#include <set>

#include "solve/coarse_grid.h"
#include "solve/linear_objective.h"
#include "solve/linear_start.h"
#include "solve/record_queries.h"
#include "util/progress.h"

namespace fenestra {
namespace {

// What the stages share.
struct ElementSearch {
  const Scene& scene;
  const Contributions& c;
  const LinearObjective& objective;
  const ElementGrid& grid;
  const GeneticSettings& ga;
  RecordQueries& records;
  SolveResult& out;
  Progress* progress;

  double fitness_of(const std::vector<uint8_t>& open, const SensorValues& exact) const {
    return exact_fitness(objective, grid, ga.shape, open, exact.value - c.closed.value);
  }
};

// Stage 1 on the fine grid.
LinearStart fine_linear_start(const ElementSearch& s, double* seconds) {
  if (s.progress) s.progress->start("solving: linear start", 1);
  LinearStart start;
  *seconds = run_stage(&s.out.stages, "linear start", [&] {
    start = linear_start(s.objective, s.grid, s.progress);
    return start.converged ? stop_reason::kConverged : stop_reason::kIterationLimit;
  });
  s.out.nnls_relative_rms = start.relative_rms;
  s.out.nnls_iterations = start.iterations;
  return start;
}

// Coarse-to-fine starts (4a, then 2a) when the grid is large enough: on each level the linear
// start and a genetic run of half the generations, seeded with the coarser level's answer. Returns
// each level's answer on the fine grid.
std::vector<std::vector<uint8_t>> coarse_grid_starts(const ElementSearch& s, double* seconds) {
  std::vector<std::vector<uint8_t>> starts;
  *seconds = 0.0;
  if (!s.scene.solver.coarse_to_fine) {
    skip_stage(&s.out.stages, "coarse grids", stop_reason::kNoCoarseToFine);
    return starts;
  }
  const double ran = run_stage(&s.out.stages, "coarse grids", [&] {
    const char* why = stop_reason::kGridTooSmall;
    std::vector<uint8_t> carried;  // the previous (coarser) level's answer, on the fine grid
    for (int factor : {4, 2}) {
      const CoarseGrid coarse = coarsen(s.grid, factor);
      if (coarse.grid.size() < 4 || coarse.grid.size() * 2 > s.grid.size()) continue;
      LinearObjective level = s.objective;
      level.E = coarse.columns(s.objective.E);
      std::vector<std::vector<uint8_t>> level_seeds = {linear_start(level, coarse.grid, s.progress).open};
      if (!carried.empty()) {  // the coarser answer, as well as it fits this grid
        std::vector<uint8_t> mapped(coarse.grid.size(), 0);
        for (size_t k = 0; k < carried.size(); ++k) mapped[coarse.coarse_of[k]] |= carried[k];
        level_seeds.push_back(mapped);
      }
      GeneticSettings level_ga = s.ga;
      level_ga.generations = std::max(1, s.ga.generations / 2);
      level_ga.time_budget_s = 0.0;
      const GeneticResult r = run_genetic(level, coarse.grid, level_seeds, level_ga, s.progress);
      carried = coarse.expand(r.best);
      starts.push_back(carried);
      s.out.coarse_factors.push_back(factor);
      why = genetic_stop_reason(r);
      if (s.progress) s.progress->throw_if_cancelled();
    }
    return why;
  });
  if (!starts.empty()) *seconds = ran;
  return starts;
}

// Stage 2 on the fine grid.
GeneticResult fine_genetic_run(const ElementSearch& s, const std::vector<std::vector<uint8_t>>& seeds,
                               double* seconds) {
  if (s.progress) s.progress->start("solving: genetic algorithm", 1);
  GeneticResult result;
  *seconds = run_stage(&s.out.stages, "genetic", [&] {
    result = run_genetic(s.objective, s.grid, seeds, s.ga, s.progress);
    return genetic_stop_reason(result);
  });
  s.out.history = result.history;
  s.out.generations = result.generations;
  if (s.progress) s.progress->throw_if_cancelled();
  return result;
}

// The linear model (each element's light with the others closed) misses what elements do together:
// light reflected off opened elements (1-3 % on thin walls), and in thick walls the light that
// passes obliquely through neighbouring open elements and the reveals of closed ones (tens of
// percent). Successive linearisation: the exact linear model about the best state so far (each
// element's flip, from the path records), a shorter genetic run from there, the exact choice among
// its best states; repeated while the exact fitness improves. Returns the best states of every run.
std::vector<std::vector<uint8_t>> successive_linearisation(const ElementSearch& s, const GeneticResult& result,
                                                           const std::vector<std::vector<uint8_t>>& seeds,
                                                           double* seconds) {
  std::vector<std::vector<uint8_t>> candidates = result.elite;
  if (candidates.empty()) candidates.push_back(result.best);
  if (s.ga.generations <= 0) {
    skip_stage(&s.out.stages, "successive linearisation", stop_reason::kNoGenerations);
    *seconds = 0.0;
    return candidates;
  }
  *seconds = run_stage(&s.out.stages, "successive linearisation", [&] {
    std::vector<uint8_t> about = result.best;
    SensorValues about_values = s.records.exact(about);
    double about_fitness = s.fitness_of(about, about_values);
    for (int round = 0; round < kLinearisationRounds; ++round) {
      const LinearObjective local = linearised_objective(s.objective, s.records, about, about_values.value);
      GeneticSettings second = s.ga;
      second.generations = std::max(1, s.ga.generations / 4);
      second.seed = s.ga.seed + 1 + round;
      std::vector<std::vector<uint8_t>> second_seeds = {about};
      second_seeds.insert(second_seeds.end(), seeds.begin(), seeds.end());
      const GeneticResult refined = run_genetic(local, s.grid, second_seeds, second, s.progress);
      s.out.generations += refined.generations;
      candidates.insert(candidates.end(), refined.elite.begin(), refined.elite.end());
      bool improved = false;
      for (const auto& open : refined.elite) {
        const SensorValues& exact = s.records.exact(open);
        const double f = s.fitness_of(open, exact);
        if (f < about_fitness * (1.0 - 1e-6)) about = open, about_values = exact, about_fitness = f, improved = true;
      }
      if (!improved) return stop_reason::kNoImprovement;
    }
    return stop_reason::kRoundLimit;
  });
  return candidates;
}

// The final choice among the best states uses the exact evaluation from the path records.
ElementStage exact_choice(const ElementSearch& s, std::vector<std::vector<uint8_t>> candidates,
                          const LinearStart& fine_start) {
  if (s.progress) s.progress->start("solving: exact evaluation", 1);
  ElementStage stage;
  SolveResult& out = s.out;
  const double seconds = run_stage(&out.stages, "exact evaluation", [&] {
    candidates.push_back(fine_start.open);
    std::vector<std::pair<double, size_t>> ranked;  // distinct states by fitness
    std::set<std::vector<uint8_t>> seen;
    for (size_t k = 0; k < candidates.size(); ++k) {
      const std::vector<uint8_t>& open = candidates[k];
      const SensorValues& exact = s.records.exact(open);
      const double f = s.fitness_of(open, exact);
      if (seen.insert(open).second) ranked.push_back({f, k});
      if (f < stage.fitness) {
        stage.fitness = f;
        out.open = open;
        stage.values = exact;
      }
    }
    std::sort(ranked.begin(), ranked.end());
    for (const auto& [f, k] : ranked) stage.candidates.push_back(candidates[k]);
    out.start_error = goal_error(out.goals, s.records.exact(fine_start.open).value);
    out.unconstrained_open = out.open;
    out.unconstrained_openings = merge_into_rectangles(s.scene.domain, out.open);
    out.unconstrained_error = goal_error(out.goals, stage.values.value);
    return stop_reason::kDone;
  });
  out.timings.push_back({"exact evaluation", seconds});
  stage.start_open = fine_start.open;
  stage.start_continuous = fine_start.continuous;
  stage.open = out.open;
  return stage;
}

}  // namespace

ElementStage linear_element_stages(const Scene& scene, const LinearObjective& objective, const ElementGrid& grid,
                                   const GeneticSettings& ga, RecordQueries& records, SolveResult& out,
                                   Progress* progress) {
  const ElementSearch s{scene, records.contributions(), objective, grid, ga, records, out, progress};
  double start_seconds = 0.0, coarse_seconds = 0.0, genetic_seconds = 0.0, linearisation_seconds = 0.0;
  const LinearStart fine_start = fine_linear_start(s, &start_seconds);
  std::vector<std::vector<uint8_t>> seeds = {fine_start.open};
  for (std::vector<uint8_t>& coarse : coarse_grid_starts(s, &coarse_seconds)) seeds.push_back(std::move(coarse));
  out.timings.push_back({"linear start", start_seconds});
  if (coarse_seconds > 0.0) out.timings.push_back({"coarse grids", coarse_seconds});

  const GeneticResult result = fine_genetic_run(s, seeds, &genetic_seconds);
  std::vector<std::vector<uint8_t>> candidates = successive_linearisation(s, result, seeds, &linearisation_seconds);
  out.timings.push_back({"genetic", genetic_seconds + linearisation_seconds});
  if (progress) progress->throw_if_cancelled();
  return exact_choice(s, std::move(candidates), fine_start);
}

ElementChoice search_within_bounds(const LinearObjective& objective, const ElementGrid& grid, const GeneticSettings& ga,
                                   RecordQueries& records, const std::vector<uint8_t>& linear_start_open,
                                   const std::vector<uint8_t>& free_open, const std::vector<uint8_t>& excluded,
                                   Progress* progress) {
  const Contributions& c = records.contributions();
  const std::vector<uint8_t> clipped = without_elements(free_open, excluded);
  const SensorValues clipped_values = records.exact(clipped);
  const LinearObjective local =
      without_elements(linearised_objective(objective, records, clipped, clipped_values.value), excluded);
  GeneticSettings within = ga;
  within.generations = std::max(1, ga.generations / 2);
  within.time_budget_s = ga.time_budget_s / 2.0;
  within.seed = ga.seed + 0x5EC0;
  const GeneticResult r =
      run_genetic(local, grid, {clipped, without_elements(linear_start_open, excluded)}, within, progress);
  if (progress) progress->throw_if_cancelled();
  ElementChoice best;
  std::vector<std::vector<uint8_t>> candidates = r.elite;
  candidates.push_back(clipped);
  for (const std::vector<uint8_t>& candidate : candidates) {
    const std::vector<uint8_t> open = without_elements(candidate, excluded);
    const SensorValues& exact = records.exact(open);
    const double f = exact_fitness(objective, grid, ga.shape, open, exact.value - c.closed.value);
    if (f < best.fitness) best.open = open, best.values = exact, best.fitness = f;
  }
  return best;
}

}  // namespace fenestra
