#pragma once
// What a solve returns (solve_openings, solve/solver.h): the final openings and their predictions,
// the stages' errors and figures, the trade-offs, the warnings, and each stage's seconds and why it
// stopped. io/solve_result.h writes it.
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "solve/climate_design.h"
#include "solve/composition.h"
#include "solve/constraint_costs.h"
#include "solve/genetic.h"
#include "solve/goals.h"
#include "solve/rectangles.h"
#include "solve/solve_stage.h"
#include "trace/record_sink.h"

namespace fenestra {

// One entry of the choice of trade-offs (solve/tradeoffs.h): a set of openings and its prediction.
struct TradeoffResult {
  std::vector<OpeningRectangle> openings;
  Eigen::VectorXd predicted, predicted_stderr;  // per sensor
  GoalError error;
  bool cut = false;     // predicted by real cutters (thick walls), not the path records
  bool answer = false;  // the solver's answer (the one with the most openings, unless least glazing took a
                        // trade-off that meets the climate goals with less glass)
  // With climate goals: each goal's figure for these openings, from the path records (empty when
  // they cannot tell), or from real cutters where least glazing checked them so (climate_cut).
  std::vector<ClimateFigure> climate;
  bool climate_cut = false;
};

// What the exact search over whole openings did (solve/opening_search.h).
struct OpeningSearchSummary {
  bool ran = false;
  std::vector<std::string> starts;  // where it started, in order
  std::string best_start;           // the start its best answer descends from ("" when a restart found it)
  int evaluations = 0, scored = 0, best_found_after = 0, moves = 0, restarts = 0, pair_moves = 0;
  int alternatives_kept = 0;  // other local optima whose edges off the grid beat the answer's
  bool kept = false;  // its answer replaced the openings within the constraints
};

// The choice of openings in thick walls by the error they reach once their edges leave the grid
// (solve/refinable_openings.h), relative RMS errors interpolated off the grid.
struct ThickWallOpeningsSummary {
  bool ran = false;
  int evaluations = 0, moves = 0;
  double interpolated_before = 0.0, interpolated_after = 0.0;
  bool kept = false;      // its openings replaced the search's
  bool reverted = false;  // and, their thick-wall edges searched, met the goals worse: the search's kept
};

// Edges in thick walls placed, and with a catalogue searched, with real cutters
// (solve/thick_wall_edges.h).
struct ThickWallEdgesSummary {
  bool ran = false;
  bool searched = false;  // pairs and single moves searched (catalogue sizes); else only placed
  int cuts = 0, paths_per_cut = 0, moves = 0;
  int rough_cuts = 0;  // of half paths_per_cut, that ranked the first scan's pairs
  bool from_placement = false;  // started where the records' interpolation placed the sides
};

// Openings in thick walls removed or merged by real cutters (solve/thick_wall_merges.h).
struct ThickWallMergesSummary {
  bool ran = false;
  int cuts = 0, rough_cuts = 0;  // of ThickWallEdgesSummary::paths_per_cut paths, and of half as many
  int removed = 0, merged = 0;   // openings removed, pairs merged into one
  int merges_searched = 0;       // merged openings whose edges were searched again
  double traced_share = 1.0;     // of the sensors its cuts could have traced, those they did
};

// Every side of the openings in thick walls moved at once by real cuts (solve/thick_wall_joint_edges.h).
struct ThickWallJointEdgesSummary {
  bool ran = false;
  int steps = 0, sides = 0;
  int cuts = 0, judged_cuts = 0;     // of `paths_per_cut` and of `judge_paths` paths per sensor
  int paths_per_cut = 0, judge_paths = 0;
  bool scanned = false;              // the steps stalled beyond the noise: pairs of edges scanned
  int scan_cuts = 0, scan_rough_cuts = 0, scan_moves = 0;  // scan_moves: kept (0 when not)
  double traced_share = 1.0;  // of the sensors its difference and scan cuts could have traced, those they did
};

struct SolveResult {
  std::vector<uint8_t> open;                 // per element: the final openings' elements
  std::vector<OpeningRectangle> openings;    // the final openings: admissible rectangles
  // Before the architectural refinement: the genetic algorithm's (exactly re-ranked) elements,
  // merged into rectangles, and their exact error; after the paper's refinement alone.
  std::vector<uint8_t> unconstrained_open;
  std::vector<OpeningRectangle> unconstrained_openings;
  GoalError unconstrained_error, refined_error;
  SolverGoals goals;
  // Per sensor, for the chosen state: the exact value from the path records (what the user sees),
  // its standard error, the linear model and the paper's compensated estimate (Eq. 3).
  Eigen::VectorXd predicted, predicted_stderr, linear, compensated;
  GoalError error, linear_error, compensated_error;
  GoalError start_error;                     // the rounded stage-1 state (exact evaluation)
  // The final openings path-traced with real cutters (`evaluate`), when solver.verify is on.
  bool verified = false;
  Eigen::VectorXd verified_value, verified_stderr;
  GoalError verified_error;
  double nnls_relative_rms = 0.0;            // the continuous NNLS solution in the linear model
  int nnls_iterations = 0;
  std::vector<GenerationRecord> history;     // the fine-grid genetic stage
  int generations = 0;
  int edge_moves = 0;  // edges moved off the element grid (refine_edges)
  // Whether the constraints stage also started from a search without the elements no admissible
  // opening can cover (run when the free answer opened some), and whether that start was kept.
  bool second_start = false, second_start_kept = false;
  OpeningSearchSummary opening_search;
  ThickWallOpeningsSummary thick_wall_openings;
  ThickWallEdgesSummary thick_wall_edges;
  ThickWallMergesSummary thick_wall_merges;
  ThickWallJointEdgesSummary thick_wall_joint_edges;
  // When the constraints cost much light (constraints_cost_much), the error without each family
  // of limits, least first (solve/constraint_costs.h); else empty.
  std::vector<ConstraintCost> constraint_costs;
  double fitness = 0.0;                      // the chosen state's fitness with exact predictions
  std::vector<int> coarse_factors;           // coarse grids solved first (e.g. 4, 2)
  struct Timing {
    std::string stage;
    double seconds = 0.0;
  };
  std::vector<Timing> timings;               // seconds by the groups of stages of `timings_s`
  std::vector<SolveStage> stages;            // each stage run or skipped, in order (solve/solve_stage.h)
  // What the user should know before trusting the result (too few paths, a prediction the
  // real-cutter check contradicts), in words.
  std::vector<std::string> warnings;
  // What the final openings break of the constraints (solved_constraint_violations): empty unless
  // no admissible answer was found; each line is also a warning.
  std::vector<std::string> constraint_violations;
  // Facade composition (solve/composition.h): each rule applied and what it cost.
  std::vector<CompositionStep> composition;
  // The answer, then the best found with fewer openings, down to one (solver.tradeoffs).
  std::vector<TradeoffResult> tradeoffs;
  // Climate goals (scene goals.climate): each goal's figures and the year of the final openings.
  ClimateOutcome climate;
  // What the tracer dropped while recording the contributions solved from (record_sink.h).
  DropCounts dropped;
};

}  // namespace fenestra
