#pragma once
// Stage 1 and 2 of the solver for climate goals (docs/solver.md, "Climate goals"): starts from
// NNLS on the annual mean, the genetic algorithm on the hourly model about all elements closed,
// then about its best state (successive linearisation), the exact year from the path records
// choosing among the best states of each run.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "annual/hourly_flip_model.h"
#include "solve/climate_objective.h"
#include "solve/climate_problem.h"
#include "solve/element_grid.h"
#include "solve/genetic.h"
#include "solve/goals.h"
#include "solve/solve_stage.h"
#include "trace/contributions.h"

namespace fenestra {

class Progress;
class RecordQueries;  // solve/record_queries.h
struct Scene;

// The year of a set of open elements, exact from the path records at the problem's sensors and
// hours, and the climate objective's error of it (shape excluded).
struct ClimateYear {
  ClimateTally tally;  // of every shard's sensors
  double error = 0.0;
};
ClimateYear climate_year(RecordQueries& records, const ClimateProblem& problem, const std::vector<uint8_t>& open);

struct ClimateDesign {
  std::vector<uint8_t> open;                     // the answer in elements
  std::vector<std::vector<uint8_t>> candidates;  // the best states seen, exactly ranked, best first
  double error = 0.0;                            // the answer's error (exact year), shape excluded
  std::vector<ClimateFigure> figures;            // the answer's, exact from the path records
  std::vector<ClimateFigure> all_open_figures;   // every element open: what the domain can give
  std::vector<GenerationRecord> history;         // the first genetic run
  int generations = 0;
  int linearisations = 0;                        // rounds about a best state that improved it
  double model_bytes = 0.0;                      // the largest hourly model held, over all its shards
  double seconds_model = 0.0, seconds_search = 0.0;
  // "climate model", "climate search" and "climate linearisation", with why each stopped.
  std::vector<SolveStage> stages;
};

// `seeds`: further starting states (e.g. the linear start of per-sensor goals); `excluded`: elements
// no admissible opening can cover (empty: none), kept closed.
ClimateDesign design_for_climate(RecordQueries& records, const ClimateProblem& problem, const ElementGrid& grid,
                                 const GeneticSettings& ga, const std::vector<std::vector<uint8_t>>& seeds,
                                 const std::vector<uint8_t>& excluded = {}, Progress* progress = nullptr);

struct AnnualStudy;  // annual/annual_study.h

// What a solve on climate goals reports (the solve result's "climate").
struct ClimateOutcome {
  bool active = false;
  std::vector<ClimateFigure> element_figures;   // the element answer, before the constraints
  std::vector<ClimateFigure> all_open_figures;  // every element open
  // The final openings: from the path records (empty when they cannot tell, e.g. edges off the
  // grid lines of a thick wall), and path-traced with real cutters and independent paths (empty
  // unless verified).
  std::vector<ClimateFigure> achieved, verified;
  std::shared_ptr<const AnnualStudy> study, verified_study;
  // The two years disagree beyond the noise (sDA by more than the share of its sensors whose DA is
  // within its noise of the time fraction, and by more than kHeadlineFractionGap; another fraction
  // figure by more than kHeadlineFractionGap; an annual mean by more than 3 combined standard
  // errors): the figures shown are the real cutters', and a warning names the difference.
  bool headline_cutters = false;
  std::vector<uint8_t> apart;  // per goal: its two figures disagree beyond the noise (1), or not (0)
  // Least glazing took a trade-off that meets the goals with less glass than the solver's answer.
  bool answer_from_tradeoffs = false;
  // The figures shown (CLI, result["climate"]["goals"][i]["achieved"], the add-on): the real
  // cutters' when they disagree with the records beyond the noise or the records cannot tell,
  // else the records'.
  bool headline_is_cut() const { return headline_cutters || achieved.empty(); }
  const std::vector<ClimateFigure>& headline() const { return headline_is_cut() ? verified : achieved; }
  const std::shared_ptr<const AnnualStudy>& headline_study() const {
    return headline_cutters || !study ? verified_study : study;
  }
  double glazing_area_m2 = 0.0, domain_area_m2 = 0.0;
  int linearisations = 0;
  double model_bytes = 0.0;
  std::vector<std::string> unmet;  // per goal the final openings miss, in words
};

// Fraction figures (sDA, ASE, UDI, EN 17037) from the records and with real cutters further apart
// than this are a disagreement beyond the noise: two points, the agreement the thick-wall tests
// hold the two to.
constexpr double kHeadlineFractionGap = 0.02;

// The figures of a year of illuminance (sensors x the sky matrix's hours, lux, as AnnualIlluminance
// holds it) for the problem's sensors and hours.
std::vector<ClimateFigure> climate_figures(const ClimateProblem& problem, const Eigen::MatrixXf& total,
                                           const Eigen::MatrixXf& direct);

}  // namespace fenestra
