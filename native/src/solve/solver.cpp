#include "solve/solver.h"

#include <algorithm>
#include <chrono>
#include <functional>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>

#include "annual/annual_contributions.h"
#include "annual/annual_cut_study.h"
#include "annual/annual_study.h"
#include "scene/sky_figures.h"
#include "solve/catalogue_snap.h"
#include "solve/climate_design.h"
#include "solve/coarse_grid.h"
#include "solve/compensation.h"
#include "solve/constraint_costs.h"
#include "solve/edge_refinement.h"
#include "solve/least_glazing.h"
#include "solve/linear_start.h"
#include "solve/nnls.h"
#include "solve/prediction_check.h"
#include "solve/record_queries.h"
#include "solve/refine_openings.h"
#include "solve/thick_wall_edges.h"
#include "solve/tradeoffs.h"
#include "trace/contributions_origin.h"
#include "trace/evaluate.h"
#include "trace/flip_effects.h"
#include "util/number_text.h"

namespace fenestra {

OpeningConstraints measured_constraints(const Scene& scene);  // below

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// A daylight sky without light (the sun never up) makes every value 0: no goal can be met.
void refuse_dark_sky(const Scene& scene) {
  const std::string dark = dark_sky_warning(scene);
  if (!dark.empty())
    throw std::invalid_argument("scene '" + scene.source + "': sky: " + dark +
                                "; the goals cannot be met: choose a date and time interval with daylight");
}

// The linear model net of the all-closed values, weighted so that its error is a relative
// mean-squared error (sum w (p - g)^2 / sum w g^2).
LinearObjective linear_objective(const Contributions& c, const SolverGoals& goals, double bound_weight) {
  LinearObjective o;
  o.E = c.E;
  const Eigen::Index n = c.E.rows();
  double norm = 0.0;
  for (Eigen::Index i = 0; i < n; ++i)
    if (goals.weight[i] > 0.0) norm += goals.weight[i] * goals.target[i] * goals.target[i];
  if (!(norm > 0.0)) norm = goals.weight.sum() * std::max(1e-30, c.all_open.value.squaredNorm() / n);  // all goals 0
  o.target = Eigen::VectorXd::Zero(n);
  o.weight = Eigen::VectorXd::Zero(n);
  o.lower = Eigen::VectorXd::Constant(n, -std::numeric_limits<double>::infinity());
  o.upper = Eigen::VectorXd::Constant(n, std::numeric_limits<double>::infinity());
  for (Eigen::Index i = 0; i < n; ++i) {
    if (!(goals.weight[i] > 0.0)) continue;
    o.target[i] = goals.target[i] - c.closed.value[i];
    o.weight[i] = goals.weight[i] / norm;
    o.lower[i] = goals.lower[i] - c.closed.value[i];
    o.upper[i] = goals.upper[i] - c.closed.value[i];
  }
  o.bound_weight = bound_weight;
  return o;
}

// Whether the openings `refined` meet the goals better than `start` when both are really cut.
bool refined_edges_verified_better(RecordQueries& records, const std::vector<PanelRectangle>& start,
                                   const std::vector<PanelRectangle>& refined, const SolverGoals& goals) {
  auto verified_error = [&](const std::vector<PanelRectangle>& openings) {
    std::vector<OpeningInput> cutters(openings.begin(), openings.end());
    return goal_error(goals, records.cut(cutters, 0).value).relative_rms;
  };
  return verified_error(refined) < verified_error(start);
}

struct LinearStart {
  std::vector<uint8_t> open;
  double relative_rms = 0.0;  // of the continuous solution
  int iterations = 0;
};

// Stage 1: NNLS on the weighted system, excess over 1 to the neighbours, rounded.
LinearStart linear_start(const LinearObjective& o, const ElementGrid& grid, const Progress* progress) {
  const Eigen::VectorXd sqrt_w = o.weight.cwiseSqrt();
  const Eigen::MatrixXd A = sqrt_w.asDiagonal() * o.E;
  const Eigen::VectorXd b = sqrt_w.cwiseProduct(o.target);
  const NnlsResult r = nnls(A, b, 0, 0.0, progress);
  Eigen::VectorXd x = r.x;
  redistribute_excess(grid, &x);
  LinearStart s;
  s.open = round_to_binary(x);
  s.relative_rms = r.residual_norm;  // weights make it relative
  s.iterations = r.iterations;
  return s;
}

ShapeWeights shape_of(const SolverSettings& s) {
  ShapeWeights w;
  w.isolated = s.isolated_weight;
  w.boundary = s.boundary_weight;
  w.regions = s.regions_weight;
  return w;
}

// Fitness with the error part taken from exact predictions (the shape part as the GA counts it).
double exact_fitness(const LinearObjective& o, const ElementGrid& grid, const ShapeWeights& shape,
                     const std::vector<uint8_t>& open, const Eigen::VectorXd& predicted_net) {
  return prediction_error(o, predicted_net) + shape_penalty(shape, shape_counts(grid, open));
}

// Rounds of successive linearisation after the first genetic run (each stops early when it gains nothing).
constexpr int kLinearisationRounds = 4;

// The objective with the model V(o) = V(S) + sum over the elements o flips from S of their exact
// flip effect D(., k): a constant base plus columns +D(., k) (k closed in S) or -D(., k) (k open).
LinearObjective linearised_objective(const LinearObjective& objective, RecordQueries& records,
                                     const std::vector<uint8_t>& about, const Eigen::VectorXd& about_values) {
  const Contributions& c = records.contributions();
  const Eigen::MatrixXd D = records.flip_effects(about);
  LinearObjective local = objective;
  Eigen::VectorXd base = about_values;
  for (size_t k = 0; k < about.size(); ++k) {
    if (about[k]) {
      base += D.col(k);
      local.E.col(k) = -D.col(k);
    } else {
      local.E.col(k) = D.col(k);
    }
  }
  const Eigen::VectorXd shift = base - c.closed.value;  // the objective's targets are net of the closed values
  for (Eigen::Index i = 0; i < shift.size(); ++i)
    if (local.weight[i] > 0.0) {
      local.target[i] -= shift[i];
      local.lower[i] -= shift[i];
      local.upper[i] -= shift[i];
    }
  return local;
}

// The objective with no light from the elements flagged in `excluded` (their columns zeroed).
LinearObjective without_elements(LinearObjective o, const std::vector<uint8_t>& excluded) {
  for (size_t k = 0; k < excluded.size(); ++k)
    if (excluded[k]) o.E.col(static_cast<Eigen::Index>(k)).setZero();
  return o;
}

std::vector<uint8_t> without_elements(std::vector<uint8_t> open, const std::vector<uint8_t>& excluded) {
  for (size_t k = 0; k < open.size(); ++k)
    if (excluded[k]) open[k] = 0;
  return open;
}

bool opens_any(const std::vector<uint8_t>& open, const std::vector<uint8_t>& flagged) {
  for (size_t k = 0; k < open.size(); ++k)
    if (open[k] && flagged[k]) return true;
  return false;
}

// A set of open elements with its exact values and fitness.
struct ElementChoice {
  std::vector<uint8_t> open;
  SensorValues values;
  double fitness = std::numeric_limits<double>::infinity();
};

// The element search again with the elements flagged in `excluded` kept closed: a genetic run
// (half the generations) on the exact linear model about the free answer less those elements,
// seeded with it and with the linear start without them; the exact evaluation picks among its best.
ElementChoice search_within_bounds(const LinearObjective& objective, const Contributions& c, const ElementGrid& grid,
                                   const ShapeWeights& shape, const GeneticSettings& ga, RecordQueries& records,
                                   const std::vector<uint8_t>& linear_start_open, const std::vector<uint8_t>& free_open,
                                   const std::vector<uint8_t>& excluded, Progress* progress) {
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
    const double f = exact_fitness(objective, grid, shape, open, exact.value - c.closed.value);
    if (f < best.fitness) best.open = open, best.values = exact, best.fitness = f;
  }
  return best;
}

// What the element stage hands the constraints stage: the answer in elements, its exact values and
// fitness, and the start the second search within the constraints begins from.
struct ElementStage {
  std::vector<uint8_t> open, start_open;
  SensorValues values;
  double fitness = std::numeric_limits<double>::infinity();
};

// Stages 1 and 2 on per-sensor goals: the linear start (and coarse-to-fine starts), the genetic
// algorithm, successive linearisation, and the exact choice among the best states.
ElementStage linear_element_stage(const Scene& scene, const Contributions& c, const LinearObjective& objective,
                                  const ElementGrid& grid, const ShapeWeights& shape, const GeneticSettings& ga,
                                  RecordQueries& records, SolveResult& out, Progress* progress) {
  const SolverSettings& settings = scene.solver;
  ElementStage stage;
  // Stage 1 on the fine grid, and coarse-to-fine starts (4a, then 2a) when the grid is large enough.
  if (progress) progress->start("solving: linear start", 1);
  auto t = Clock::now();
  const LinearStart fine_start = linear_start(objective, grid, progress);
  out.nnls_relative_rms = fine_start.relative_rms;
  out.nnls_iterations = fine_start.iterations;
  std::vector<std::vector<uint8_t>> seeds = {fine_start.open};
  double coarse_seconds = 0.0;
  if (settings.coarse_to_fine) {
    std::vector<uint8_t> carried;  // the previous (coarser) level's answer, on the fine grid
    for (int factor : {4, 2}) {
      const CoarseGrid coarse = coarsen(grid, factor);
      if (coarse.grid.size() < 4 || coarse.grid.size() * 2 > grid.size()) continue;
      const auto level_start = Clock::now();
      LinearObjective level = objective;
      level.E = coarse.columns(objective.E);
      std::vector<std::vector<uint8_t>> level_seeds = {linear_start(level, coarse.grid, progress).open};
      if (!carried.empty()) {  // the coarser answer, as well as it fits this grid
        std::vector<uint8_t> mapped(coarse.grid.size(), 0);
        for (size_t k = 0; k < carried.size(); ++k) mapped[coarse.coarse_of[k]] |= carried[k];
        level_seeds.push_back(mapped);
      }
      GeneticSettings level_ga = ga;
      level_ga.generations = std::max(1, ga.generations / 2);
      level_ga.time_budget_s = 0.0;
      const GeneticResult r = run_genetic(level, coarse.grid, level_seeds, level_ga, progress);
      carried = coarse.expand(r.best);
      seeds.push_back(carried);
      out.coarse_factors.push_back(factor);
      coarse_seconds += since(level_start);
      if (progress) progress->throw_if_cancelled();
    }
  }
  out.timings.push_back({"linear start", since(t) - coarse_seconds});
  if (coarse_seconds > 0.0) out.timings.push_back({"coarse grids", coarse_seconds});

  // Stage 2 on the fine grid.
  if (progress) progress->start("solving: genetic algorithm", 1);
  t = Clock::now();
  const GeneticResult result = run_genetic(objective, grid, seeds, ga, progress);
  out.history = result.history;
  out.generations = result.generations;
  if (progress) progress->throw_if_cancelled();
  // The linear model (each element's light with the others closed) misses what elements do together:
  // light reflected off opened elements (1-3 % on thin walls), and in thick walls the light that
  // passes obliquely through neighbouring open elements and the reveals of closed ones (tens of
  // percent). Successive linearisation: the exact linear model about the best state so far (each
  // element's flip, from the path records), a shorter genetic run from there, the exact choice among
  // its best states; repeated while the exact fitness improves.
  std::vector<std::vector<uint8_t>> candidates = result.elite;
  if (candidates.empty()) candidates.push_back(result.best);
  if (ga.generations > 0) {
    std::vector<uint8_t> about = result.best;
    SensorValues about_values = records.exact(about);
    double about_fitness = exact_fitness(objective, grid, shape, about, about_values.value - c.closed.value);
    for (int round = 0; round < kLinearisationRounds; ++round) {
      const LinearObjective local = linearised_objective(objective, records, about, about_values.value);
      GeneticSettings second = ga;
      second.generations = std::max(1, ga.generations / 4);
      second.seed = ga.seed + 1 + round;
      std::vector<std::vector<uint8_t>> second_seeds = {about};
      second_seeds.insert(second_seeds.end(), seeds.begin(), seeds.end());
      const GeneticResult refined = run_genetic(local, grid, second_seeds, second, progress);
      out.generations += refined.generations;
      candidates.insert(candidates.end(), refined.elite.begin(), refined.elite.end());
      bool improved = false;
      for (const auto& open : refined.elite) {
        const SensorValues& exact = records.exact(open);
        const double f = exact_fitness(objective, grid, shape, open, exact.value - c.closed.value);
        if (f < about_fitness * (1.0 - 1e-6)) about = open, about_values = exact, about_fitness = f, improved = true;
      }
      if (!improved) break;
    }
  }
  out.timings.push_back({"genetic", since(t)});
  if (progress) progress->throw_if_cancelled();

  // The final choice among the best states uses the exact evaluation from the path records.
  if (progress) progress->start("solving: exact evaluation", 1);
  t = Clock::now();
  candidates.push_back(fine_start.open);
  double& best = stage.fitness;
  SensorValues& chosen = stage.values;
  for (const auto& open : candidates) {
    const SensorValues& exact = records.exact(open);
    const double f = exact_fitness(objective, grid, shape, open, exact.value - c.closed.value);
    if (f < best) {
      best = f;
      out.open = open;
      chosen = exact;
    }
  }
  out.start_error = goal_error(out.goals, records.exact(fine_start.open).value);
  out.unconstrained_open = out.open;
  out.unconstrained_openings = merge_into_rectangles(scene.domain, out.open);
  out.unconstrained_error = goal_error(out.goals, chosen.value);
  out.timings.push_back({"exact evaluation", since(t)});
  stage.start_open = fine_start.open;
  stage.open = out.open;
  return stage;
}


bool has_thick_panel(const OpeningDomain& domain) {
  for (const Panel& p : domain.panels())
    if (p.thickness > 0.0f) return true;
  return false;
}

// "41.0 %" for fractions, "512 lx" for the annual mean.
std::string figure_text(const ClimateGoal& goal, double x) {
  char text[48];
  if (goal.unit() == "lux") std::snprintf(text, sizeof text, "%.0f lx", x);
  else std::snprintf(text, sizeof text, "%.1f %%", 100.0 * x);
  return text;
}

// Each goal the final openings miss, with what they reach and, when even every element open
// falls short, what the domain can give at most: the best compromise, said as such.
std::vector<std::string> unmet_climate_goals(const ClimateGoals& goals, const std::vector<ClimateFigure>& achieved,
                                             const std::vector<ClimateFigure>& elements,
                                             const std::vector<ClimateFigure>& all_open) {
  std::vector<std::string> out;
  for (size_t g = 0; g < goals.goals.size() && g < achieved.size(); ++g) {
    const ClimateGoal& goal = goals.goals[g];
    if (figure_meets(goal, achieved[g].achieved)) continue;
    std::string line = goal.describe() + " is not met: the openings reach " + figure_text(goal, achieved[g].achieved);
    if (g < all_open.size() && goal.sense() == GoalSense::AtLeast && !figure_meets(goal, all_open[g].achieved))
      line += "; even every element of the opening domain open reaches only " + figure_text(goal, all_open[g].achieved) +
              ": the goal cannot be met here";
    else if (g < elements.size() && figure_meets(goal, elements[g].achieved))
      line += "; the open elements before the constraints reached " + figure_text(goal, elements[g].achieved) +
              ": the opening constraints cost it";
    else
      line += " (the best compromise found with the other goals)";
    out.push_back(line);
  }
  return out;
}

// Whether a goal's figure from the path records and with real cutters differ beyond the noise: sDA
// by more than its noise (sda_noise) and kHeadlineFractionGap, another fraction by more than
// kHeadlineFractionGap, an annual mean (lux) by more than 3 combined standard errors of the goal's
// sensors' mean.
// An sDA goal's noise: the share of its sensors whose DA, in either year, lies within its noise of
// the time fraction (either side may be right for them). A sensor's DA is uncertain by the share of
// occupied hours whose value lies within 3 combined relative standard errors r of the threshold
// (the coefficients' errors move every hour by about r).
double sda_noise(const ClimateGoal& goal, const AnnualStudy& a, const AnnualStudy& b) {
  int uncertain = 0;
  for (int i : goal.sensors) {
    const double mean = std::max(1e-9, a.occupied_mean.value[i]);
    const double r = std::hypot(a.occupied_mean.standard_error[i], b.occupied_mean.standard_error[i]) / mean;
    int occupied = 0, near = 0, over_a = 0, over_b = 0;
    for (size_t h = 0; h < a.occupied.size(); ++h) {
      if (!a.occupied[h]) continue;
      const double e = a.illuminance.total(i, static_cast<Eigen::Index>(h));
      ++occupied;
      near += std::abs(e - goal.illuminance_lux) <= 3.0 * r * e;
      over_a += e >= goal.illuminance_lux;
      over_b += b.illuminance.total(i, static_cast<Eigen::Index>(h)) >= goal.illuminance_lux;
    }
    if (occupied == 0) continue;
    const double band = (near + 1.0) / occupied;
    uncertain += std::abs(static_cast<double>(over_a) / occupied - goal.time_fraction) <= band ||
                 std::abs(static_cast<double>(over_b) / occupied - goal.time_fraction) <= band;
  }
  return static_cast<double>(uncertain) / static_cast<double>(std::max<size_t>(1, goal.sensors.size()));
}

bool beyond_noise(const ClimateGoal& goal, double records, double cut, const AnnualStudy& records_year,
                  const AnnualStudy& cut_year) {
  if (goal.metric == ClimateMetric::SpatialDaylightAutonomy)
    return std::abs(records - cut) > std::max(kHeadlineFractionGap, sda_noise(goal, records_year, cut_year)) + 1e-9;
  if (goal.unit() != "lux") return std::abs(records - cut) > kHeadlineFractionGap;
  double variance = 0.0;
  for (int i : goal.sensors)
    variance += std::pow(records_year.occupied_mean.standard_error[i], 2) + std::pow(cut_year.occupied_mean.standard_error[i], 2);
  const double n = static_cast<double>(std::max<size_t>(1, goal.sensors.size()));
  return std::abs(records - cut) > 3.0 * std::sqrt(variance) / n;
}

// The final openings' year and each climate goal's figure: from the path records, and with real
// cutters when verification is on.
void report_climate(const Scene& scene, RecordQueries& records, const ClimateProblem& problem,
                    const std::vector<PanelRectangle>& openings, bool verify, int verify_paths, SolveResult* out,
                    Progress* progress) {
  ClimateOutcome& climate = out->climate;
  for (const PanelRectangle& r : openings) climate.glazing_area_m2 += (r.u1 - r.u0) * (r.v1 - r.v0);
  for (const Element& e : scene.domain.elements()) climate.domain_area_m2 += static_cast<double>(e.width()) * e.height();
  try {
    auto study = std::make_shared<AnnualStudy>(records.annual_study(openings));
    climate.achieved = climate_figures(problem, study->illuminance.total, study->illuminance.direct);
    climate.study = std::move(study);
  } catch (const std::invalid_argument& e) {
    out->warnings.push_back(std::string("climate goals: the path records cannot give the final openings' year (") +
                            e.what() + ")");
  }
  if (verify) {
    const std::vector<OpeningInput> cutters(openings.begin(), openings.end());
    auto cut = std::make_shared<AnnualStudy>(records.annual_cut(cutters, verify_paths));
    climate.verified = climate_figures(problem, cut->illuminance.total, cut->illuminance.direct);
    climate.verified_study = std::move(cut);
  }
  std::string apart;  // the goals whose two figures disagree beyond the noise
  for (size_t g = 0; g < climate.verified.size() && g < climate.achieved.size(); ++g) {
    const ClimateGoal& goal = scene.sensors.climate_goals.goals[g];
    const double records = climate.achieved[g].achieved, cut = climate.verified[g].achieved;
    if (beyond_noise(goal, records, cut, *climate.study, *climate.verified_study))
      apart += std::string(apart.empty() ? "" : ", ") + goal.describe() + ": " + figure_text(goal, records) +
               " from the path records, " + figure_text(goal, cut) + " with real cutters";
    else if (figure_meets(goal, records) && !figure_meets(goal, cut))
      out->warnings.push_back("climate goals: " + goal.describe() + " is met from the path records (" +
                              figure_text(goal, records) + ") but not with real cutters (" + figure_text(goal, cut) +
                              "): a result at the edge of the goal; more paths per sensor tell which is right");
  }
  if (!apart.empty()) {
    climate.headline_cutters = true;
    out->warnings.push_back("climate goals: the year from the path records and the year with real cutters disagree "
                            "beyond the noise (" + apart + "): the figures shown are the real cutters'");
  }
  const std::vector<ClimateFigure>& judged = climate.headline();
  climate.unmet =
      unmet_climate_goals(scene.sensors.climate_goals, judged, climate.element_figures, climate.all_open_figures);
  for (const std::string& u : climate.unmet) out->warnings.push_back("climate goals: " + u);
}

// Gains on the followed light when openings within the constraints miss a climate goal the
// element answer met.
constexpr double kClimateFollowGains[] = {1.15, 1.35, 1.6};

// The year of a set of open elements scored by the climate objective, and whether every goal is met.
struct ClimateScore {
  double error = 0.0;
  bool all_met = false;
};
ClimateScore climate_error_of(RecordQueries& records, const ClimateProblem& problem, const std::vector<uint8_t>& open) {
  const HourlyFlipModel year = records.hourly_model(open, problem.rows, problem.columns, false);
  double area = 0.0;
  for (size_t k = 0; k < open.size(); ++k)
    if (open[k]) area += problem.objective->element_area(static_cast<int>(k));
  ClimateScore score;
  score.error = problem.objective->error(year.total, year.direct, area);
  const std::vector<ClimateFigure> figures = problem.objective->figures(year.total, year.direct);
  score.all_met = true;
  for (size_t g = 0; g < figures.size(); ++g)
    score.all_met = score.all_met && figure_meets(problem.objective->goals().goals[g], figures[g].achieved);
  return score;
}

// Per sensor, whether the scene gives it a goal of its own (those are not raised).
std::vector<uint8_t> scene_goal_weight(const Scene& scene, const Contributions& c) {
  const SolverGoals own = resolve_goals(scene, c);
  std::vector<uint8_t> has(own.weight.size());
  for (Eigen::Index i = 0; i < own.weight.size(); ++i) has[i] = own.weight[i] > 0.0;
  return has;
}

SolverGoals raised_goals(SolverGoals goals, const std::vector<int>& rows, const std::vector<uint8_t>& own, double gain) {
  for (int i : rows)
    if (!own[i]) goals.target[i] *= gain;
  return goals;
}

// A trade-off's climate figures: the answer's, or its openings' year from the path records.
std::vector<ClimateFigure> tradeoff_climate(RecordQueries& records, const ClimateProblem& problem,
                                            const TradeoffResult& entry, const SolveResult& out) {
  if (entry.answer) return out.climate.headline();
  std::vector<PanelRectangle> rects;
  for (const OpeningRectangle& o : entry.openings) rects.push_back(o.parameter);
  try {
    const AnnualStudy year = records.annual_study(rects);
    return climate_figures(problem, year.illuminance.total, year.illuminance.direct);
  } catch (const std::invalid_argument&) {
    return {};  // edges off the grid lines of a thick wall: the records cannot tell
  }
}

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

// Least glazing: the entry of the trade-off list (the answer included) with the least glass among
// those whose year meets every climate goal, from the path records and, with verification on,
// with real cutters too. Fills each entry's `climate` (the answer's from `answer_figures`).
// Returns its index, or -1 when none meets the goals.
int least_glazing_entry(const Scene& scene, RecordQueries& records, const ClimateProblem& problem,
                        const std::vector<ClimateFigure>& answer_figures, bool verify, int verify_paths,
                        std::vector<TradeoffResult>* tradeoffs) {
  const ClimateGoals& goals = scene.sensors.climate_goals;
  std::vector<GlazingCandidate> candidates;
  for (TradeoffResult& entry : *tradeoffs) {
    entry.climate = entry.answer ? answer_figures : tradeoff_climate(records, problem, entry, SolveResult());
    candidates.push_back({glazing_area(entry.openings), all_climate_goals_met(goals, entry.climate)});
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

// The per-sensor goals the constraints stage follows after a climate search: each sensor the
// climate goals look at takes the answer's mean illuminance of the occupied hours as its goal
// (sensors with a goal of their own keep it), so that openings within the constraints give the
// light that met the climate goals.
SolverGoals goals_following(SolverGoals goals, const std::vector<int>& rows, const SensorValues& answer) {
  for (int i : rows) {
    if (goals.weight[i] > 0.0) continue;
    goals.target[i] = answer.value[i];
    goals.weight[i] = 1.0;
  }
  return goals;
}

// Stages 1 and 2 on climate goals (solve/climate_design.h), then the goals the constraints stage
// follows (goals_following) and its objective.
ElementStage climate_element_stage(const Scene& scene, const Contributions& c, const ElementGrid& grid,
                                   const ShapeWeights& shape, const GeneticSettings& ga, RecordQueries& records,
                                   LinearObjective* objective, SolveResult& out,
                                   std::optional<ClimateProblem>* problem, Progress* progress) {
  // Elements no admissible opening can cover stay closed: the answer must survive the constraints.
  const std::vector<uint8_t> excluded =
      elements_out_of_bounds(scene.domain, grid_search_constraints(scene.domain, measured_constraints(scene)));
  problem->emplace(climate_problem(scene, records.annual().get(), out.goals));
  std::vector<std::vector<uint8_t>> seeds;
  if (out.goals.count() > 0) seeds.push_back(linear_start(*objective, grid, progress).open);
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

  ElementStage stage;
  stage.open = stage.start_open = design.open;
  stage.values = records.exact(design.open);
  out.goals = goals_following(out.goals, (*problem)->rows, stage.values);
  *objective = linear_objective(c, out.goals, scene.solver.bound_weight);
  stage.fitness = exact_fitness(*objective, grid, shape, stage.open, stage.values.value - c.closed.value);
  out.open = design.open;
  out.start_error = goal_error(out.goals, stage.values.value);
  out.unconstrained_open = out.open;
  out.unconstrained_openings = merge_into_rectangles(scene.domain, out.open);
  out.unconstrained_error = out.start_error;
  return stage;
}

}  // namespace

// The constraints as the solver applies them: sills and heads measured from each panel's faces.
OpeningConstraints measured_constraints(const Scene& scene) {
  OpeningConstraints constraints = scene.solver.constraints;
  constraints.panel_base_z = panel_base_heights(scene.domain, scene.mesh);
  constraints.panel_top_z = panel_top_heights(scene.domain, scene.mesh);
  return constraints;
}

// Every constraint: each opening's, the counts, and the facades' composition.
std::vector<std::string> all_violations(const OpeningDomain& domain, const std::vector<PanelRectangle>& openings,
                                        const OpeningConstraints& constraints) {
  std::vector<std::string> out = constraint_violations(domain, openings, constraints);
  for (const std::string& v : composition_violations(domain, constraints, openings)) out.push_back(v);
  return out;
}

std::vector<std::string> solved_constraint_violations(const Scene& scene, const std::vector<PanelRectangle>& openings) {
  return all_violations(scene.domain, openings, measured_constraints(scene));
}

bool composes(const OpeningDomain& domain, const OpeningConstraints& constraints) {
  for (size_t p = 0; p < domain.panels().size(); ++p)
    if (constraints.for_panel(static_cast<int>(p)).composes()) return true;
  return false;
}

SolveResult solve_openings(const Scene& scene, const Contributions& c, Progress* progress) {
  LocalRecordQueries records(scene, c, scene.domain, progress);
  return solve_openings(scene, records, progress);
}

SolveResult solve_openings(const Scene& scene, RecordQueries& records, Progress* progress) {
  const Contributions& c = records.contributions();
  check_contributions_match(scene, c, "solve");
  refuse_dark_sky(scene);
  const auto start = Clock::now();
  SolveResult out;
  out.dropped = c.dropped;
  out.goals = resolve_goals(scene, c);
  const bool climate = !scene.sensors.climate_goals.empty();
  SolverSettings settings = scene.solver;
  // In thick walls the records give a year only for edges on the grid lines: climate answers keep them there.
  if (climate && has_thick_panel(scene.domain)) settings.refine_edges = false;
  LinearObjective objective = linear_objective(c, out.goals, settings.bound_weight);
  std::optional<ClimateProblem> climate_problem_of;
  const ElementGrid grid = ElementGrid::from_domain(scene.domain);
  const ShapeWeights shape = shape_of(settings);
  GeneticSettings ga;
  ga.population = settings.population;
  ga.generations = settings.generations;
  ga.seed = settings.seed;
  ga.time_budget_s = settings.time_budget_s;
  ga.elite = settings.elite;
  ga.shape = shape;

  auto t = Clock::now();
  const ElementStage stage = climate ? climate_element_stage(scene, c, grid, shape, ga, records, &objective, out, &climate_problem_of, progress)
                                     : linear_element_stage(scene, c, objective, grid, shape, ga, records, out, progress);
  double best = stage.fitness;
  SensorValues chosen = stage.values;

  // Architectural refinement: regions become admissible rectangles (the paper's final step),
  // then a local search over whole openings; the exact evaluation has the last word.
  if (progress) progress->start("solving: openings within the constraints", 1);
  t = Clock::now();
  const OpeningConstraints constraints = measured_constraints(scene);
  auto exact_of = [&](const std::vector<GridRectangle>& rects, SensorValues* values) {
    const std::vector<uint8_t> open = rectangles_mask(scene.domain, rects);
    *values = records.exact(open);
    return exact_fitness(objective, grid, shape, open, values->value - c.closed.value);
  };
  // With a catalogue, the grid's openings keep near its sizes; they take them exactly below.
  const OpeningConstraints grid_constraints = grid_search_constraints(scene.domain, constraints);
  // Openings within the constraints from a set of open elements, and the exact linear model about
  // them (the local search's, then the edge search's screen).
  struct Constrained {
    std::vector<GridRectangle> rects;
    SensorValues values;
    double fitness = 0.0;
    GoalError refined_error;
    std::optional<LinearObjective> about;
  };
  auto constrain = [&](const std::vector<uint8_t>& open, const SensorValues& open_values,
                       const OpeningConstraints& grid_constraints) {
    Constrained k;
    // Rectangles are scored by the exact linear model about the state (the elements' joint light).
    const LinearObjective about_open = linearised_objective(objective, records, open, open_values.value);
    k.rects = refine_openings(scene.domain, open, about_open, grid_constraints, progress);
    k.fitness = exact_of(k.rects, &k.values);
    k.refined_error = goal_error(out.goals, k.values.value);
    if (settings.improve_iterations <= 0) return k;
    if (progress) progress->start("solving: local search over openings", 1);
    // Each round searches the exact linear model about the current openings, and is kept only if
    // the exact evaluation agrees; the next round linearises about its answer.
    auto linearise = [&] {
      k.about = linearised_objective(objective, records, rectangles_mask(scene.domain, k.rects), k.values.value);
    };
    linearise();
    for (int round = 0; round < kLinearisationRounds; ++round) {
      const std::vector<GridRectangle> improved = improve_rectangles(
          scene.domain, k.rects, *k.about, grid_constraints, settings.seed + round, settings.improve_iterations,
          progress);
      SensorValues improved_values;
      const double f = exact_of(improved, &improved_values);
      if (!(f < k.fitness * (1.0 - 1e-6))) break;
      k.fitness = f;
      k.rects = improved;
      k.values = improved_values;
      linearise();
    }
    return k;
  };
  const SensorValues free_values = chosen;
  Constrained kept = constrain(out.open, chosen, grid_constraints);
  // When the free answer takes light from elements no admissible opening can cover (margins,
  // rows below the sill or above the head limits), the openings made from it can land far from
  // the best: a second start searches the elements again without those, and the better is kept.
  const std::vector<uint8_t> out_of_bounds = elements_out_of_bounds(scene.domain, grid_constraints);
  if (opens_any(out.open, out_of_bounds)) {
    if (progress) progress->start("solving: elements within the constraints", 1);
    const ElementChoice within = search_within_bounds(objective, c, grid, shape, ga, records, stage.start_open,
                                                      out.open, out_of_bounds, progress);
    Constrained second = constrain(within.open, within.values, grid_constraints);
    out.second_start = true;
    if (second.fitness < kept.fitness) kept = std::move(second), out.second_start_kept = true;
  }
  // Climate goals: openings that follow the element answer's light can still fall short of a goal
  // it met (a sensor just over its threshold drops below). The constraints stage again with the
  // followed light raised, kept when the year of its openings is better.
  if (climate) {
    if (progress) progress->start("solving: openings for the climate goals", 1);
    const ClimateProblem& problem = *climate_problem_of;
    auto climate_score = [&](const std::vector<GridRectangle>& rects) {
      return climate_error_of(records, problem, rectangles_mask(scene.domain, rects));
    };
    ClimateScore kept_score = climate_score(kept.rects);
    const SolverGoals followed = out.goals;
    for (double gain : kClimateFollowGains) {
      if (kept_score.all_met) break;
      const SolverGoals raised = raised_goals(followed, problem.rows, scene_goal_weight(scene, c), gain);
      const LinearObjective previous = objective;
      objective = linear_objective(c, raised, settings.bound_weight);
      Constrained k = constrain(stage.open, stage.values, grid_constraints);
      const ClimateScore score = climate_score(k.rects);
      if (score.error < kept_score.error) {
        kept = std::move(k), kept_score = score, out.goals = raised;
      } else {
        objective = previous;
      }
    }
  }
  // When the constraints cost much light, which of them: each family lifted in turn.
  const double free_rms = out.unconstrained_error.relative_rms;
  const double constrained_rms = goal_error(out.goals, kept.values.value).relative_rms;
  // (With climate goals the per-sensor goals are the element answer's light: the climate figures
  // tell what the constraints cost, in report_climate.)
  if (!climate && constraints_cost_much(free_rms, constrained_rms)) {
    if (progress) progress->start("solving: what the constraints cost", 1);
    // Searched from the free answer and from the openings found within the constraints (which
    // stay admissible when a limit is lifted), so lifting never reports more error than keeping.
    const std::vector<uint8_t> kept_open = rectangles_mask(scene.domain, kept.rects);
    out.constraint_costs = constraint_costs(constraints, [&](const OpeningConstraints& lifted) {
      const OpeningConstraints lifted_grid = grid_search_constraints(scene.domain, lifted);
      const Constrained from_free = constrain(out.open, free_values, lifted_grid);
      const Constrained from_kept = constrain(kept_open, kept.values, lifted_grid);
      return std::min({constrained_rms, goal_error(out.goals, from_free.values.value).relative_rms,
                       goal_error(out.goals, from_kept.values.value).relative_rms});
    }, free_rms, constrained_rms);
    out.warnings.push_back(constraint_cost_warning(free_rms, constrained_rms, out.constraint_costs));
  }
  std::vector<GridRectangle> rects = std::move(kept.rects);
  chosen = kept.values;
  best = kept.fitness;
  out.refined_error = kept.refined_error;
  std::optional<LinearObjective> about = std::move(kept.about);
  auto linearise_about_rects = [&] {
    about = linearised_objective(objective, records, rectangles_mask(scene.domain, rects), chosen.value);
  };
  out.open = rectangles_mask(scene.domain, rects);
  out.openings.clear();
  for (const GridRectangle& r : rects) out.openings.push_back(to_world(scene.domain, r));
  out.fitness = best;
  std::vector<PanelRectangle> final_rects;
  for (const GridRectangle& r : rects) final_rects.push_back(panel_rectangle(r, scene.domain.element_size()));
  // Whether `chosen` holds the records' exact values of final_rects (not so for catalogue sizes in
  // thick walls until their refined grid is traced).
  bool chosen_exact = true;
  if (uses_catalogue(scene.domain, constraints) && !rects.empty()) {
    if (progress) progress->start("solving: catalogue sizes", 1);
    if (!about) linearise_about_rects();
    const CatalogueSnap snap =
        snap_to_catalogue(scene.domain, records, objective, constraints, about->E, final_rects, progress);
    const double grid_error = prediction_error(objective, chosen.value - c.closed.value);
    final_rects = snap.openings;
    chosen_exact = snap.exact;
    if (snap.exact) chosen = records.evaluate(final_rects);
    else chosen.value = snap.values;
    out.fitness += prediction_error(objective, chosen.value - c.closed.value) - grid_error;
    out.warnings.insert(out.warnings.end(), snap.notes.begin(), snap.notes.end());
  }
  // Edges below the element size, where the exact error says so.
  double thick_seconds = 0.0;
  if (settings.refine_edges && !final_rects.empty()) {
    if (progress) progress->start("solving: edges off the element grid", 1);
    if (!about) linearise_about_rects();
    EdgeSearchScope scope;
    scope.opening_light = &about->E;
    const EdgeRefinement edges = refine_edges(scene.domain, records, objective, constraints, final_rects, progress, scope);
    out.edge_moves = edges.moves;
    if (edges.moves > 0 && !chosen_exact) {
      final_rects = edges.openings;  // the prediction comes from the refined grid or real cutters below
    } else if (edges.moves > 0) {
      const SensorValues v = records.evaluate(edges.openings);
      const double grid_error = prediction_error(objective, chosen.value - c.closed.value);
      const double error = prediction_error(objective, v.value - c.closed.value);
      if (error < grid_error) {
        chosen = v;
        out.fitness += error - grid_error;
        final_rects = edges.openings;
      }
    }
    // In thick walls, below the element size: the paths traced again on a grid refined about the
    // openings' edges. Its records then give the prediction, unless its openings are refused.
    std::string skipped;
    const auto thick_start = Clock::now();
    std::optional<ThickWallEdges> thick =
        refine_thick_wall_edges(scene, records, objective, constraints, final_rects, progress, &skipped);
    if (!skipped.empty()) out.warnings.push_back(skipped);
    const bool traced_thick = thick.has_value();
    // The refined records are noisier than the element grid's (one way at each tube side), and a
    // search over many candidates picks their noise too: with verification on, real cutters
    // decide between the openings before and after (the same random numbers for both).
    if (thick && thick->edges.moves > 0 && settings.verify &&
        !refined_edges_verified_better(records, final_rects, thick->edges.openings, out.goals))
      thick.reset();
    if (thick) {
      // Errors within one set of records: the first round's start is these openings.
      out.edge_moves += thick->edges.moves;
      out.fitness += thick->error - (chosen_exact ? thick->start_error
                                                  : prediction_error(objective, chosen.value - c.closed.value));
      chosen = thick->values;
      chosen_exact = true;
      final_rects = thick->edges.openings;
    }
    if (traced_thick) thick_seconds = since(thick_start);
  }
  if (!chosen_exact) {
    // Catalogue sizes in thick walls without their refined records: cut for real.
    std::vector<OpeningInput> cutters(final_rects.begin(), final_rects.end());
    chosen = records.cut(cutters, 0);
  }
  out.openings.clear();
  for (const PanelRectangle& r : final_rects) out.openings.push_back(to_world(scene.domain, r));
  out.open = open_elements(scene.domain, final_rects);
  // Facade composition: the rules' candidates scored by the exact error (records on thin walls,
  // real cutters when an opening is in a thick wall).
  std::function<SensorValues(const std::vector<PanelRectangle>&)> values_of =
      [&](const std::vector<PanelRectangle>& set) {
        const bool thick = std::any_of(set.begin(), set.end(), [&](const PanelRectangle& r) {
          return scene.domain.panels()[static_cast<size_t>(r.panel)].thickness > 0.0f;
        });
        if (!thick) return records.evaluate(set);
        std::vector<OpeningInput> cutters(set.begin(), set.end());
        return records.cut(cutters, settings.verify_paths);
      };
  // (Outside the block below: the trade-offs call `compose`, which refers to it, after it.)
  const std::function<double(const std::vector<PanelRectangle>&)> error_of =
      [&](const std::vector<PanelRectangle>& set) { return goal_error(out.goals, values_of(set).value).relative_rms; };
  std::function<std::vector<PanelRectangle>(const std::vector<PanelRectangle>&)> compose;
  double compose_seconds = 0.0;
  if (composes(scene.domain, constraints) && !final_rects.empty()) {
    const auto compose_start = Clock::now();
    if (progress) progress->start("solving: facade composition", 1);
    const Composition composed = compose_facades(scene.domain, constraints, final_rects, error_of, progress);
    out.composition = composed.steps;
    for (const CompositionStep& step : composed.steps)
      if (!step.met)
        out.warnings.push_back(step.rule + ": no admissible way to meet it was found on every facade; left as it was");
      else if (step.error_after > step.error_before + 1e-3)
        out.warnings.push_back(step.rule + " raises the error from " + percent_text(step.error_before) + " to " +
                               percent_text(step.error_after));
    if (composed.openings != final_rects) {
      final_rects = composed.openings;
      chosen = values_of(final_rects);
      out.openings.clear();
      for (const PanelRectangle& r : final_rects) out.openings.push_back(to_world(scene.domain, r));
      out.open = open_elements(scene.domain, final_rects);
    }
    compose = [&](const std::vector<PanelRectangle>& set) {
      return compose_facades(scene.domain, constraints, set, error_of, progress).openings;
    };
    compose_seconds = since(compose_start);
    out.timings.push_back({"composition", compose_seconds});
  }
  out.constraint_violations = all_violations(scene.domain, final_rects, constraints);
  for (const std::string& v : out.constraint_violations) out.warnings.push_back("constraints: " + v);
  out.predicted = chosen.value;
  out.predicted_stderr = chosen.standard_error;
  out.linear = linear_prediction(c, out.open);
  out.compensated = compensated_prediction(c, out.open);
  out.error = goal_error(out.goals, out.predicted);
  out.linear_error = goal_error(out.goals, out.linear);
  out.compensated_error = goal_error(out.goals, out.compensated);
  out.timings.push_back({"constraints", since(t) - thick_seconds - compose_seconds});
  if (thick_seconds > 0.0) out.timings.push_back({"thick-wall edges", thick_seconds});
  if (progress) progress->throw_if_cancelled();

  if (settings.tradeoffs && !out.openings.empty()) {
    t = Clock::now();
    if (progress) progress->start("solving: fewer openings", 1);
    TradeoffResult answer;
    answer.openings = out.openings;
    answer.predicted = out.predicted;
    answer.predicted_stderr = out.predicted_stderr;
    answer.error = out.error;
    answer.answer = true;
    out.tradeoffs.push_back(answer);
    for (const Tradeoff& f : fewer_openings(scene, records, objective, constraints, final_rects,
                                            about ? &about->E : nullptr, settings.verify_paths, compose, progress)) {
      TradeoffResult entry;
      for (const PanelRectangle& r : f.openings) entry.openings.push_back(to_world(scene.domain, r));
      entry.predicted = f.values.value;
      entry.predicted_stderr = f.values.standard_error;
      entry.error = goal_error(out.goals, f.values.value);
      entry.cut = f.cut;
      out.tradeoffs.push_back(std::move(entry));
    }
    out.timings.push_back({"trade-offs", since(t)});
    // Least glazing: a trade-off that meets every climate goal with less glass than the answer
    // becomes the answer (the list is of designs the solver evaluated; none passing with less
    // glass is shown beside it).
    if (climate && scene.sensors.climate_goals.least_glazing) {
      std::vector<ClimateFigure> answer_figures;
      try {
        const AnnualStudy year = records.annual_study(final_rects);
        answer_figures = climate_figures(*climate_problem_of, year.illuminance.total, year.illuminance.direct);
      } catch (const std::invalid_argument&) {
        // Edges off the grid lines of a thick wall: the records cannot tell; the answer stays.
      }
      const int least = answer_figures.empty() ? -1
                                                : least_glazing_entry(scene, records, *climate_problem_of, answer_figures,
                                                                      settings.verify, settings.verify_paths, &out.tradeoffs);
      if (least >= 0 && !out.tradeoffs[static_cast<size_t>(least)].answer) {
        for (TradeoffResult& entry : out.tradeoffs) entry.answer = false;
        TradeoffResult& chosen_entry = out.tradeoffs[static_cast<size_t>(least)];
        chosen_entry.answer = true;
        out.openings = chosen_entry.openings;
        final_rects.clear();
        for (const OpeningRectangle& o : out.openings) final_rects.push_back(o.parameter);
        out.open = open_elements(scene.domain, final_rects);
        out.predicted = chosen_entry.predicted;
        out.predicted_stderr = chosen_entry.predicted_stderr;
        out.linear = linear_prediction(c, out.open);
        out.compensated = compensated_prediction(c, out.open);
        out.error = chosen_entry.error;
        out.linear_error = goal_error(out.goals, out.linear);
        out.compensated_error = goal_error(out.goals, out.compensated);
        out.warnings.erase(std::remove_if(out.warnings.begin(), out.warnings.end(),
                                          [](const std::string& w) { return w.rfind("constraints: ", 0) == 0; }),
                           out.warnings.end());
        out.constraint_violations = all_violations(scene.domain, final_rects, constraints);
        for (const std::string& v : out.constraint_violations) out.warnings.push_back("constraints: " + v);
        out.climate.answer_from_tradeoffs = true;
      }
    }
  }
  if (settings.verify) {
    t = Clock::now();
    std::vector<OpeningInput> cutters;
    for (const OpeningRectangle& o : out.openings) cutters.emplace_back(o.parameter);
    const SensorValues v = records.cut(cutters, settings.verify_paths);
    out.verified = true;
    out.verified_value = v.value;
    out.verified_stderr = v.standard_error;
    out.verified_error = goal_error(out.goals, v.value);
    out.timings.push_back({"verification", since(t)});
  }
  if (climate) {
    t = Clock::now();
    report_climate(scene, records, *climate_problem_of, final_rects, settings.verify, settings.verify_paths, &out, progress);
    for (TradeoffResult& entry : out.tradeoffs)
      if (entry.answer || entry.climate.empty()) entry.climate = tradeoff_climate(records, *climate_problem_of, entry, out);
    out.timings.push_back({"climate figures", since(t)});
  }
  for (const std::string& w : {sparse_sampling_warning(c.paths_per_sensor, c.element_count()),
                               prediction_mismatch_warning(out)})
    if (!w.empty()) out.warnings.push_back(w);
  out.timings.push_back({"total", since(start)});
  if (progress) progress->advance();
  return out;
}

SolveResult solve_openings(const Scene& scene, Progress* progress) {
  refuse_dark_sky(scene);
  require_goals(scene);  // before tracing
  Scene traced = scene;
  if (scene.solver.paths_per_sensor > 0) traced.render.paths_per_sensor = scene.solver.paths_per_sensor;
  const auto t = Clock::now();
  Contributions c = compute_contributions(traced, progress);
  c.origin = contributions_origin(traced);
  const double seconds = since(t);
  SolveResult out = solve_openings(traced, c, progress);
  out.timings.insert(out.timings.begin(), {"contributions", seconds});
  out.timings.back().seconds += seconds;
  return out;
}

}  // namespace fenestra
