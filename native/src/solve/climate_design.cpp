#include "solve/climate_design.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <set>

#include "annual/annual_records.h"
#include "annual/annual_study.h"
#include "scene/scene.h"
#include "solve/climate_search.h"
#include "solve/linear_start.h"
#include "solve/nnls.h"
#include "solve/record_queries.h"
#include "util/progress.h"

namespace fenestra {
namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// Rounds about a best state (each a genetic run of a quarter of the generations), while they improve.
constexpr int kLinearisationRounds = 2;
// Mean illuminance levels of the NNLS starts, as multiples of the goals' illuminance: daylight
// autonomy at E needs a mean well above E (the year's light is skewed), so several are tried.
constexpr double kStartLevels[] = {0.75, 1.5, 3.0};

// The illuminance the goals name (0 when none does, e.g. ASE alone).
double goal_illuminance(const ClimateGoals& goals) {
  double level = 0.0;
  for (const ClimateGoal& g : goals.goals) switch (g.metric) {
      case ClimateMetric::SpatialDaylightAutonomy:
      case ClimateMetric::MeanIlluminance: level = std::max(level, g.illuminance_lux); break;
      case ClimateMetric::En17037: level = std::max(level, en17037_illuminances(g.level).target_lux); break;
      case ClimateMetric::UsefulDaylight: level = std::max(level, std::sqrt(std::max(1.0, g.lower_lux) * g.upper_lux)); break;
      case ClimateMetric::SunlightExposure: break;
    }
  return level;
}

// NNLS on the occupied-hour means (the records' values) toward a uniform mean `level` at the
// problem's sensors, rounded to 0/1 after the excess is moved to neighbours.
std::vector<uint8_t> mean_start(const Contributions& c, const std::vector<int>& rows, const ElementGrid& grid,
                                double level, const Progress* progress) {
  Eigen::MatrixXd A(rows.size(), c.E.cols());
  Eigen::VectorXd b(rows.size());
  for (size_t r = 0; r < rows.size(); ++r) {
    A.row(r) = c.E.row(rows[r]) / level;
    b[r] = (level - c.closed.value[rows[r]]) / level;
  }
  Eigen::VectorXd x = nnls(A, b, 0, 0.0, progress).x;
  redistribute_excess(grid, &x);
  return round_to_binary(x);
}

struct Ranked {
  std::vector<uint8_t> open;
  double fitness = std::numeric_limits<double>::infinity();
  double error = 0.0;
};

// The exact year of each candidate (path records), best first.
std::vector<Ranked> rank_exactly(RecordQueries& records, const ClimateProblem& p, const ElementGrid& grid,
                                 const ShapeWeights& shape, const std::vector<std::vector<uint8_t>>& candidates,
                                 const Progress* progress) {
  if (progress) progress->throw_if_cancelled();
  std::vector<Ranked> out;
  std::set<std::vector<uint8_t>> seen;
  for (const auto& open : candidates) {
    if (!seen.insert(open).second) continue;
    Ranked r;
    r.open = open;
    r.error = climate_year(records, p, open).error;
    r.fitness = r.error + shape_penalty(shape, shape_counts(grid, open));
    out.push_back(std::move(r));
  }
  std::stable_sort(out.begin(), out.end(), [](const Ranked& a, const Ranked& b) { return a.fitness < b.fitness; });
  return out;
}

}  // namespace

ClimateYear climate_year(RecordQueries& records, const ClimateProblem& p, const std::vector<uint8_t>& open) {
  ClimateYear out;
  out.tally = records.climate_tally(p, open);
  double area = 0.0;
  for (size_t k = 0; k < open.size(); ++k)
    if (open[k]) area += p.objective->element_area(static_cast<int>(k));
  out.error = p.objective->error(out.tally, area);
  return out;
}

std::vector<ClimateFigure> climate_figures(const ClimateProblem& p, const Eigen::MatrixXf& total,
                                           const Eigen::MatrixXf& direct) {
  const Eigen::Index rows = static_cast<Eigen::Index>(p.rows.size()), columns = static_cast<Eigen::Index>(p.columns.hour.size());
  HourlyMatrix t(rows, columns), d(direct.size() ? rows : 0, direct.size() ? columns : 0);
  for (Eigen::Index r = 0; r < rows; ++r)
    for (Eigen::Index j = 0; j < columns; ++j) {
      t(r, j) = total(p.rows[r], p.columns.hour[j]);
      if (d.size()) d(r, j) = direct(p.rows[r], p.columns.hour[j]);
    }
  return p.objective->figures(t, d);
}

ClimateDesign design_for_climate(RecordQueries& records, const ClimateProblem& p, const ElementGrid& grid,
                                 const GeneticSettings& ga, const std::vector<std::vector<uint8_t>>& seeds,
                                 const std::vector<uint8_t>& excluded, Progress* progress) {
  // Excluded elements change nothing in the model (its shards drop their flips) and leave every state.
  auto within = [&](std::vector<std::vector<uint8_t>> states) {
    for (auto& s : states)
      for (size_t k = 0; k < excluded.size(); ++k)
        if (excluded[k]) s[k] = 0;
    return states;
  };
  const Contributions& c = records.contributions();
  const size_t n = c.element_count();
  ClimateDesign out;
  auto t = Clock::now();
  if (progress) progress->start("solving: the year's hourly model", 1);
  const std::vector<uint8_t> closed(n, 0), all_open(n, 1);
  std::unique_ptr<ClimateModel> model = records.climate_model(p, closed, excluded);
  out.model_bytes = model->model_bytes();
  out.all_open_figures = p.objective->figures(records.climate_tally(p, within({all_open})[0]));
  out.seconds_model += since(t);
  out.stages.push_back({"climate model", out.seconds_model, stop_reason::kDone});

  const auto search_start = Clock::now();
  std::vector<std::vector<uint8_t>> starts = {closed, all_open};
  const double level = goal_illuminance(p.objective->goals());
  if (level > 0.0)
    for (double k : kStartLevels) starts.push_back(mean_start(c, p.rows, grid, k * level, progress));
  starts.insert(starts.end(), seeds.begin(), seeds.end());
  starts = within(std::move(starts));

  t = Clock::now();
  const GeneticResult first = run_climate_genetic(*model, *p.objective, grid, starts, ga, progress);
  out.history = first.history;
  out.generations = first.generations;
  std::vector<std::vector<uint8_t>> pool = within(first.elite);
  pool.insert(pool.end(), starts.begin(), starts.end());
  std::vector<Ranked> ranked = rank_exactly(records, p, grid, ga.shape, pool, progress);
  out.seconds_search += since(t);
  out.stages.push_back({"climate search", since(search_start), genetic_stop_reason(first)});
  // Successive linearisation: the model about the best state is exact for it and its single
  // flips, where the model about "all closed" misses what open elements do together.
  const auto rounds_start = Clock::now();
  const char* rounds_stop = ga.generations > 0 ? stop_reason::kRoundLimit : stop_reason::kNoGenerations;
  for (int round = 0; round < kLinearisationRounds && ga.generations > 0; ++round) {
    t = Clock::now();
    if (progress) progress->start("solving: the hourly model about the best state", 1);
    model.reset();  // one model at a time in the shards
    model = records.climate_model(p, ranked.front().open, excluded);
    out.model_bytes = std::max(out.model_bytes, model->model_bytes());
    out.seconds_model += since(t);
    t = Clock::now();
    GeneticSettings local = ga;
    local.generations = std::max(1, ga.generations / 4);
    local.time_budget_s = ga.time_budget_s / 4.0;
    local.seed = ga.seed + 1 + round;
    const GeneticResult refined = run_climate_genetic(*model, *p.objective, grid, {ranked.front().open}, local, progress);
    out.generations += refined.generations;
    std::vector<std::vector<uint8_t>> again = within(refined.elite);
    for (const Ranked& r : ranked) again.push_back(r.open);
    const double before = ranked.front().fitness;
    ranked = rank_exactly(records, p, grid, ga.shape, again, progress);
    out.seconds_search += since(t);
    if (!(ranked.front().fitness < before * (1.0 - 1e-9))) {
      rounds_stop = stop_reason::kNoImprovement;
      break;
    }
    ++out.linearisations;
  }
  out.stages.push_back({"climate linearisation", since(rounds_start), rounds_stop});
  if (progress) progress->throw_if_cancelled();
  out.open = ranked.front().open;
  out.error = ranked.front().error;
  for (const Ranked& r : ranked) out.candidates.push_back(r.open);
  model.reset();
  out.figures = p.objective->figures(records.climate_tally(p, out.open));
  return out;
}

}  // namespace fenestra
