#include "solve/solver.h"

#include <algorithm>
#include <chrono>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <stdexcept>

#include "annual/annual_contributions.h"
#include "annual/annual_study.h"
#include "daylight/sky_figures.h"
#include "solve/catalogue_snap.h"
#include "solve/climate_report.h"
#include "solve/climate_stage.h"
#include "solve/compensation.h"
#include "solve/edge_refinement.h"
#include "solve/least_glazing.h"
#include "solve/linear_objective.h"
#include "solve/linear_stage.h"
#include "solve/linear_start.h"
#include "solve/opening_search.h"
#include "solve/refinable_openings.h"
#include "solve/prediction_check.h"
#include "solve/refine_openings.h"
#include "solve/thick_wall_edges.h"
#include "solve/thick_wall_joint_edges.h"
#include "solve/thick_wall_merges.h"
#include "solve/tradeoffs.h"
#include "trace/contributions_origin.h"
#include "util/number_text.h"

namespace fenestra {
namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// A daylight sky without light (the sun never up) makes every value 0: no goal can be met.
void refuse_dark_sky(const Scene& scene) {
  const std::string dark = dark_sky_warning(*scene.sky, scene.daylight.get());
  if (!dark.empty())
    throw std::invalid_argument("scene '" + scene.source + "': sky: " + dark +
                                "; the goals cannot be met: choose a date and time interval with daylight");
}

bool has_thick_panel(const OpeningDomain& domain) {
  for (const Panel& p : domain.panels())
    if (p.thickness > 0.0f) return true;
  return false;
}

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

// Of the sensors cuts could have traced, the share they did (1 when none were cut).
double traced_share(size_t traced, size_t cut) {
  return cut > 0 ? static_cast<double>(traced) / static_cast<double>(cut) : 1.0;
}

bool composes(const OpeningDomain& domain, const OpeningConstraints& constraints) {
  for (size_t p = 0; p < domain.panels().size(); ++p)
    if (constraints.for_panel(static_cast<int>(p)).composes()) return true;
  return false;
}

// Rules the user set (not only the automatic alignment of sills and heads).
bool composes_by_choice(const OpeningDomain& domain, const OpeningConstraints& constraints) {
  for (size_t p = 0; p < domain.panels().size(); ++p)
    if (constraints.for_panel(static_cast<int>(p)).composes_by_choice()) return true;
  return false;
}

// Whether some facade holds two openings or more.
bool a_facade_has_two(const OpeningDomain& domain, const std::vector<PanelRectangle>& openings) {
  const std::vector<int> facade = facades_of(domain);
  std::map<int, int> count;
  for (const PanelRectangle& r : openings)
    if (facade[static_cast<size_t>(r.panel)] >= 0 && ++count[facade[static_cast<size_t>(r.panel)]] >= 2) return true;
  return false;
}

// Openings within the constraints from a set of open elements, and the exact linear model about
// them (the local search's, then the edge search's screen).
struct Constrained {
  std::vector<GridRectangle> rects;
  SensorValues values;
  double fitness = 0.0;
  GoalError refined_error;
  std::optional<LinearObjective> about;
};

// One solve: the stages in the order they run (solve()), sharing what they hand each other. Each
// stage is listed in out.stages with its seconds and why it stopped, or why it was skipped.
// The search over whole openings starts from the linear start rounded at these levels, and from
// the element search's best states up to this many in all.
constexpr double kSearchRoundingLevels[] = {0.25, 0.5, 0.75};
constexpr size_t kSearchElementStarts = 3;
// A set the search considers is ruled out when its error, each sensor's sampled value moved by up
// to this many sampling errors towards its goal, does not gain: a sensor beyond it once in about
// 16 000 (a normal's two-sided tail), and then only that sensor's term is off.
constexpr double kBoundStandardErrors = 4.0;
// Edges in thick walls leave the grid on records traced again, the longest stage of a solid-wall
// solve: not traced when the openings on the grid miss the goals by at most this relative RMS
// beyond the records' noise (nothing the refinement could gain would show).
constexpr double kThickEdgesWorthTracing = 0.005;

class OpeningSolve {
 public:
  OpeningSolve(const Scene& scene, RecordQueries& records, Progress* progress)
      : scene_(scene), records_(records), c_(records.contributions()), progress_(progress),
        climate_(!scene.sensors.climate_goals.empty()), settings_(scene.solver),
        grid_(ElementGrid::from_domain(scene.domain)), ga_(genetic_settings_from(scene.solver)),
        constraints_(measured_constraints(scene)) {
    // In thick walls the records give a year only for edges on the grid lines: climate answers keep them there.
    if (climate_ && has_thick_panel(scene.domain)) settings_.refine_edges = false;
    out_.dropped = c_.dropped;
    // Said with the result's other warnings, so the Python API and Blender show it too.
    if (const std::string w = dropped_warning(c_.dropped); !w.empty()) out_.warnings.push_back(w);
    out_.goals = resolve_goals(scene, c_);
    objective_ = linear_objective(c_, out_.goals, settings_.bound_weight);
    // With a catalogue, the grid's openings keep near its sizes; they take them exactly below.
    grid_constraints_ = grid_search_constraints(scene.domain, constraints_);
  }
  OpeningSolve(const OpeningSolve&) = delete;
  OpeningSolve& operator=(const OpeningSolve&) = delete;

  SolveResult solve() {
    const auto start = Clock::now();
    element_stages();
    // Architectural refinement: regions become admissible rectangles (the paper's final step),
    // then a local search over whole openings; the exact evaluation has the last word.
    if (progress_) progress_->start("solving: openings within the constraints", 1);
    const auto constraints_start = Clock::now();
    openings_within_constraints();
    second_start();
    opening_search();
    thick_wall_openings();
    climate_openings();
    constraint_costs_stage();
    take_kept_openings();
    catalogue_sizes();
    edges_off_the_grid();
    composition();
    final_predictions();
    out_.timings.push_back({"constraints", since(constraints_start) - thick_seconds_ - compose_seconds_});
    if (thick_seconds_ > 0.0) out_.timings.push_back({"thick-wall edges", thick_seconds_});
    if (progress_) progress_->throw_if_cancelled();
    tradeoffs();
    least_glazing();
    verification();
    climate_figures_stage();
    for (const std::string& w : {sparse_sampling_warning(c_.paths_per_sensor, c_.element_count()),
                                 prediction_mismatch_warning(out_)})
      if (!w.empty()) out_.warnings.push_back(w);
    out_.timings.push_back({"total", since(start)});
    if (progress_) progress_->advance();
    return std::move(out_);
  }

 private:
  // Stages 1 and 2: the answer in elements (solve/linear_stage.h, solve/climate_stage.h).
  void element_stages() {
    element_ = climate_ ? climate_element_stages(scene_, grid_, ga_, constraints_, records_, &objective_, out_,
                                                 &climate_problem_, progress_)
                        : linear_element_stages(scene_, objective_, grid_, ga_, records_, out_, progress_);
    chosen_ = element_.values;
    free_values_ = chosen_;
  }

  double exact_of(const std::vector<GridRectangle>& rects, SensorValues* values) {
    const std::vector<uint8_t> open = rectangles_mask(scene_.domain, rects);
    *values = records_.exact(open);
    return exact_fitness(objective_, grid_, ga_.shape, open, values->value - c_.closed.value);
  }

  // The stages "rectangles" and "local search" from a set of open elements; listed in *stages when
  // given (the first time), run unlisted within the later stages that call them again.
  Constrained constrain(const std::vector<uint8_t>& open, const SensorValues& open_values,
                        const OpeningConstraints& grid_constraints, std::vector<SolveStage>* stages = nullptr) {
    std::vector<SolveStage> unlisted;
    if (!stages) stages = &unlisted;
    Constrained k;
    run_stage(stages, "rectangles", [&] {
      // Rectangles are scored by the exact linear model about the state (the elements' joint light).
      const LinearObjective about_open = linearised_objective(objective_, records_, open, open_values.value);
      k.rects = refine_openings(scene_.domain, open, about_open, grid_constraints, progress_);
      k.fitness = exact_of(k.rects, &k.values);
      k.refined_error = goal_error(out_.goals, k.values.value);
      return stop_reason::kDone;
    });
    stages->back().error_before = goal_error(out_.goals, open_values.value).relative_rms;
    stages->back().error_after = k.refined_error.relative_rms;
    if (settings_.improve_iterations <= 0) {
      skip_stage(stages, "local search", stop_reason::kNoImproveIterations);
      return k;
    }
    if (progress_) progress_->start("solving: local search over openings", 1);
    // Each round searches the exact linear model about the current openings, and is kept only if
    // the exact evaluation agrees; the next round linearises about its answer.
    const double refined_rms = k.refined_error.relative_rms;
    run_stage(stages, "local search", [&] {
      auto linearise = [&] {
        k.about = linearised_objective(objective_, records_, rectangles_mask(scene_.domain, k.rects), k.values.value);
      };
      linearise();
      for (int round = 0; round < kLinearisationRounds; ++round) {
        const std::vector<GridRectangle> improved =
            improve_rectangles(scene_.domain, k.rects, *k.about, grid_constraints, settings_.seed + round,
                               settings_.improve_iterations, progress_);
        SensorValues improved_values;
        const double f = exact_of(improved, &improved_values);
        if (!(f < k.fitness * (1.0 - 1e-6))) return stop_reason::kNoImprovement;
        k.fitness = f;
        k.rects = improved;
        k.values = improved_values;
        linearise();
      }
      return stop_reason::kRoundLimit;
    });
    stages->back().error_before = refined_rms;
    stages->back().error_after = goal_error(out_.goals, k.values.value).relative_rms;
    return k;
  }

  void openings_within_constraints() { kept_ = constrain(out_.open, chosen_, grid_constraints_, &out_.stages); }

  // When the free answer takes light from elements no admissible opening can cover (margins,
  // rows below the sill or above the head limits), the openings made from it can land far from
  // the best: a second start searches the elements again without those, and the better is kept.
  void second_start() {
    const std::vector<uint8_t> out_of_bounds = elements_out_of_bounds(scene_.domain, grid_constraints_);
    if (!opens_any(out_.open, out_of_bounds)) return skip_stage(&out_.stages, "second start", stop_reason::kNothingOutOfBounds);
    run_stage(&out_.stages, "second start", [&] {
      if (progress_) progress_->start("solving: elements within the constraints", 1);
      const ElementChoice within = search_within_bounds(objective_, grid_, ga_, records_, element_.start_open,
                                                        out_.open, out_of_bounds, progress_);
      Constrained second = constrain(within.open, within.values, grid_constraints_);
      out_.second_start = true;
      if (second.fitness < kept_.fitness) kept_ = std::move(second), out_.second_start_kept = true;
      return stop_reason::kDone;
    });
  }

  // Admissible openings made from an open set: its regions as rectangles, scored by the exact linear
  // model about it.
  std::vector<GridRectangle> openings_from(const std::vector<uint8_t>& open) {
    const SensorValues& values = records_.exact(open);
    const LinearObjective about = linearised_objective(objective_, records_, open, values.value);
    return refine_openings(scene_.domain, open, about, grid_constraints_, progress_);
  }

  // Where the search over whole openings starts: the openings within the constraints so far, the
  // linear start rounded at several levels, and the element search's next best states.
  std::vector<std::vector<GridRectangle>> opening_search_starts(std::vector<std::string>* names) {
    std::vector<std::vector<GridRectangle>> starts = {kept_.rects};
    names->push_back("the openings within the constraints");
    const std::vector<uint8_t> out_of_bounds = elements_out_of_bounds(scene_.domain, grid_constraints_);
    std::set<std::vector<uint8_t>> tried = {out_.open};
    auto add = [&](std::vector<uint8_t> open, const std::string& name) {
      for (size_t k = 0; k < open.size(); ++k) open[k] &= static_cast<uint8_t>(!out_of_bounds[k]);
      if (std::none_of(open.begin(), open.end(), [](uint8_t o) { return o != 0; })) return false;
      if (!tried.insert(open).second) return false;
      starts.push_back(openings_from(open));
      names->push_back(name);
      return true;
    };
    if (element_.start_continuous.size() == static_cast<Eigen::Index>(grid_.size()))
      for (double level : kSearchRoundingLevels)
        add(round_to_binary(element_.start_continuous, level), "the linear start rounded at " + decimal_text(level));
    size_t states = 0;
    for (size_t k = 1; k < element_.candidates.size() && states < kSearchElementStarts; ++k)
      states += add(element_.candidates[k], "the element search's state " + std::to_string(k + 1)) ? 1 : 0;
    return starts;
  }

  // The exact search over whole openings from several starts (solve/opening_search.h): the linear
  // models that made the openings misjudge what elements do together; the records do not.
  void opening_search() {
    if (climate_) return skip_stage(&out_.stages, "opening search", stop_reason::kClimateFollowsLight);
    if (settings_.search_evaluations <= 0)
      return skip_stage(&out_.stages, "opening search", stop_reason::kNoSearchEvaluations);
    const double before = kept_.refined_error.relative_rms;
    run_stage(&out_.stages, "opening search", [&] {
      // Its bar counts the sets scored against the limit (the search mostly stops before it).
      if (progress_)
        progress_->start("solving: searching whole openings", static_cast<uint64_t>(settings_.search_evaluations));
      const OpeningScore score = [&](const std::vector<GridRectangle>& rects) {
        SensorValues unused;
        return exact_of(rects, &unused);
      };
      std::vector<std::string> names;
      const std::vector<std::vector<GridRectangle>> starts = opening_search_starts(&names);
      // Pair moves are ranked by the light each move adds alone (exact, from the records), summed.
      const OpeningScreen screen = [&](const std::vector<GridRectangle>& about,
                                       const std::vector<std::array<std::vector<GridRectangle>, 2>>& singles) {
        const std::vector<uint8_t> base_open = rectangles_mask(scene_.domain, about);
        const Eigen::VectorXd base = records_.exact(base_open).value;
        std::vector<double> predicted;
        for (const auto& [a, b] : singles) {
          const std::vector<uint8_t> open_a = rectangles_mask(scene_.domain, a), open_b = rectangles_mask(scene_.domain, b);
          std::vector<uint8_t> both = open_b;  // b's change, and a's where a differs from `about`
          for (size_t k = 0; k < both.size(); ++k)
            if (open_a[k] != base_open[k]) both[k] = open_a[k];
          const Eigen::VectorXd sum = records_.exact(open_a).value + records_.exact(open_b).value - base;
          predicted.push_back(exact_fitness(objective_, grid_, ga_.shape, both, sum - c_.closed.value));
        }
        return predicted;
      };
      // A move is ruled out when even its sampled values' least error (each sensor anywhere within
      // kBoundStandardErrors of its sampling error) does not gain.
      const OpeningBound bound = [&](const std::vector<GridRectangle>& rects) {
        const std::vector<uint8_t> open = rectangles_mask(scene_.domain, rects);
        const SensorValues sampled = records_.sampled(open);
        return exact_fitness_lower_bound(objective_, grid_, ga_.shape, open, sampled.value - c_.closed.value,
                                         kBoundStandardErrors * sampled.standard_error);
      };
      const OpeningSearchResult found = search_whole_openings(scene_.domain, grid_constraints_, starts, score,
                                                              settings_.search_evaluations, progress_, screen, bound);
      OpeningSearchSummary& summary = out_.opening_search;
      summary.ran = true;
      summary.starts = names;
      summary.evaluations = found.evaluations;
      summary.scored = found.scored;
      summary.best_found_after = found.best_found_after;
      summary.moves = found.moves;
      summary.restarts = found.restarts;
      summary.pair_moves = found.pair_moves;
      if (found.best_start >= 0) summary.best_start = names[static_cast<size_t>(found.best_start)];
      search_alternatives_ = found.alternatives;
      search_starts_ = starts;
      summary.kept = found.score < kept_.fitness;
      if (found.score < kept_.fitness) {
        kept_.fitness = exact_of(found.rects, &kept_.values);
        kept_.rects = found.rects;
        kept_.refined_error = goal_error(out_.goals, kept_.values.value);
        kept_.about = linearised_objective(objective_, records_, rectangles_mask(scene_.domain, kept_.rects),
                                           kept_.values.value);
      }
      return found.out_of_evaluations ? stop_reason::kEvaluationLimit : stop_reason::kNoImprovement;
    });
    out_.stages.back().error_before = before;
    out_.stages.back().error_after = kept_.refined_error.relative_rms;
  }

  bool thick_panel(int panel) const { return scene_.domain.panels()[static_cast<size_t>(panel)].thickness > 0.0f; }

  // In thick walls the grid's best is a poor guide once edges may leave the grid: the openings
  // chosen again by the error they reach with their sides interpolated off it
  // (solve/refinable_openings.h), when the thick-wall edges stage will trace them.
  void thick_wall_openings() {
    const char* skipped = climate_                                     ? stop_reason::kClimateThickWalls
                          : !settings_.refine_edges                    ? stop_reason::kNoRefineEdges
                          : !scene_.domain.has_thick_walls()           ? stop_reason::kNoThickWallEdge
                          : uses_catalogue(scene_.domain, constraints_) ? stop_reason::kCatalogueSizes
                          : settings_.search_evaluations <= 0          ? stop_reason::kNoSearchEvaluations
                          : kept_.rects.empty()                        ? stop_reason::kNoOpenings
                          : within_the_noise(kept_.values)             ? stop_reason::kWithinNoise
                                                                       : nullptr;
    if (skipped) return skip_stage(&out_.stages, "thick-wall openings", skipped);
    ThickWallOpeningsSummary& summary = out_.thick_wall_openings;
    run_stage(&out_.stages, "thick-wall openings", [&] {
      if (progress_) progress_->start("solving: openings for edges off the grid in thick walls", 1);
      const OpeningValues values_of = [&](const std::vector<GridRectangle>& rects) {
        return Eigen::VectorXd(records_.exact(rectangles_mask(scene_.domain, rects)).value - c_.closed.value);
      };
      // From the search's answer, its other local optima and its starts: the two whose interpolated
      // errors are lowest.
      std::vector<std::vector<GridRectangle>> starts = {kept_.rects};
      starts.insert(starts.end(), search_alternatives_.begin(), search_alternatives_.end());
      starts.insert(starts.end(), search_starts_.begin(), search_starts_.end());
      const RefinableOpenings found = search_refinable_openings(scene_.domain, grid_constraints_, starts, values_of,
                                                                objective_, settings_.search_evaluations, progress_);
      summary.ran = true;
      summary.evaluations = found.evaluations;
      summary.moves = found.moves;
      summary.interpolated_before = std::sqrt(found.start_errors.at(0));
      summary.interpolated_after = std::sqrt(found.error);
      // Openings the thick-wall edge search reaches from the search's answer bring nothing: it
      // searches them exactly, from the answer's own.
      summary.kept = !found.rects.empty() && found.error < found.start_errors[0] &&
                     !within_thick_wall_edge_reach(kept_.rects, found.rects, scene_.domain.element_size(),
                                                   constraints_.module);
      if (summary.kept) {
        grid_best_ = kept_;
        kept_.fitness = exact_of(found.rects, &kept_.values);
        kept_.rects = found.rects;
        kept_.refined_error = goal_error(out_.goals, kept_.values.value);
        kept_.about = linearised_objective(objective_, records_, rectangles_mask(scene_.domain, kept_.rects),
                                           kept_.values.value);
      } else {
        summary.interpolated_after = summary.interpolated_before;
      }
      return found.out_of_evaluations ? stop_reason::kEvaluationLimit : stop_reason::kNoImprovement;
    });
    // Its errors are those interpolated off the grid (on the grid they may rise).
    out_.stages.back().error_before = summary.interpolated_before;
    out_.stages.back().error_after = summary.interpolated_after;
  }

  // Climate goals: openings that follow the element answer's light can still fall short of a goal
  // it met (a sensor just over its threshold drops below). The constraints stage again with the
  // followed light raised at the sensors of the goals missed from below (on a floor, the rooms
  // short of light; the others keep theirs), kept when the year of its openings is better.
  void climate_openings() {
    if (!climate_) return skip_stage(&out_.stages, "climate openings", stop_reason::kNoClimateGoals);
    run_stage(&out_.stages, "climate openings", [&] {
      if (progress_) progress_->start("solving: openings for the climate goals", 1);
      const ClimateProblem& problem = *climate_problem_;
      auto score_of = [&](const std::vector<GridRectangle>& rects) {
        return climate_score(records_, problem, rectangles_mask(scene_.domain, rects));
      };
      ClimateScore kept_score = score_of(kept_.rects);
      const SolverGoals followed = out_.goals;
      for (double gain : kClimateFollowGains) {
        if (kept_score.all_met || kept_score.short_rows.empty()) break;
        const SolverGoals raised = raised_goals(scene_, c_, out_.goals, followed, kept_score.short_rows, gain);
        const LinearObjective previous = objective_;
        objective_ = linear_objective(c_, raised, settings_.bound_weight);
        Constrained k = constrain(element_.open, element_.values, grid_constraints_);
        const ClimateScore score = score_of(k.rects);
        if (score.error < kept_score.error) {
          kept_ = std::move(k), kept_score = score, out_.goals = raised;
        } else {
          objective_ = previous;
        }
      }
      return kept_score.all_met ? stop_reason::kGoalsMet : stop_reason::kRoundLimit;
    });
  }

  // When the constraints cost much light, which of them: each family lifted in turn.
  void constraint_costs_stage() {
    // (With climate goals the per-sensor goals are the element answer's light: the climate figures
    // tell what the constraints cost, in report_climate.)
    if (climate_) return skip_stage(&out_.stages, "constraint costs", stop_reason::kClimateTellsCost);
    const double free_rms = out_.unconstrained_error.relative_rms;
    const double constrained_rms = goal_error(out_.goals, kept_.values.value).relative_rms;
    if (!constraints_cost_much(free_rms, constrained_rms))
      return skip_stage(&out_.stages, "constraint costs", stop_reason::kCostLittle);
    run_stage(&out_.stages, "constraint costs", [&] {
      if (progress_) progress_->start("solving: what the constraints cost", 1);
      // Searched from the free answer and from the openings found within the constraints (which
      // stay admissible when a limit is lifted), so lifting never reports more error than keeping.
      const std::vector<uint8_t> kept_open = rectangles_mask(scene_.domain, kept_.rects);
      out_.constraint_costs = constraint_costs(constraints_, [&](const OpeningConstraints& lifted) {
        const OpeningConstraints lifted_grid = grid_search_constraints(scene_.domain, lifted);
        const Constrained from_free = constrain(out_.open, free_values_, lifted_grid);
        const Constrained from_kept = constrain(kept_open, kept_.values, lifted_grid);
        return std::min({constrained_rms, goal_error(out_.goals, from_free.values.value).relative_rms,
                         goal_error(out_.goals, from_kept.values.value).relative_rms});
      }, free_rms, constrained_rms);
      out_.warnings.push_back(constraint_cost_warning(free_rms, constrained_rms, out_.constraint_costs));
      return stop_reason::kDone;
    });
  }

  // The openings kept on the element grid become the answer the stages below refine.
  void take_kept_openings() {
    rects_ = std::move(kept_.rects);
    chosen_ = kept_.values;
    out_.refined_error = kept_.refined_error;
    about_ = std::move(kept_.about);
    out_.open = rectangles_mask(scene_.domain, rects_);
    out_.openings.clear();
    for (const GridRectangle& r : rects_) out_.openings.push_back(to_world(scene_.domain, r));
    out_.fitness = kept_.fitness;
    for (const GridRectangle& r : rects_) final_rects_.push_back(panel_rectangle(r, scene_.domain.element_size()));
  }

  void linearise_about_rects() {
    about_ = linearised_objective(objective_, records_, rectangles_mask(scene_.domain, rects_), chosen_.value);
  }

  double chosen_error() const { return prediction_error(objective_, chosen_.value - c_.closed.value); }

  void catalogue_sizes() {
    if (!uses_catalogue(scene_.domain, constraints_))
      return skip_stage(&out_.stages, "catalogue sizes", stop_reason::kNoCatalogue);
    if (rects_.empty()) return skip_stage(&out_.stages, "catalogue sizes", stop_reason::kNoOpenings);
    run_stage(&out_.stages, "catalogue sizes", [&] {
      if (progress_) progress_->start("solving: catalogue sizes", 1);
      if (!about_) linearise_about_rects();
      // In thick walls the sizes are chosen by real cuts (the linear model misjudges whole
      // openings there); climate goals are not the design sky's, so they keep the linear model.
      const bool thick = std::any_of(final_rects_.begin(), final_rects_.end(),
                                     [&](const PanelRectangle& r) { return thick_panel(r.panel); });
      const int cut_paths = thick && !climate_ ? thick_wall_cut_paths(c_.paths_per_sensor) : 0;
      const CatalogueSnap snap = snap_to_catalogue(scene_.domain, records_, objective_, constraints_, about_->E,
                                                   final_rects_, progress_, cut_paths);
      const double grid_error = chosen_error();
      final_rects_ = snap.openings;
      chosen_exact_ = snap.exact;
      if (cut_paths > 0) chosen_ = {snap.values, snap.standard_error};
      else if (snap.exact) chosen_ = records_.evaluate(final_rects_);
      else chosen_.value = snap.values;
      out_.fitness += chosen_error() - grid_error;
      out_.warnings.insert(out_.warnings.end(), snap.notes.begin(), snap.notes.end());
      return stop_reason::kDone;
    });
  }

  // Edges below the element size, where the exact error says so; in thick walls on records traced
  // again about the openings' edges.
  void edges_off_the_grid() {
    const char* skipped = !settings_.refine_edges ? (scene_.solver.refine_edges ? stop_reason::kClimateThickWalls
                                                                                : stop_reason::kNoRefineEdges)
                          : final_rects_.empty()  ? stop_reason::kNoOpenings
                                                  : nullptr;
    if (skipped) {
      skip_stage(&out_.stages, "edges off the grid", skipped);
      skip_stage(&out_.stages, "thick-wall edges", skipped);
      skip_stage(&out_.stages, "thick-wall merges", skipped);
      return skip_stage(&out_.stages, "thick-wall joint edges", skipped);
    }
    run_stage(&out_.stages, "edges off the grid", [&] {
      if (progress_) progress_->start("solving: edges off the element grid", 1);
      if (!about_) linearise_about_rects();
      EdgeSearchScope scope;
      scope.opening_light = &about_->E;
      // Openings chosen for their edges off the grid in thick walls move there, not on the grid.
      scope.thick_panels = !grid_best_;
      EdgeRefinement edges =
          refine_edges(scene_.domain, records_, objective_, constraints_, final_rects_, progress_, scope);
      if (edges.moves > 0 && climate_ && !climate_goals_kept(final_rects_, edges.openings)) edges.moves = 0;
      out_.edge_moves = edges.moves;
      if (edges.moves > 0 && !chosen_exact_) {
        final_rects_ = edges.openings;  // the prediction comes from real cutters below
      } else if (edges.moves > 0) {
        const SensorValues v = records_.evaluate(edges.openings);
        const double grid_error = chosen_error();
        const double error = prediction_error(objective_, v.value - c_.closed.value);
        if (error < grid_error) {
          chosen_ = v;
          out_.fitness += error - grid_error;
          final_rects_ = edges.openings;
        }
      }
      edges_of_the_search_alternatives();
      return stop_reason::kDone;
    });
    thick_wall_edges();
  }

  // Climate goals: the edges follow the per-sensor light, which is not the year; they are kept when
  // the year of `after` meets every goal `before` meets.
  bool climate_goals_kept(const std::vector<PanelRectangle>& before, const std::vector<PanelRectangle>& after) {
    const auto figures_of = [&](const std::vector<PanelRectangle>& rects) {
      const AnnualStudy year = records_.annual_study(rects);
      return climate_figures(*climate_problem_, year.illuminance.total, year.illuminance.direct);
    };
    const std::vector<ClimateFigure> was = figures_of(before), is = figures_of(after);
    const std::vector<ClimateGoal>& goals = climate_problem_->objective->goals().goals;
    for (size_t g = 0; g < goals.size(); ++g)
      if (figure_meets(goals[g], was[g].achieved) && !figure_meets(goals[g], is[g].achieved)) return false;
    return true;
  }

  // The grid's best is not always the best once edges leave the grid: on thin panels (where the
  // records evaluate any rectangle exactly) the edges of the search's other local optima move too,
  // and the best by the exact error is kept.
  void edges_of_the_search_alternatives() {
    if (!chosen_exact_ || uses_catalogue(scene_.domain, constraints_)) return;
    for (const std::vector<GridRectangle>& alternative : search_alternatives_) {
      const bool thin = std::all_of(alternative.begin(), alternative.end(), [&](const GridRectangle& r) {
        return scene_.domain.panels()[static_cast<size_t>(r.panel)].thickness == 0.0f;
      });
      if (!thin || alternative.empty()) continue;
      const std::vector<uint8_t> open = rectangles_mask(scene_.domain, alternative);
      LinearObjective about = linearised_objective(objective_, records_, open, records_.exact(open).value);
      std::vector<PanelRectangle> start;
      for (const GridRectangle& r : alternative) start.push_back(panel_rectangle(r, scene_.domain.element_size()));
      EdgeSearchScope scope;
      scope.opening_light = &about.E;
      const EdgeRefinement edges = refine_edges(scene_.domain, records_, objective_, constraints_, start, progress_, scope);
      const SensorValues v = records_.evaluate(edges.openings);
      const double current = chosen_error(), error = prediction_error(objective_, v.value - c_.closed.value);
      if (!(error < current)) continue;
      chosen_ = v;
      out_.fitness += error - current;
      out_.edge_moves = edges.moves;
      final_rects_ = edges.openings;
      about_ = std::move(about);
      ++out_.opening_search.alternatives_kept;
    }
  }

  // The openings (exact values) miss the goals by at most kThickEdgesWorthTracing beyond the
  // records' noise, with one of them in a thick wall.
  bool grid_meets_the_goals_within_the_noise() const {
    const bool thick = std::any_of(final_rects_.begin(), final_rects_.end(),
                                   [&](const PanelRectangle& r) { return thick_panel(r.panel); });
    return thick && chosen_exact_ && within_the_noise(chosen_);
  }

  bool within_the_noise(const SensorValues& values) const {
    if (values.standard_error.size() != values.value.size()) return false;
    const double error = goal_error(out_.goals, values.value).relative_rms;
    const double noise = goal_noise(out_.goals, values.standard_error);
    return error * error - noise * noise <= kThickEdgesWorthTracing * kThickEdgesWorthTracing;
  }

  // In thick walls, below the element size: the edges searched with real cutters, from where the
  // element grid's records place them (solve/thick_wall_edges.h). The cuts give the prediction.
  void thick_wall_edges() {
    bool searched = false;
    const double seconds = run_stage(&out_.stages, "thick-wall edges", [&] {
      if (grid_meets_the_goals_within_the_noise()) return stop_reason::kWithinNoise;
      const bool thick = std::any_of(final_rects_.begin(), final_rects_.end(),
                                     [&](const PanelRectangle& r) { return thick_panel(r.panel); });
      if (!thick || edge_steps(scene_.domain.element_size(), constraints_.module, true).size() < 2)
        return stop_reason::kNoThickWallEdge;
      const StageStatus stage(progress_, "solving: edges in thick walls, with real cutters");
      const int paths = thick_wall_cut_paths(c_.paths_per_sensor);
      // Free sizes: placed here, every side then moved at once (thick_wall_joint_edges); sizes
      // from a catalogue slide by pairs of edges instead, which the joint steps cannot.
      const bool slide = uses_catalogue(scene_.domain, constraints_);
      const ThickWallEdges cut =
          slide ? search_thick_wall_edges(scene_.domain, records_, objective_, constraints_, final_rects_, paths,
                                          progress_)
                : place_thick_wall_edges(scene_.domain, records_, objective_, constraints_, final_rects_, paths);
      searched = true;
      ThickWallEdgesSummary& summary = out_.thick_wall_edges;
      summary.ran = true;
      summary.searched = slide;
      summary.cuts = cut.cuts;
      summary.rough_cuts = cut.rough_cuts;
      summary.paths_per_cut = paths;
      summary.moves = cut.edges.moves;
      summary.from_placement = cut.from_placement;
      const double start_error = prediction_error(objective_, cut.start_values.value - c_.closed.value);
      thick_start_error_ = goal_error(out_.goals, cut.start_values.value).relative_rms;
      const double error = prediction_error(objective_, cut.values.value - c_.closed.value);
      out_.edge_moves += cut.edges.moves;
      out_.fitness += error - (chosen_exact_ ? start_error : chosen_error());
      chosen_ = cut.values;
      chosen_exact_ = true;
      final_rects_ = cut.edges.openings;
      return stop_reason::kDone;
    });
    if (searched) {
      thick_seconds_ = seconds;
      out_.stages.back().error_before = thick_start_error_;
      out_.stages.back().error_after = goal_error(out_.goals, chosen_.value).relative_rms;
    }
    thick_wall_merges(searched);
    thick_wall_joint_edges(searched);
    keep_the_search_if_better();
  }

  // Every side of the openings in thick walls moved at once, judged by cuts of more paths
  // (solve/thick_wall_joint_edges.h), after the edge search (`searched`) and the merges.
  void thick_wall_joint_edges(bool searched) {
    const char* skipped = !searched ? stop_reason::kNoThickWallEdgeSearch
                          : within_the_noise(chosen_) ? stop_reason::kCutsWithinNoise
                                                      : nullptr;
    if (skipped) return skip_stage(&out_.stages, "thick-wall joint edges", skipped);
    double before = 0.0;  // the start's judged cut
    thick_seconds_ += run_stage(&out_.stages, "thick-wall joint edges", [&] {
      const StageStatus stage(progress_, "solving: all edges in thick walls together, with real cutters");
      const int paths = out_.thick_wall_edges.paths_per_cut;
      const int judge_paths = joint_edge_judge_paths(paths, c_.paths_per_sensor);
      ThickWallJointEdges joint = joint_thick_wall_edges(scene_.domain, records_, objective_, constraints_,
                                                         final_rects_, paths, judge_paths, kThickWallJointEdgeStream,
                                                         progress_);
      // The scans already ran from there when the thick-wall edges stage searched (a catalogue).
      if (!within_the_noise(joint.values) && !out_.thick_wall_edges.searched)
        scan_stalled_joint_edges(scene_.domain, records_, objective_, constraints_, final_rects_, paths, judge_paths,
                                 kThickWallJointEdgeStream, progress_, &joint);
      ThickWallJointEdgesSummary& summary = out_.thick_wall_joint_edges;
      summary.ran = true;
      summary.steps = joint.steps;
      summary.sides = joint.sides;
      summary.cuts = joint.cuts;
      summary.judged_cuts = joint.judged_cuts;
      summary.paths_per_cut = paths;
      summary.judge_paths = judge_paths;
      summary.scanned = joint.scanned;
      summary.scan_cuts = joint.scan_cuts;
      summary.scan_rough_cuts = joint.scan_rough_cuts;
      summary.scan_moves = joint.scan_moves;
      summary.traced_share = traced_share(joint.sensors_traced, joint.sensors_cut);
      before = goal_error(out_.goals, joint.start_values.value).relative_rms;
      // The judged cut is kept either way: more paths than the edge search's, the same openings.
      out_.fitness += prediction_error(objective_, joint.values.value - c_.closed.value) - chosen_error();
      chosen_ = joint.values;
      final_rects_ = joint.openings;
      return joint.steps > 0 || joint.scan_moves > 0 ? stop_reason::kDone : stop_reason::kNoImprovement;
    });
    out_.stages.back().error_before = before;
    out_.stages.back().error_after = goal_error(out_.goals, chosen_.value).relative_rms;
  }

  // How many openings, judged by real cutters: each removed, and each pair on a thick panel merged
  // (solve/thick_wall_merges.h), after the edge search (`searched`).
  void thick_wall_merges(bool searched) {
    const char* skipped = !searched                     ? stop_reason::kNoThickWallEdgeSearch
                          : final_rects_.size() < 2     ? stop_reason::kOneOpening
                          : within_the_noise(chosen_)   ? stop_reason::kCutsWithinNoise
                                                        : nullptr;
    if (skipped) return skip_stage(&out_.stages, "thick-wall merges", skipped);
    const double before = goal_error(out_.goals, chosen_.value).relative_rms;
    thick_seconds_ += run_stage(&out_.stages, "thick-wall merges", [&] {
      const StageStatus stage(progress_, "solving: openings in thick walls merged or removed, with real cutters");
      const ThickWallMerges merges =
          merge_thick_wall_openings(scene_.domain, records_, objective_, constraints_, final_rects_,
                                    out_.thick_wall_edges.paths_per_cut, kThickWallEdgeCutStream, progress_);
      ThickWallMergesSummary& summary = out_.thick_wall_merges;
      summary.ran = true;
      summary.cuts = merges.cuts;
      summary.rough_cuts = merges.rough_cuts;
      summary.removed = merges.removed;
      summary.merged = merges.merged;
      summary.merges_searched = merges.merges_searched;
      summary.traced_share = traced_share(merges.sensors_traced, merges.sensors_cut);
      if (merges.removed + merges.merged > 0) {
        out_.fitness += prediction_error(objective_, merges.values.value - c_.closed.value) - chosen_error();
        chosen_ = merges.values;
        final_rects_ = merges.openings;
      }
      return stop_reason::kDone;
    });
    out_.stages.back().error_before = before;
    out_.stages.back().error_after = goal_error(out_.goals, chosen_.value).relative_rms;
  }

  // When thick_wall_openings chose other openings than the search, and those, refined in the
  // thick walls, meet the goals worse than the search's on the grid: the
  // search's openings instead (each error from its own records, both unbiased).
  void keep_the_search_if_better() {
    if (!grid_best_) return;
    const double grid_error = prediction_error(objective_, grid_best_->values.value - c_.closed.value);
    if (chosen_exact_ && chosen_error() < grid_error) return;
    out_.thick_wall_openings.reverted = true;
    final_rects_.clear();
    for (const GridRectangle& r : grid_best_->rects) final_rects_.push_back(panel_rectangle(r, scene_.domain.element_size()));
    rects_ = grid_best_->rects;
    chosen_ = grid_best_->values;
    chosen_exact_ = true;
    out_.fitness = grid_best_->fitness;
    out_.refined_error = grid_best_->refined_error;
    out_.edge_moves = 0;
    about_ = grid_best_->about;
  }

  void set_openings(const std::vector<PanelRectangle>& rects) {
    out_.openings.clear();
    for (const PanelRectangle& r : rects) out_.openings.push_back(to_world(scene_.domain, r));
    out_.open = open_elements(scene_.domain, rects);
  }

  // The rules' candidates are scored by the exact error (records on thin walls, real cutters when an
  // opening is in a thick wall).
  SensorValues values_of(const std::vector<PanelRectangle>& set) {
    const bool thick = std::any_of(set.begin(), set.end(), [&](const PanelRectangle& r) {
      return scene_.domain.panels()[static_cast<size_t>(r.panel)].thickness > 0.0f;
    });
    if (!thick) return records_.evaluate(set);
    std::vector<OpeningInput> cutters(set.begin(), set.end());
    return records_.cut(cutters, settings_.verify_paths, 0);
  }

  // Facade composition; `compose_` then serves the trade-offs too.
  void composition() {
    if (!chosen_exact_) {
      // Catalogue sizes in thick walls, off the element grid: cut for real.
      std::vector<OpeningInput> cutters(final_rects_.begin(), final_rects_.end());
      chosen_ = records_.cut(cutters, 0, 0);
    }
    set_openings(final_rects_);
    if (!composes(scene_.domain, constraints_))
      return skip_stage(&out_.stages, "composition", stop_reason::kNoFacadeRules);
    if (final_rects_.empty()) return skip_stage(&out_.stages, "composition", stop_reason::kNoOpenings);
    if (!composes_by_choice(scene_.domain, constraints_) && !a_facade_has_two(scene_.domain, final_rects_))
      return skip_stage(&out_.stages, "composition", stop_reason::kNothingToAlign);
    const std::function<double(const std::vector<PanelRectangle>&)> error_of =
        [this](const std::vector<PanelRectangle>& set) { return goal_error(out_.goals, values_of(set).value).relative_rms; };
    compose_seconds_ = run_stage(&out_.stages, "composition", [&] {
      if (progress_) progress_->start("solving: facade composition", 1);
      const Composition composed = compose_facades(scene_.domain, constraints_, final_rects_, error_of, progress_);
      out_.composition = composed.steps;
      for (const CompositionStep& step : composed.steps)
        if (step.automatic && !step.kept)
          out_.warnings.push_back(step.rule + " (automatic) was left out: " +
                                  (step.met ? "it would raise the error from " + percent_text(step.error_before) +
                                                  " to " + percent_text(step.error_after) + ", by more than " +
                                                  decimal_text(100.0 * kAutomaticAlignmentCost, "%g") + " point"
                                            : std::string("no admissible way to meet it was found on every facade")));
        else if (!step.met)
          out_.warnings.push_back(step.rule + ": no admissible way to meet it was found on every facade; left as it was");
        else if (step.error_after > step.error_before + 1e-3)
          out_.warnings.push_back(step.rule + (step.automatic ? " (automatic)" : "") + " raises the error from " +
                                  percent_text(step.error_before) + " to " + percent_text(step.error_after));
      if (composed.openings != final_rects_) {
        final_rects_ = composed.openings;
        chosen_ = values_of(final_rects_);
        set_openings(final_rects_);
      }
      compose_ = [this, error_of](const std::vector<PanelRectangle>& set) {
        return compose_facades(scene_.domain, constraints_, set, error_of, progress_).openings;
      };
      return stop_reason::kDone;
    });
    out_.timings.push_back({"composition", compose_seconds_});
  }

  // The answer's violations, predictions and errors.
  void final_predictions() {
    out_.constraint_violations = all_violations(scene_.domain, final_rects_, constraints_);
    for (const std::string& v : out_.constraint_violations) out_.warnings.push_back("constraints: " + v);
    out_.predicted = chosen_.value;
    out_.predicted_stderr = chosen_.standard_error;
    out_.linear = linear_prediction(c_, out_.open);
    out_.compensated = compensated_prediction(c_, out_.open);
    out_.error = goal_error(out_.goals, out_.predicted);
    out_.linear_error = goal_error(out_.goals, out_.linear);
    out_.compensated_error = goal_error(out_.goals, out_.compensated);
  }

  // The answer, then the best found with fewer openings, down to one (solver.tradeoffs).
  void tradeoffs() {
    if (!settings_.tradeoffs) return skip_stage(&out_.stages, "trade-offs", tradeoffs_skipped_ = stop_reason::kNoTradeoffs);
    if (out_.openings.empty()) return skip_stage(&out_.stages, "trade-offs", tradeoffs_skipped_ = stop_reason::kNoOpenings);
    const double seconds = run_stage(&out_.stages, "trade-offs", [&] {
      const StageStatus stage(progress_, "solving: fewer openings");
      TradeoffResult answer;
      answer.openings = out_.openings;
      answer.predicted = out_.predicted;
      answer.predicted_stderr = out_.predicted_stderr;
      answer.error = out_.error;
      answer.answer = true;
      out_.tradeoffs.push_back(answer);
      for (const Tradeoff& f : fewer_openings(scene_, records_, objective_, constraints_, final_rects_,
                                              about_ ? &about_->E : nullptr, settings_.verify_paths, compose_,
                                              progress_)) {
        TradeoffResult entry;
        for (const PanelRectangle& r : f.openings) entry.openings.push_back(to_world(scene_.domain, r));
        entry.predicted = f.values.value;
        entry.predicted_stderr = f.values.standard_error;
        entry.error = goal_error(out_.goals, f.values.value);
        entry.cut = f.cut;
        out_.tradeoffs.push_back(std::move(entry));
      }
      return stop_reason::kDone;
    });
    out_.timings.push_back({"trade-offs", seconds});
  }

  // Least glazing: a trade-off that meets every climate goal with less glass than the answer
  // becomes the answer (the list is of designs the solver evaluated; none passing with less
  // glass is shown beside it).
  void least_glazing() {
    if (!climate_) return skip_stage(&out_.stages, "least glazing", stop_reason::kNoClimateGoals);
    if (!scene_.sensors.climate_goals.least_glazing)
      return skip_stage(&out_.stages, "least glazing", stop_reason::kNoLeastGlazing);
    if (tradeoffs_skipped_) return skip_stage(&out_.stages, "least glazing", tradeoffs_skipped_);
    run_stage(&out_.stages, "least glazing", [&] {
      std::vector<ClimateFigure> answer_figures;
      try {
        const AnnualStudy year = records_.annual_study(final_rects_);
        answer_figures = climate_figures(*climate_problem_, year.illuminance.total, year.illuminance.direct);
      } catch (const std::invalid_argument&) {
        // Edges off the grid lines of a thick wall: the records cannot tell; the answer stays.
      }
      const int least = answer_figures.empty()
                            ? -1
                            : least_glazing_entry(scene_, records_, *climate_problem_, answer_figures, settings_.verify,
                                                  settings_.verify_paths, &out_.tradeoffs);
      if (least >= 0 && !out_.tradeoffs[static_cast<size_t>(least)].answer) take_tradeoff(static_cast<size_t>(least));
      return stop_reason::kDone;
    });
  }

  void take_tradeoff(size_t index) {
    for (TradeoffResult& entry : out_.tradeoffs) entry.answer = false;
    TradeoffResult& chosen_entry = out_.tradeoffs[index];
    chosen_entry.answer = true;
    out_.openings = chosen_entry.openings;
    final_rects_.clear();
    for (const OpeningRectangle& o : out_.openings) final_rects_.push_back(o.parameter);
    out_.open = open_elements(scene_.domain, final_rects_);
    out_.predicted = chosen_entry.predicted;
    out_.predicted_stderr = chosen_entry.predicted_stderr;
    out_.linear = linear_prediction(c_, out_.open);
    out_.compensated = compensated_prediction(c_, out_.open);
    out_.error = chosen_entry.error;
    out_.linear_error = goal_error(out_.goals, out_.linear);
    out_.compensated_error = goal_error(out_.goals, out_.compensated);
    out_.warnings.erase(std::remove_if(out_.warnings.begin(), out_.warnings.end(),
                                       [](const std::string& w) { return w.rfind("constraints: ", 0) == 0; }),
                        out_.warnings.end());
    out_.constraint_violations = all_violations(scene_.domain, final_rects_, constraints_);
    for (const std::string& v : out_.constraint_violations) out_.warnings.push_back("constraints: " + v);
    out_.climate.answer_from_tradeoffs = true;
  }

  // The final openings path-traced with real cutters.
  void verification() {
    if (!settings_.verify) return skip_stage(&out_.stages, "verification", stop_reason::kNoVerify);
    const double seconds = run_stage(&out_.stages, "verification", [&] {
      const StageStatus stage(progress_, "solving: checking with real cutters");
      std::vector<OpeningInput> cutters;
      for (const OpeningRectangle& o : out_.openings) cutters.emplace_back(o.parameter);
      const SensorValues v = records_.cut(cutters, settings_.verify_paths, 0);
      out_.verified = true;
      out_.verified_value = v.value;
      out_.verified_stderr = v.standard_error;
      out_.verified_error = goal_error(out_.goals, v.value);
      return stop_reason::kDone;
    });
    out_.timings.push_back({"verification", seconds});
  }

  void climate_figures_stage() {
    if (!climate_) return skip_stage(&out_.stages, "climate figures", stop_reason::kNoClimateGoals);
    const double seconds = run_stage(&out_.stages, "climate figures", [&] {
      report_climate(scene_, records_, *climate_problem_, final_rects_, settings_.verify, settings_.verify_paths, &out_);
      for (TradeoffResult& entry : out_.tradeoffs) {
        if (!entry.answer && !entry.climate.empty()) continue;
        entry.climate = tradeoff_climate(records_, *climate_problem_, entry, out_);
        // The answer's figures are the headline's; least glazing may have marked it cut before.
        if (entry.answer) entry.climate_cut = out_.climate.headline_is_cut();
      }
      return stop_reason::kDone;
    });
    out_.timings.push_back({"climate figures", seconds});
  }

  const Scene& scene_;
  RecordQueries& records_;
  const Contributions& c_;
  Progress* progress_;
  const bool climate_;
  SolverSettings settings_;
  const ElementGrid grid_;
  const GeneticSettings ga_;
  const OpeningConstraints constraints_;
  OpeningConstraints grid_constraints_;
  SolveResult out_;
  LinearObjective objective_;
  std::optional<ClimateProblem> climate_problem_;

  ElementStage element_;        // stages 1 and 2
  SensorValues chosen_;         // the exact values of the answer so far
  SensorValues free_values_;    // of the element answer
  Constrained kept_;            // the openings within the constraints kept so far
  // The search's openings when thick_wall_openings replaced them (kept if, refined, those meet the
  // goals worse).
  std::optional<Constrained> grid_best_;
  std::vector<std::vector<GridRectangle>> search_alternatives_;  // the opening search's other local optima
  std::vector<std::vector<GridRectangle>> search_starts_;        // and its starts
  std::vector<GridRectangle> rects_;          // those openings, on the element grid
  std::vector<PanelRectangle> final_rects_;   // the answer's openings
  std::optional<LinearObjective> about_;      // the exact linear model about rects_
  // Whether chosen_ holds unbiased values of final_rects_ (the records' exact ones, or real cuts;
  // not so for catalogue sizes in thick walls until they are cut).
  bool chosen_exact_ = true;
  std::function<std::vector<PanelRectangle>(const std::vector<PanelRectangle>&)> compose_;
  const char* tradeoffs_skipped_ = nullptr;
  double thick_start_error_ = 0.0;  // relative RMS of the thick-wall edges' start, cut
  double thick_seconds_ = 0.0, compose_seconds_ = 0.0;
};

}  // namespace

std::vector<std::string> solved_constraint_violations(const Scene& scene, const std::vector<PanelRectangle>& openings) {
  return all_violations(scene.domain, openings, measured_constraints(scene));
}

SolveResult solve_openings(const Scene& scene, const Contributions& c, Progress* progress) {
  LocalRecordQueries records(scene, c, progress);
  return solve_openings(scene, records, progress);
}

SolveResult solve_openings(const Scene& scene, RecordQueries& records, Progress* progress) {
  check_contributions_match(scene, records.contributions(), "solve");
  refuse_dark_sky(scene);
  OpeningSolve solve(scene, records, progress);
  return solve.solve();
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
  out.stages.insert(out.stages.begin(), {"contributions", seconds, stop_reason::kDone});
  return out;
}

}  // namespace fenestra
